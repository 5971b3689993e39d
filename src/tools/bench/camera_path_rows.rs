//! Which configurations `bench --camera-path` runs (`--path-rows`): `vbao`'s set, and `rtao` at a
//! given size, rays per frame and blur, each one frame at a time and accumulated.

use super::camera_path_score::PathSetting;
use crate::ao::{AoMethod, AoResolution, AoSettings, GuardBand};
use anyhow::{bail, Result};

/// The rows without `--path-rows`.
pub const DEFAULT_ROWS: &[&str] = &["vbao", "rtao-quarter-4"];

/// A row family: `vbao`, or `rtao-<full|half|quarter>-<rays>[-noblur]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathRows {
    Vbao,
    Rtao {
        resolution: AoResolution,
        rays: u32,
        blur: bool,
    },
}

impl PathRows {
    pub fn parse(spec: &str) -> Result<PathRows> {
        if spec == "vbao" {
            return Ok(PathRows::Vbao);
        }
        let parts: Vec<&str> = spec.split('-').collect();
        let parsed = match parts.as_slice() {
            ["rtao", size, rays, rest @ ..] if rest.is_empty() || rest == ["noblur"] => {
                AoResolution::from_name(size)
                    .zip(rays.parse::<u32>().ok().filter(|n| (1..=64).contains(n)))
                    .map(|(resolution, rays)| PathRows::Rtao {
                        resolution,
                        rays,
                        blur: rest.is_empty(),
                    })
            }
            _ => None,
        };
        match parsed {
            Some(p) => Ok(p),
            None => bail!(
                "--path-rows {spec}: expected vbao or rtao-<full|half|quarter>-<rays 1..64>[-noblur]"
            ),
        }
    }
}

/// `rtao` rows at `radius`: one frame at a time, then accumulated over `accumulate` frames.
pub fn rtao_rows(
    base: &AoSettings,
    radius: f32,
    resolution: AoResolution,
    rays: u32,
    blur: bool,
    accumulate: u32,
) -> Vec<(PathSetting, AoSettings)> {
    let size = resolution.name();
    let blurred = if blur { "" } else { ", no blur" };
    [1, accumulate]
        .into_iter()
        .map(|n| {
            let s = AoSettings {
                method: AoMethod::Rtao,
                radius,
                enabled: true,
                resolution,
                rays,
                blur,
                stratified: false,
                // Rays see what is off screen: no guard band.
                guard_band: GuardBand::Off,
                accumulate: n,
                ..*base
            };
            let frames = if n > 1 {
                format!(" ×{n}")
            } else {
                String::new()
            };
            let setting = PathSetting {
                label: format!("rtao {size} {rays} rays{frames}{blurred}"),
                method: AoMethod::Rtao,
                accumulate: n,
                settings: format!("{rays} rays per frame, {size} size{blurred}"),
            };
            (setting, s)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn row_specs_parse_or_say_what_they_expect() {
        assert_eq!(PathRows::parse("vbao").unwrap(), PathRows::Vbao);
        assert_eq!(
            PathRows::parse("rtao-quarter-4-noblur").unwrap(),
            PathRows::Rtao {
                resolution: AoResolution::Quarter,
                rays: 4,
                blur: false
            }
        );
        for bad in [
            "rtao",
            "rtao-eighth-2",
            "rtao-half-0",
            "rtao-half-2-blur",
            "gtao",
        ] {
            let e = PathRows::parse(bad).unwrap_err().to_string();
            assert!(e.contains(bad) && e.contains("rtao-<full"), "{e}");
        }
        for spec in DEFAULT_ROWS {
            PathRows::parse(spec).unwrap();
        }
    }

    #[test]
    fn rtao_rows_come_one_frame_and_accumulated() {
        let rows = rtao_rows(
            &AoSettings::default(),
            1.0,
            AoResolution::Quarter,
            2,
            true,
            16,
        );
        assert_eq!(rows.len(), 2);
        assert_eq!((rows[0].1.accumulate, rows[1].1.accumulate), (1, 16));
        assert!(rows.iter().all(|(p, s)| p.method == AoMethod::Rtao
            && s.method == AoMethod::Rtao
            && s.rays == 2
            && s.resolution == AoResolution::Quarter));
    }
}
