//! Every AO method's parameters in one place (`[ao]` in scene files, the CLI's flags, the window's
//! panel), and the one function that brings absurd values back into range.

use serde::{Deserialize, Serialize};

pub use super::ao_method::{AoMethod, MethodInfo, NormalUse, SlicePreset, TunedIntensity};
pub use super::ao_resolution::AoResolution;

/// Where the engine's methods take each pixel's normal from (`--normals`, `[ao] normals`);
/// `sao-lesson` always rebuilds it from depth, as the course teaches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NormalSource {
    /// The triangle's own normal from a pass over the geometry (a two-channel target at the AO
    /// size): exact at creases, edges and thin parts, where AO lives.
    Geometric,
    /// Rebuilt from neighbouring depths (the default): no extra pass, and off only in the texels
    /// beside creases and silhouettes. The geometric pass gained `vbao` 0.03–0.15 dB on the bench's
    /// cameras for about a quarter of the lesson chain's cost on llvmpipe at 1920×1080
    /// (docs/bench/vbao/normals-guard-band.md).
    #[default]
    Depth,
}

impl NormalSource {
    pub const ALL: [NormalSource; 2] = [NormalSource::Geometric, NormalSource::Depth];
    pub fn name(self) -> &'static str {
        match self {
            NormalSource::Geometric => "geometric",
            NormalSource::Depth => "depth",
        }
    }
    pub fn from_name(name: &str) -> Option<NormalSource> {
        NormalSource::ALL.into_iter().find(|n| n.name() == name)
    }
}

/// Pixels the engine's AO passes cover beyond each edge of the view (`--guard-band auto|PX`,
/// `[ao] guard_band = "auto"` or a number; 0 = none): the depth, normals and back faces are
/// rendered over a wider field of view at the same pixel size, so that occluders just off screen
/// count. `sao-lesson` never uses one (the course renders the view only).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(try_from = "GuardBandValue", into = "GuardBandValue")]
pub enum GuardBand {
    /// None (the default: the margin costs a third more AO pixels at `auto`, and `gtao` shows
    /// faint row steps on far, grazing floors with it).
    #[default]
    Off,
    /// The radius's projected size at the camera's focus distance, capped (`guard_band_pixels`).
    Auto,
    /// A fixed margin in pixels of the output image (rounded up to a multiple of 4, whole AO texels).
    Pixels(u32),
}

/// How a guard band is written in a scene file: a number or the word `auto`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(untagged)]
enum GuardBandValue {
    Pixels(u32),
    Word(String),
}

impl TryFrom<GuardBandValue> for GuardBand {
    type Error = String;
    fn try_from(v: GuardBandValue) -> Result<GuardBand, String> {
        match v {
            GuardBandValue::Pixels(p) => Ok(GuardBand::from_pixels(p)),
            GuardBandValue::Word(w) => GuardBand::parse(&w),
        }
    }
}

impl From<GuardBand> for GuardBandValue {
    fn from(g: GuardBand) -> GuardBandValue {
        match g {
            GuardBand::Off => GuardBandValue::Pixels(0),
            GuardBand::Auto => GuardBandValue::Word("auto".into()),
            GuardBand::Pixels(p) => GuardBandValue::Pixels(p),
        }
    }
}

/// The largest guard band asked for in pixels, as a fraction of the output's larger side: beyond it
/// the AO passes would cost more than twice the view's pixels for occluders that rarely matter.
pub const GUARD_BAND_MAX_OF_SIDE: f32 = 0.25;

/// The largest `auto` guard band, as a fraction of the output's larger side: 160 pixels at 1920×1080,
/// half again as many pixels for the AO passes. On the bench's training cameras (three scenes, R =
/// 1 m, back faces, geometric normals, 1920×1080 against footprint truths) raising the cap from 1/24
/// to 1/12 gained 0.6–1.0 dB in the room and up to 0.4 on the courtyard with two layers (4×8
/// and 3×6 slices × steps), 0.1–0.5 with one, and lost at most 0.1 on thin things; 1/8 and 1/6 added at most 0.1
/// more (docs/bench/vbao/guard-band-cap.md). Nearby surfaces would ask for more, which the cost
/// does not repay.
pub const GUARD_BAND_AUTO_MAX_OF_SIDE: f32 = 1.0 / 12.0;

impl GuardBand {
    fn from_pixels(p: u32) -> GuardBand {
        if p == 0 {
            GuardBand::Off
        } else {
            GuardBand::Pixels(p)
        }
    }

    /// "auto", or a whole number of pixels (0 = none).
    pub fn parse(s: &str) -> Result<GuardBand, String> {
        let s = s.trim();
        if s == "auto" {
            return Ok(GuardBand::Auto);
        }
        s.parse::<u32>()
            .map(GuardBand::from_pixels)
            .map_err(|_| format!("'{s}' is neither a number of pixels nor 'auto'"))
    }

    pub fn name(self) -> String {
        match self {
            GuardBand::Off => "0".into(),
            GuardBand::Auto => "auto".into(),
            GuardBand::Pixels(p) => p.to_string(),
        }
    }
}

/// How occlusion is applied to the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CompositeMode {
    /// The lesson's blend over the whole lit colour (SRC_ALPHA, ONE_MINUS_SRC_ALPHA).
    #[default]
    Blend,
    /// Blend toward `tint` with visibility^`power`.
    Tinted,
    /// A depth pre-pass, AO, then lighting with AO applied to the ambient term only.
    AmbientOnly,
}

impl CompositeMode {
    pub const ALL: [CompositeMode; 3] = [
        CompositeMode::Blend,
        CompositeMode::Tinted,
        CompositeMode::AmbientOnly,
    ];
    pub fn name(self) -> &'static str {
        match self {
            CompositeMode::Blend => "blend",
            CompositeMode::Tinted => "tinted",
            CompositeMode::AmbientOnly => "ambient-only",
        }
    }
    pub fn from_name(name: &str) -> Option<CompositeMode> {
        CompositeMode::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// The AO parameters every method reads (the course hard-codes radius 1 m, bias 0.012, intensity 5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AoSettings {
    pub enabled: bool,
    /// Which AO method computes the occlusion (`sao-lesson` = the lesson's shaders).
    pub method: AoMethod,
    /// World-space sampling radius (m).
    pub radius: f32,
    /// Distance (m) along the normal below which a sample does not occlude (removes self-occlusion).
    pub bias: f32,
    pub intensity: f32,
    pub samples: u32,
    pub spiral_turns: u32,
    pub blur: bool,
    /// How occlusion reaches the picture.
    pub composite: CompositeMode,
    /// Colour that occluded areas blend toward (`tinted`; black = the lesson's darkening).
    pub tint: [f32; 3],
    /// Visibility is raised to this power before compositing (1 = as computed).
    pub power: f32,
    /// The preset of a method with presets (slices × steps); when set it decides its sample counts instead of `samples`.
    pub quality: Option<SlicePreset>,
    /// How far behind each depth sample `vbao` takes the surface to extend: metres, or the back
    /// faces' depth; unset: a fraction of the radius (`DEFAULT_THICKNESS_OF_RADIUS`).
    pub thickness: Option<Thickness>,
    /// Size the engine's methods run at (`sao-lesson` ignores it: see `effective_resolution`).
    pub resolution: AoResolution,
    /// Where the engine's methods take the normal from (`sao-lesson` ignores it).
    pub normals: NormalSource,
    /// Margin the engine's AO passes cover beyond the view (`sao-lesson` ignores it).
    pub guard_band: GuardBand,
    /// Depth layers `vbao` marches (1 or 2): the visible surface, and the nearest one hidden at least
    /// `LAYER_SEPARATION_OF_RADIUS` × R behind it.
    pub layers: u32,
    /// Whether `vbao`'s taps read a texel of the slab hierarchy that spans the gap to the previous
    /// tap instead of their own texel.
    pub slab_hierarchy: SlabHierarchy,
    /// `rtao`'s rays per pixel and frame (`--rays-per-pixel`).
    pub rays: u32,
    /// Frames averaged, the history reprojected as the camera moves (`--accumulate`; 1 = none).
    pub accumulate: u32,
    /// `rtao`: each pixel's rays as one stratified lattice, the CPU reference's sampling (`reference
    /// --gpu`), instead of a sequence that continues from frame to frame. Not a scene-file key.
    #[serde(skip)]
    pub stratified: bool,
    /// With `stratified`: this frame traces lattice points `first .. first + rays` of a lattice of
    /// `of` points, as `(first, of)` (`reference --gpu` splits a pixel's rays over several passes);
    /// `of` 0: the lattice is this frame's `rays`. Not a scene-file key.
    #[serde(skip)]
    pub lattice_slice: (u32, u32),
    /// Which of the keys a method's recommendation covers the scene file or a flag wrote
    /// (`ao_defaults::apply` fills in the others). Not a scene-file key.
    #[serde(skip)]
    pub written: super::ao_written::WrittenKeys,
}

/// What `vbao` takes to lie behind each depth sample (`[ao] thickness = 0.3` or `"backface"`,
/// `--thickness 0.3|backface`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ThicknessValue", into = "ThicknessValue")]
pub enum Thickness {
    /// The same thickness (m) everywhere.
    Metres(f32),
    /// Each pixel's own: a depth pass of the back faces (front faces culled) gives where the
    /// object ends, and the slab reaches there but is never thinner than the default thickness
    /// (the taps skip the texels between them, and a back face a few centimetres behind one texel
    /// says nothing of the next ones); the default where no back face lies behind (open planes).
    /// With `layers = 2` the hidden surface's slab reaches its own back face (one more pass) but is
    /// never thinner than a quarter of the default, the default where it has none.
    Backface,
}

/// How a thickness is written in a scene file: a number or the word `backface`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(untagged)]
enum ThicknessValue {
    Metres(f32),
    Word(String),
}

impl TryFrom<ThicknessValue> for Thickness {
    type Error = String;
    fn try_from(v: ThicknessValue) -> Result<Thickness, String> {
        match v {
            ThicknessValue::Metres(m) => Ok(Thickness::Metres(m)),
            ThicknessValue::Word(w) => Thickness::parse(&w),
        }
    }
}

impl From<Thickness> for ThicknessValue {
    fn from(t: Thickness) -> ThicknessValue {
        match t {
            Thickness::Metres(m) => ThicknessValue::Metres(m),
            Thickness::Backface => ThicknessValue::Word("backface".into()),
        }
    }
}

impl Thickness {
    /// "backface" or metres.
    pub fn parse(s: &str) -> Result<Thickness, String> {
        let s = s.trim();
        if s == "backface" {
            return Ok(Thickness::Backface);
        }
        s.parse::<f32>()
            .map(Thickness::Metres)
            .map_err(|_| format!("'{s}' is neither a thickness in metres nor 'backface'"))
    }
}

/// Whether `vbao`'s taps read the slab hierarchy (`[ao] slab_hierarchy = "auto" | "on" | "off"`,
/// `ao::slab_hierarchy`): each tap then stands for the gap to the previous one with the nearest slab
/// under a texel about half as wide as that gap, so a thin board between two taps is not skipped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SlabHierarchy {
    /// On with `thickness = "backface"`, off with a constant thickness: on the bench's training
    /// cameras of its three scenes (1920×1080, R = 1 m, every preset) it raised the back-face
    /// slabs everywhere but for two cameras at `ultra` (under 0.1 dB down), and lowered the
    /// constant thickness's thin things at `high` and `ultra` (docs/bench/vbao/slab-hierarchy.md).
    #[default]
    Auto,
    /// Each tap reads its own texel of the linear depth (taps skip what lies between them).
    Off,
    On,
}

impl SlabHierarchy {
    pub const ALL: [SlabHierarchy; 3] =
        [SlabHierarchy::Auto, SlabHierarchy::Off, SlabHierarchy::On];
    pub fn name(self) -> &'static str {
        match self {
            SlabHierarchy::Auto => "auto",
            SlabHierarchy::Off => "off",
            SlabHierarchy::On => "on",
        }
    }
}

/// The second layer's minimum separation from the first, as a fraction of the radius. Small next to
/// the slabs (R/2), so a surface hidden just behind a thin foreground object still counts; large
/// enough that depth quantisation and coplanar surfaces never make the visible surface its own
/// second layer. Mara et al. (2016) found the separation matters little once it is below the
/// scene's typical object thickness.
pub const LAYER_SEPARATION_OF_RADIUS: f32 = 0.1;

/// With back faces, the thinnest slab `vbao` gives the second layer, as a fraction of the set
/// thickness (`LAYER2_MIN_THICKNESS` in `Res/ao/vbao.frag`; docs/bench/vbao/layer2-backfaces.md
/// chose it): the screen-space reference applies the same floor.
pub const LAYER2_MIN_THICKNESS_OF_SET: f32 = 0.25;

/// `vbao`'s default thickness as a fraction of the radius, chosen on the bench's training cameras of
/// its three scenes (docs/bench/vbao-thickness.md): thinner lets light through walls seen edge-on,
/// thicker turns every chair leg and shelf board into a wall reaching the radius. R/2 has the best
/// sum and the best worst case over the three scenes; R was best on the courtyard alone.
pub const DEFAULT_THICKNESS_OF_RADIUS: f32 = 0.5;

impl Default for AoSettings {
    fn default() -> Self {
        AoSettings {
            enabled: true,
            method: AoMethod::SaoLesson,
            radius: 1.0,
            bias: 0.012,
            intensity: 5.0,
            samples: 11,
            spiral_turns: 3,
            blur: true,
            composite: CompositeMode::Blend,
            tint: [0.0; 3],
            power: 1.0,
            quality: None,
            thickness: None,
            resolution: AoResolution::Half,
            normals: NormalSource::Depth,
            guard_band: GuardBand::Off,
            layers: 1,
            slab_hierarchy: SlabHierarchy::Auto,
            rays: 2,
            accumulate: 1,
            stratified: false,
            lattice_slice: (0, 0),
            written: Default::default(),
        }
    }
}

/// Ranges the shaders handle. Radius: 1 mm to 100 m (beyond, every method's disc covers the screen
/// and the clamped screen radius decides anyway); samples: 1 to 256 (the shaders' loop bound);
/// power: 0.05 to 20 (outside, visibility rounds to all-open or all-closed in 8 bits).
pub const RADIUS_RANGE: (f32, f32) = (1e-3, 100.0);
pub const BIAS_RANGE: (f32, f32) = (0.0, 10.0);
pub const INTENSITY_RANGE: (f32, f32) = (0.0, 1000.0);
pub const POWER_RANGE: (f32, f32) = (0.05, 20.0);
pub const SAMPLES_RANGE: (u32, u32) = (1, 256);
pub const SPIRAL_TURNS_RANGE: (u32, u32) = (1, 64);
/// Depth layers: the visible one, and one hidden behind it.
pub const LAYERS_RANGE: (u32, u32) = (1, 2);
/// `rtao`: rays per pixel and frame (the shader's loop bound), frames accumulated.
pub const RAYS_RANGE: (u32, u32) = (1, 1024);
pub const ACCUMULATE_RANGE: (u32, u32) = (1, 4096);
/// Thickness: 0.1 mm (a sheet) to 1 km (a heightfield, as GTAO assumes).
pub const THICKNESS_RANGE: (f32, f32) = (1e-4, 1000.0);

impl AoSettings {
    /// The resolution the selected method runs at: the lesson's SAO stays at half size as taught.
    pub fn effective_resolution(&self) -> AoResolution {
        if self.method.info().engine_chain {
            self.resolution
        } else {
            AoResolution::Half
        }
    }

    /// The thickness `vbao` uses (m): the set one, else the default fraction of the radius (also
    /// where back faces are asked for but none lies behind a pixel).
    pub fn thickness_metres(&self) -> f32 {
        match self.thickness {
            Some(Thickness::Metres(m)) => m,
            _ => DEFAULT_THICKNESS_OF_RADIUS * self.radius,
        }
    }

    /// Whether a frame needs the back-face depth pass: a method that reads it (`vbao`) with
    /// `thickness = "backface"`.
    pub fn uses_back_faces(&self) -> bool {
        self.method.info().back_faces && self.thickness == Some(Thickness::Backface)
    }

    /// Whether `vbao`'s taps read the slab hierarchy (`SlabHierarchy::Auto` decided).
    pub fn uses_slab_hierarchy(&self) -> bool {
        match self.slab_hierarchy {
            SlabHierarchy::On => true,
            SlabHierarchy::Off => false,
            SlabHierarchy::Auto => self.thickness == Some(Thickness::Backface),
        }
    }

    /// Whether a frame needs the second depth layer: a method that reads it (`vbao`) with
    /// `layers = 2`.
    pub fn uses_second_layer(&self) -> bool {
        self.method.info().second_layer && self.layers >= 2
    }

    /// Whether a frame needs the second layer's back faces: both the back faces and the second
    /// layer, so the hidden surface's slab reaches its own back face as the visible one's does.
    pub fn uses_second_layer_back_faces(&self) -> bool {
        self.uses_back_faces() && self.uses_second_layer()
    }

    /// How far behind the visible surface the second layer begins (m).
    pub fn layer_separation_metres(&self) -> f32 {
        LAYER_SEPARATION_OF_RADIUS * self.radius
    }

    /// Whether a frame draws geometry of its own for the AO chain besides the main pass (the back
    /// faces, the second layer, the surface normals): the engine then draws all of it, its front
    /// depth included, at the AO size.
    pub fn uses_surface_passes(&self) -> bool {
        self.uses_back_faces() || self.uses_second_layer() || self.uses_surface_normals()
    }

    /// Whether a frame needs the surface-normal pass: as the method's row says
    /// (`MethodInfo::normals`), with `normals = "geometric"` where the method lets it choose.
    pub fn uses_surface_normals(&self) -> bool {
        match self.method.info().normals {
            NormalUse::None => false,
            NormalUse::Chosen => self.normals == NormalSource::Geometric,
            NormalUse::Always => true,
        }
    }

    /// Clamps absurd values into a range the shaders handle, and says what was changed (naming the
    /// `[ao]` key).
    pub fn sanitized(mut self) -> (AoSettings, Vec<String>) {
        let mut notes = Vec::new();
        let mut fix = |name: &str, v: &mut f32, (lo, hi): (f32, f32)| {
            let old = *v;
            *v = if v.is_finite() {
                v.clamp(lo, hi)
            } else {
                lo.max(hi.min(1.0))
            };
            if *v != old {
                notes.push(format!("ao.{name} {old} is out of range, using {}", *v));
            }
        };
        fix("radius", &mut self.radius, RADIUS_RANGE);
        fix("bias", &mut self.bias, BIAS_RANGE);
        fix("intensity", &mut self.intensity, INTENSITY_RANGE);
        fix("power", &mut self.power, POWER_RANGE);
        if let Some(Thickness::Metres(t)) = &mut self.thickness {
            fix("thickness", t, THICKNESS_RANGE);
        }
        for c in &mut self.tint {
            let old = *c;
            *c = if c.is_finite() {
                c.clamp(0.0, 1.0)
            } else {
                0.0
            };
            if *c != old {
                notes.push(format!(
                    "ao.tint channel {old} is out of range, using {}",
                    *c
                ));
            }
        }
        let mut fix_count = |name: &str, v: &mut u32, (lo, hi): (u32, u32)| {
            if !(lo..=hi).contains(v) {
                notes.push(format!(
                    "ao.{name} {v} is out of range, using {}",
                    (*v).clamp(lo, hi)
                ));
                *v = (*v).clamp(lo, hi);
            }
        };
        fix_count("samples", &mut self.samples, SAMPLES_RANGE);
        fix_count("spiral_turns", &mut self.spiral_turns, SPIRAL_TURNS_RANGE);
        fix_count("layers", &mut self.layers, LAYERS_RANGE);
        fix_count("rays", &mut self.rays, RAYS_RANGE);
        fix_count("accumulate", &mut self.accumulate, ACCUMULATE_RANGE);
        (self, notes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_second_layers_least_slab_is_the_shaders() {
        // The screen-space reference applies the floor `vbao`'s shader applies: one value.
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/Res/ao/vbao.frag");
        let text = std::fs::read_to_string(path).expect("Res/ao/vbao.frag");
        let line = text
            .lines()
            .find(|l| l.starts_with("const float LAYER2_MIN_THICKNESS ="))
            .expect("vbao.frag declares LAYER2_MIN_THICKNESS");
        let value: f32 = line
            .trim_end_matches(';')
            .rsplit('=')
            .next()
            .and_then(|v| v.trim().parse().ok())
            .expect("a number");
        assert_eq!(value, LAYER2_MIN_THICKNESS_OF_SET);
    }

    #[test]
    fn names_round_trip() {
        for m in AoMethod::ALL {
            assert_eq!(AoMethod::from_name(m.name()), Some(m));
        }
        for q in SlicePreset::ALL {
            assert_eq!(SlicePreset::from_name(q.name()), Some(q));
        }
        for c in CompositeMode::ALL {
            assert_eq!(CompositeMode::from_name(c.name()), Some(c));
        }
        assert_eq!(Thickness::parse("backface"), Ok(Thickness::Backface));
        assert_eq!(Thickness::parse(" 0.25"), Ok(Thickness::Metres(0.25)));
        assert!(Thickness::parse("thick").is_err());
        for r in AoResolution::ALL {
            assert_eq!(AoResolution::from_name(r.name()), Some(r));
        }
        for n in NormalSource::ALL {
            assert_eq!(NormalSource::from_name(n.name()), Some(n));
        }
        for g in [GuardBand::Off, GuardBand::Auto, GuardBand::Pixels(80)] {
            assert_eq!(GuardBand::parse(&g.name()), Ok(g));
        }
        assert!(GuardBand::parse("-3").is_err() && GuardBand::parse("wide").is_err());
        let toml_ao = |text: &str| toml::from_str::<AoSettings>(text).map(|s| s.guard_band);
        assert_eq!(toml_ao("guard_band = \"auto\""), Ok(GuardBand::Auto));
        assert_eq!(toml_ao("guard_band = 64"), Ok(GuardBand::Pixels(64)));
        assert_eq!(toml_ao("guard_band = 0"), Ok(GuardBand::Off));
        assert!(toml_ao("guard_band = \"wide\"").is_err());
        assert_eq!(AoMethod::from_name("ssao"), None);
    }

    #[test]
    fn sanitized_clamps_and_names_the_key() {
        let s = AoSettings {
            radius: f32::NAN,
            samples: 0,
            power: 1e9,
            ..Default::default()
        };
        let (s, notes) = s.sanitized();
        assert!(s.radius.is_finite() && s.radius > 0.0);
        assert_eq!(s.samples, 1);
        assert_eq!(s.power, 20.0);
        assert!(
            notes.iter().any(|n| n.starts_with("ao.radius")),
            "{notes:?}"
        );
        assert!(
            notes.iter().any(|n| n.starts_with("ao.samples")),
            "{notes:?}"
        );
        let (d, none) = AoSettings::default().sanitized();
        assert_eq!(d, AoSettings::default());
        assert!(none.is_empty());
    }
}
