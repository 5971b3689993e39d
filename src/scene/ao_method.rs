//! The AO methods and, for each, one row saying what it reads (`MethodInfo`): the settings, the
//! panel, `tune`, the bench and the engine ask the row instead of naming methods. The rows of the
//! layer above (`ao::method::row`: how a method is built, its counts and its shader interface)
//! complete them.

use serde::{Deserialize, Serialize};

/// Where a method takes each pixel's normal from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalUse {
    /// It reads no normal (the lesson's SAO rebuilds its own in `sao.frag`; Crytek's sphere needs none).
    None,
    /// As `[ao] normals` says: rebuilt from depth, or the surface-normal pass.
    Chosen,
    /// Always the surface-normal pass (`rtao`'s rays leave the triangle's own plane).
    Always,
}

/// The intensity values `tune` searches for a method, by what intensity means to its shader.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TunedIntensity {
    /// The lesson's scale: occlusion `min(1, sum · intensity / n)`.
    Scale,
    /// The exponent of visibility, `5 / intensity` (5 the identity).
    Exponent,
}

/// What one method reads and how the tools treat it: one row per method, in `AoMethod::info`.
#[derive(Clone, Copy, Debug)]
pub struct MethodInfo {
    /// Its name on the command line and in scene files (`--method`, `[ao] method`); also the name of
    /// its pages, `lessons/methods/NAME.md` and `lessons/ja/methods/NAME.md`.
    pub name: &'static str,
    /// Its Rust file, `src/ao/method/MODULE.rs`.
    pub module: &'static str,
    /// Its occlusion shader under `Res/`.
    pub shader: &'static str,
    /// Runs on the engine's AO chain (AO size, guard band, surface passes, bilateral up-sampling);
    /// `false`: the lesson's chain as taught (half size, the view only).
    pub engine_chain: bool,
    /// Its occluders come from the depth buffer (`false`: from the scene's triangles).
    pub reads_depth_occluders: bool,
    pub normals: NormalUse,
    /// `bias` (m) lifts its samples off the surface.
    pub bias: bool,
    /// `spiral_turns` shapes its taps.
    pub spiral_turns: bool,
    /// A thickness behind each depth sample (`thickness` in metres).
    pub thickness: bool,
    /// The back-face depth pass (`thickness = "backface"`).
    pub back_faces: bool,
    /// The second depth layer (`layers = 2`).
    pub second_layer: bool,
    /// The slab hierarchy (`slab_hierarchy`).
    pub slab_hierarchy: bool,
    /// Its quality presets as slices × steps per side; `None`: `samples` alone sets its taps.
    pub presets: Option<fn(SlicePreset) -> (u32, u32)>,
    /// The presets the bench runs besides its quick grid of samples.
    pub bench_presets: &'static [SlicePreset],
    /// Rays per pixel (`rays`) and frames accumulated (`accumulate`) instead of samples.
    pub rays: bool,
    /// The intensities `tune` searches; `None`: left at the scene's.
    pub tuned_intensity: Option<TunedIntensity>,
    /// The lesson's linear blend leaves the sky out (the pixels at the far plane keep their colour),
    /// where the method's occlusion is not up-sampled as it blends.
    pub blend_leaves_sky: bool,
    /// The σ (AO texels) of its packed blur's Gaussian, given the rays per pixel and frame (which
    /// only a method that traces rays reads); `None`: the blur's own table (σ about 3).
    pub blur_sigma: Option<fn(u32) -> f32>,
    /// Its occlusion pass and its blur in the frame's statistics (`render --stats`, the panel).
    pub pass_label: &'static str,
    pub blur_label: &'static str,
    /// Its composite over the lit picture (the linear blend, when not up-sampled as it blends).
    pub composite_label: &'static str,
}

/// A row with every input off, for the rows below to start from.
const PLAIN: MethodInfo = MethodInfo {
    name: "",
    module: "",
    shader: "",
    engine_chain: true,
    reads_depth_occluders: true,
    normals: NormalUse::Chosen,
    bias: false,
    spiral_turns: false,
    thickness: false,
    back_faces: false,
    second_layer: false,
    slab_hierarchy: false,
    presets: None,
    bench_presets: &[],
    rays: false,
    tuned_intensity: None,
    blend_leaves_sky: false,
    blur_sigma: None,
    pass_label: "",
    blur_label: "",
    composite_label: "",
};

const SAO_LESSON: MethodInfo = MethodInfo {
    name: "sao-lesson",
    pass_label: "sao",
    blur_label: "sao blur",
    composite_label: "sao composite",
    module: "sao_lesson",
    shader: "sao.frag",
    engine_chain: false,
    normals: NormalUse::None,
    bias: true,
    spiral_turns: true,
    tuned_intensity: Some(TunedIntensity::Scale),
    ..PLAIN
};
const SAO: MethodInfo = MethodInfo {
    name: "sao",
    pass_label: "sao",
    blur_label: "sao packed blur",
    composite_label: "sao composite",
    module: "sao",
    shader: "ao/sao.frag",
    blend_leaves_sky: true,
    bias: true,
    spiral_turns: true,
    ..PLAIN
};
const CRYTEK: MethodInfo = MethodInfo {
    name: "crytek",
    pass_label: "crytek",
    blur_label: "crytek packed blur",
    composite_label: "crytek composite",
    module: "crytek",
    shader: "ao/crytek.frag",
    normals: NormalUse::None,
    bias: true,
    ..PLAIN
};
const HEMISPHERE: MethodInfo = MethodInfo {
    name: "hemisphere",
    pass_label: "hemisphere",
    blur_label: "hemisphere packed blur",
    composite_label: "hemisphere composite",
    module: "hemisphere",
    shader: "ao/hemisphere.frag",
    bias: true,
    ..PLAIN
};
const HBAO: MethodInfo = MethodInfo {
    name: "hbao",
    pass_label: "hbao",
    blur_label: "hbao packed blur",
    composite_label: "hbao composite",
    module: "hbao",
    shader: "ao/hbao.frag",
    ..PLAIN
};
const ANGLE_BASED: MethodInfo = MethodInfo {
    name: "angle-based",
    pass_label: "angle-based",
    blur_label: "angle-based packed blur",
    composite_label: "angle-based composite",
    module: "angle_based",
    shader: "ao/angle_based.frag",
    ..PLAIN
};
const GTAO: MethodInfo = MethodInfo {
    name: "gtao",
    pass_label: "gtao",
    blur_label: "gtao packed blur",
    composite_label: "gtao composite",
    module: "gtao",
    shader: "ao/gtao.frag",
    presets: Some(SlicePreset::gtao_slices_steps),
    // "high" is the accurate end the report compares.
    bench_presets: &[SlicePreset::High, SlicePreset::Ultra],
    ..PLAIN
};
const VBAO: MethodInfo = MethodInfo {
    name: "vbao",
    pass_label: "vbao",
    blur_label: "vbao packed blur",
    composite_label: "vbao composite",
    module: "vbao",
    shader: "ao/vbao.frag",
    bias: true,
    thickness: true,
    back_faces: true,
    second_layer: true,
    slab_hierarchy: true,
    presets: Some(SlicePreset::vbao_slices_steps),
    // Every preset: the report shows the cheapest one that reaches a given accuracy.
    bench_presets: &SlicePreset::ALL,
    // Its recommended configuration leaves little noise per texel, and a quarter-size texel is
    // wide: the shared blur smoothed away more than the noise (docs/bench/blur.md).
    blur_sigma: Some(|_| 1.0),
    ..PLAIN
};
const RTAO: MethodInfo = MethodInfo {
    name: "rtao",
    pass_label: "rtao",
    blur_label: "rtao packed blur",
    composite_label: "rtao composite",
    module: "rtao",
    shader: "ao/rtao.frag",
    reads_depth_occluders: false,
    normals: NormalUse::Always,
    rays: true,
    tuned_intensity: Some(TunedIntensity::Exponent),
    // The noise of n rays falls as 1/√n, and so does the width that removes it: 3 texels at one
    // ray (the shared blur's), 1.5 at four; each the best of those tried at 1, 2, 4 and 11 rays
    // (docs/bench/blur.md).
    blur_sigma: Some(|rays| 3.0 / (rays.max(1) as f32).sqrt()),
    ..PLAIN
};

/// Declares the methods once: the enum, `ALL` in this order, and `info` (a new variant names its
/// row here or nothing compiles).
macro_rules! ao_methods {
    ($($(#[$attr:meta])* $variant:ident => $row:ident,)*) => {
        /// The AO methods, named as on the command line (`--method`) and in scene files.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
        #[serde(rename_all = "kebab-case")]
        pub enum AoMethod {
            $($(#[$attr])* $variant,)*
        }

        impl AoMethod {
            pub const ALL: [AoMethod; [$(AoMethod::$variant),*].len()] = [$(AoMethod::$variant),*];

            /// What the method reads, and where its files are.
            pub fn info(self) -> &'static MethodInfo {
                match self {
                    $(AoMethod::$variant => &$row,)*
                }
            }
        }
    };
}

ao_methods! {
    /// The lesson's SAO as taught (errata fixed, one 9×9 bilateral blur).
    #[default]
    SaoLesson => SAO_LESSON,
    /// The engine's SAO: round disc in view space, packed blur, small discs and sky skipped.
    Sao => SAO,
    /// Sphere sampling with depth comparison (Crytek).
    Crytek => CRYTEK,
    /// Normal-oriented hemisphere kernel with range check.
    Hemisphere => HEMISPHERE,
    /// Horizon-based AO (directions × steps).
    Hbao => HBAO,
    /// UE4-style paired samples.
    AngleBased => ANGLE_BASED,
    /// Ground-truth-based AO (analytic cosine-weighted horizon integral).
    Gtao => GTAO,
    /// Visibility bitmask: occluders of finite thickness, sectors of equal cosine weight.
    Vbao => VBAO,
    /// Ray-traced AO: the scene's triangles in a BVH, a few cosine-weighted rays per pixel.
    Rtao => RTAO,
}

impl AoMethod {
    pub fn name(self) -> &'static str {
        self.info().name
    }

    pub fn from_name(name: &str) -> Option<AoMethod> {
        AoMethod::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// Quality presets (`--quality`, `[ao] quality`) of the methods that march slices: slices × steps
/// per side, each method's own (its row's `MethodInfo::presets`: `gtao_slices_steps`,
/// `vbao_slices_steps`). Every preset reads level 0 of the AO-size linear-depth chain (a horizon
/// search needs exact depths: the min mip chain would raise horizons); the sample count is what
/// costs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SlicePreset {
    /// `gtao` 1 slice × 4 steps (8 taps): the blur hides the 4×4 rotation tile; `vbao` the same.
    Low,
    /// `gtao` 2 slices × 4 steps (16 taps): the bench's default setting; `vbao` 1 × 8.
    Medium,
    /// `gtao` 3 slices × 6 steps (36 taps); `vbao` 1 × 16.
    High,
    /// `gtao` 4 slices × 8 steps (64 taps); `vbao` 1 × 32.
    Ultra,
}

impl SlicePreset {
    pub const ALL: [SlicePreset; 4] = [
        SlicePreset::Low,
        SlicePreset::Medium,
        SlicePreset::High,
        SlicePreset::Ultra,
    ];
    /// `gtao`'s slices × steps per side.
    pub fn gtao_slices_steps(self) -> (u32, u32) {
        match self {
            SlicePreset::Low => (1, 4),
            SlicePreset::Medium => (2, 4),
            SlicePreset::High => (3, 6),
            SlicePreset::Ultra => (4, 8),
        }
    }
    /// `vbao`'s slices × steps per side: one slice, the steps doubling from preset to preset (8,
    /// 16, 32 and 64 taps). At equal taps, steps beat slices: the blur already averages the slice
    /// directions of neighbouring pixels, while a longer march leaves smaller gaps for thin slabs to
    /// fall into. Summed over the bench's six training cameras at 1920×1080 against footprint truths
    /// (R = 1 m; scene defaults / back faces with geometric normals and guard band / the same with two
    /// layers), 64 taps: 4×8 128.99 / 150.77 / 167.52 dB, 2×16 132.09 / 161.55 / 183.70, 1×32
    /// 132.31 / 165.03 / 184.66; 16 taps: 2×4 117.94 / 136.07 / 146.22, 1×8 128.18 / 149.09 / 163.64
    /// (docs/bench/vbao/steps-or-slices.md).
    pub fn vbao_slices_steps(self) -> (u32, u32) {
        match self {
            SlicePreset::Low => (1, 4),
            SlicePreset::Medium => (1, 8),
            SlicePreset::High => (1, 16),
            SlicePreset::Ultra => (1, 32),
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            SlicePreset::Low => "low",
            SlicePreset::Medium => "medium",
            SlicePreset::High => "high",
            SlicePreset::Ultra => "ultra",
        }
    }
    pub fn from_name(name: &str) -> Option<SlicePreset> {
        SlicePreset::ALL.into_iter().find(|q| q.name() == name)
    }
}
