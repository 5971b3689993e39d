//! What a method file's method reads (`reads`), and its `[recommended]` table: the configuration
//! its method runs with where neither the scene's `[ao]` table nor a flag sets a key, as each engine method has its own
//! (`ao_defaults::recommended`). Keys and values are the scene file's; a key left out keeps the
//! struct's own default (`ao_defaults::PLAIN`). There is no `quality`: a method file has no presets.

use super::ao_defaults::{Recommended, PLAIN};
use super::ao_settings::{AoResolution, GuardBand, NormalSource, Thickness, LAYERS_RANGE};
use rust_i18n::t;
use serde::Deserialize;

/// What the engine draws for a method, beyond the linear-depth chain every method gets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MethodReads {
    /// The surface-normal pass (`texNormal`, `SurfaceNormal` in `common.glsl`) when the settings
    /// ask for geometric normals.
    pub normals: bool,
    /// Back-face depth (`aoBackFaces`, binding 1) when the settings ask for it.
    pub back_faces: bool,
    /// A second depth layer (`aoLayers`) when the settings ask for it.
    pub second_layer: bool,
    /// The settings' thickness (`aoThickness`).
    pub thickness: bool,
}

#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRecommended {
    resolution: Option<AoResolution>,
    normals: Option<NormalSource>,
    guard_band: Option<GuardBand>,
    layers: Option<u32>,
    thickness: Option<Thickness>,
}

/// The recommendation `raw` writes, checked against what the method reads: a value that asks the
/// engine for an input the method does not read would be dropped without a word, so it is an
/// error naming the key (the caller adds the file, line and column).
pub(super) fn check(
    raw: &RawRecommended,
    reads: &MethodReads,
) -> Result<Recommended, (&'static str, String)> {
    let unread = |key: &'static str, input: &str| {
        let why = t!("method_file.recommends_unread", key = key, input = input).into_owned();
        Err((key, why))
    };
    let mut r = PLAIN;
    if let Some(resolution) = raw.resolution {
        r.resolution = resolution;
    }
    if let Some(normals) = raw.normals {
        if normals == NormalSource::Geometric && !reads.normals {
            return unread("normals", "normals");
        }
        r.normals = normals;
    }
    if let Some(guard_band) = raw.guard_band {
        r.guard_band = guard_band;
    }
    if let Some(layers) = raw.layers {
        if !(LAYERS_RANGE.0..=LAYERS_RANGE.1).contains(&layers) {
            let why = t!(
                "method_file.layers_range",
                min = LAYERS_RANGE.0,
                max = LAYERS_RANGE.1
            );
            return Err(("layers", why.into_owned()));
        }
        if layers > 1 && !reads.second_layer {
            return unread("layers", "second-layer");
        }
        r.layers = layers;
    }
    if let Some(thickness) = raw.thickness {
        match thickness {
            Thickness::Backface if !reads.back_faces => return unread("thickness", "back-faces"),
            Thickness::Metres(m) if !(m.is_finite() && m > 0.0) => {
                let why = t!("method_file.bad_thickness", value = m).into_owned();
                return Err(("thickness", why));
            }
            Thickness::Metres(_) if !reads.thickness => return unread("thickness", "thickness"),
            _ => {}
        }
        r.thickness = Some(thickness);
    }
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> RawRecommended {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn keys_left_out_keep_the_plain_defaults() {
        let r = check(&parse("guard_band = \"auto\""), &MethodReads::default()).unwrap();
        assert_eq!(
            r,
            Recommended {
                guard_band: GuardBand::Auto,
                ..PLAIN
            }
        );
        assert_eq!(check(&parse(""), &MethodReads::default()).unwrap(), PLAIN);
    }

    #[test]
    fn a_recommendation_needs_the_input_it_asks_for() {
        let none = MethodReads::default();
        let all = MethodReads {
            normals: true,
            back_faces: true,
            second_layer: true,
            thickness: true,
        };
        for (text, key) in [
            ("normals = \"geometric\"", "normals"),
            ("layers = 2", "layers"),
            ("thickness = \"backface\"", "thickness"),
            ("thickness = 0.2", "thickness"),
        ] {
            assert_eq!(check(&parse(text), &none).unwrap_err().0, key, "{text}");
            assert!(check(&parse(text), &all).is_ok(), "{text}");
        }
        for text in ["layers = 3", "layers = 0", "thickness = -1.0"] {
            assert!(check(&parse(text), &all).is_err(), "{text}");
        }
        assert!(toml::from_str::<RawRecommended>("quality = \"high\"").is_err());
    }
}
