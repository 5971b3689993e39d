//! Each AO method's recommended configuration: what runs when neither the scene's `[ao]` table
//! nor a flag sets a key. One table, each value with its reason; chosen with `opengl3d tune
//! --budget 1.0` on the bench's training cameras (docs/bench/defaults.md), so that a user who
//! types `--method NAME` gets the most accurate configuration that costs no more than the
//! lesson's chain.
//!
//! The keys covered are the ones that change what a method knows of the scene (where normals come
//! from, how many depth layers, how thick a surface is, what lies beyond the view), the size it
//! runs at, the preset of the methods that have one and the rays per pixel of the one that traces. The lesson's SAO keeps the struct's own
//! defaults: it is the course's, and ignores these keys anyway.

use super::ao_settings::{
    AoMethod, AoResolution, AoSettings, GuardBand, NormalSource, SlicePreset, Thickness,
};
pub use super::ao_written::WrittenKeys;

/// A method's recommended values of the keys in [`WrittenKeys`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Recommended {
    pub quality: Option<SlicePreset>,
    pub resolution: AoResolution,
    pub normals: NormalSource,
    pub guard_band: GuardBand,
    pub layers: u32,
    pub thickness: Option<Thickness>,
    /// Rays per pixel and frame, for a method that traces rays (`None`: the key means nothing to it
    /// and is left as it is).
    pub rays: Option<u32>,
}

/// The struct's own defaults (`AoSettings::default()`): the lesson's SAO as the course teaches it,
/// and what a method file recommends for the keys it leaves out.
pub const PLAIN: Recommended = Recommended {
    quality: None,
    resolution: AoResolution::Half,
    normals: NormalSource::Depth,
    guard_band: GuardBand::Off,
    layers: 1,
    thickness: None,
    rays: None,
};

/// The recommended configuration of `method` (docs/bench/defaults.md has the runs behind each).
pub fn recommended(method: AoMethod) -> Recommended {
    match method {
        AoMethod::SaoLesson => PLAIN,
        AoMethod::Rtao => Recommended {
            // The only size within the lesson's cost at the default two rays per pixel: at half
            // size a frame cost about the lesson's chain on the bench's rooms and twice it on a
            // lone model. Its other keys change nothing it traces.
            resolution: AoResolution::Quarter,
            // The most rays within the lesson's cost on every training camera (two lone models
            // among them); eight went over it on half of them. Accumulated over frames, the same
            // count reaches 32 dB standing still on the bench scenes.
            rays: Some(4),
            ..PLAIN
        },
        AoMethod::Vbao => Recommended {
            // 1 slice × 32 steps: the most accurate preset on every training camera, within the
            // lesson's cost on the three bench scenes and on two lone models.
            quality: Some(SlicePreset::Ultra),
            // A sixteenth of the pixels pays for everything below; at 1920×1080 a texel still
            // covers little of what AO varies over.
            resolution: AoResolution::Quarter,
            // The triangle's own normal: exact at creases and thin parts, where AO lives.
            normals: NormalSource::Geometric,
            // Occluders just off screen count: the largest single gain on the room's walls.
            guard_band: GuardBand::Auto,
            // The surface hidden behind a thin foreground object still occludes.
            layers: 2,
            // Each pixel's own thickness, from the back faces: chair legs stay thin, walls stay walls.
            thickness: Some(Thickness::Backface),
            rays: None,
        },
        // The methods below: each key the quick protocol's search chose on at least two of the
        // three scenes (docs/bench/defaults.md); their sample counts stay the scene's `samples`.
        AoMethod::Sao | AoMethod::Hemisphere => Recommended {
            // Chosen on all three scenes: the rebuilt normal bends at every crease.
            normals: NormalSource::Geometric,
            // Chosen on two: walls just off screen darken the room's corners.
            guard_band: GuardBand::Auto,
            ..PLAIN
        },
        AoMethod::Crytek | AoMethod::Hbao | AoMethod::AngleBased => Recommended {
            // Chosen on two scenes (Crytek reads no normal; the others' normal choice split).
            guard_band: GuardBand::Auto,
            ..PLAIN
        },
        AoMethod::Gtao => Recommended {
            // 3 slices × 6 steps: the quick search chose `ultra` on all three scenes, but at
            // 1920×1080 `ultra` cost 1.07–1.14× the lesson on two of them; `high` 0.84–0.95×.
            quality: Some(SlicePreset::High),
            // Chosen on two scenes each.
            normals: NormalSource::Geometric,
            guard_band: GuardBand::Auto,
            ..PLAIN
        },
    }
}

/// Sets every key of `s` that was not written to `s.method`'s recommended value (so switching
/// the method also switches the unwritten keys).
pub fn apply(s: &mut AoSettings) {
    apply_from(s, &recommended(s.method));
}

/// `apply` with the recommendation `r` (a method file's, for one).
pub fn apply_from(s: &mut AoSettings, r: &Recommended) {
    let w = s.written;
    if !w.quality {
        s.quality = r.quality;
    }
    if !w.resolution {
        s.resolution = r.resolution;
    }
    if !w.normals {
        s.normals = r.normals;
    }
    if !w.guard_band {
        s.guard_band = r.guard_band;
    }
    if !w.layers {
        s.layers = r.layers;
    }
    if !w.thickness {
        s.thickness = r.thickness;
    }
    if let (false, Some(rays)) = (w.rays, r.rays) {
        s.rays = rays;
    }
}

/// One key of the configuration a frame runs with, and where its value came from.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ChosenKey {
    pub key: &'static str,
    pub value: String,
    /// True when the value is the method's recommendation, not written by the scene file or a
    /// flag (nor changed since, in the window's panel).
    pub recommended: bool,
}

/// The configuration keys `s` runs with, for `render --stats` and the window's panel.
pub fn chosen(s: &AoSettings) -> Vec<ChosenKey> {
    chosen_from(s, &recommended(s.method))
}

/// `chosen`, against the recommendation `r` (a method file's, for one).
pub fn chosen_from(s: &AoSettings, r: &Recommended) -> Vec<ChosenKey> {
    let w = s.written;
    let thickness = match s.thickness {
        None => format!("{}", s.thickness_metres()),
        Some(Thickness::Metres(m)) => format!("{m}"),
        Some(Thickness::Backface) => "backface".into(),
    };
    let quality = s.quality.map_or_else(
        || format!("samples {}", s.samples),
        |q| q.name().to_string(),
    );
    let key = |key, value: String, written: bool, same: bool| ChosenKey {
        key,
        value,
        recommended: !written && same,
    };
    let mut keys = vec![
        key("quality", quality, w.quality, s.quality == r.quality),
        key(
            "resolution",
            s.resolution.name().into(),
            w.resolution,
            s.resolution == r.resolution,
        ),
        key(
            "normals",
            s.normals.name().into(),
            w.normals,
            s.normals == r.normals,
        ),
        key(
            "guard_band",
            s.guard_band.name(),
            w.guard_band,
            s.guard_band == r.guard_band,
        ),
        key(
            "layers",
            s.layers.to_string(),
            w.layers,
            s.layers == r.layers,
        ),
        key(
            "thickness",
            thickness,
            w.thickness,
            s.thickness == r.thickness,
        ),
    ];
    // Only a method that traces rays recommends a count.
    if let Some(rays) = r.rays {
        keys.push(key("rays", s.rays.to_string(), w.rays, s.rays == rays));
    }
    keys
}

/// `chosen` on one line: `quality = ultra, resolution = quarter, …`, a `*` after each value the
/// scene file or a flag set.
pub fn chosen_line(s: &AoSettings) -> String {
    chosen_line_from(s, &recommended(s.method))
}

/// `chosen_line`, against the recommendation `r`.
pub fn chosen_line_from(s: &AoSettings, r: &Recommended) -> String {
    chosen_from(s, r)
        .iter()
        .map(|c| {
            let mark = if c.recommended { "" } else { "*" };
            format!("{} = {}{mark}", c.key, c.value)
        })
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lessons_sao_keeps_the_structs_defaults() {
        let mut s = AoSettings::default();
        apply(&mut s);
        assert_eq!(s, AoSettings::default());
    }

    #[test]
    fn written_keys_are_kept_and_the_others_follow_the_method() {
        let mut s = AoSettings {
            method: AoMethod::Vbao,
            normals: NormalSource::Depth,
            written: WrittenKeys {
                normals: true,
                ..Default::default()
            },
            ..Default::default()
        };
        apply(&mut s);
        let r = recommended(AoMethod::Vbao);
        assert_eq!(s.normals, NormalSource::Depth);
        assert_eq!((s.layers, s.thickness), (r.layers, r.thickness));
        // Back to the lesson: the unwritten keys return to its values.
        s.method = AoMethod::SaoLesson;
        apply(&mut s);
        assert_eq!((s.layers, s.thickness, s.quality), (1, None, None));
    }

    #[test]
    fn rtao_recommends_its_rays_unless_they_were_written() {
        let mut s = AoSettings {
            method: AoMethod::Rtao,
            ..Default::default()
        };
        apply(&mut s);
        assert_eq!(Some(s.rays), recommended(AoMethod::Rtao).rays);
        assert_ne!(s.rays, AoSettings::default().rays);
        assert!(chosen_line(&s).contains(&format!("rays = {}", s.rays)));
        let mut written = AoSettings {
            method: AoMethod::Rtao,
            rays: 7,
            written: WrittenKeys {
                rays: true,
                ..Default::default()
            },
            ..Default::default()
        };
        apply(&mut written);
        assert_eq!(written.rays, 7);
        assert!(chosen_line(&written).contains("rays = 7*"));
        // A method that does not trace lists no rays.
        s.method = AoMethod::Vbao;
        apply(&mut s);
        assert!(!chosen_line(&s).contains("rays"));
    }
}
