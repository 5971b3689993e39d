//! What the benchmark runs: the AO methods by name with their quality settings, and the fixed
//! cameras of each scene (some train the fit of a method's intensity/contrast, the others test it).
//!
//! A method is any `AoMethod` the engine knows: its row (`AoMethod::info`) makes it available here
//! as `--methods NAME`; its settings come from `settings_for`, which reads the row.

use crate::ao::AoMethod;
use crate::math::Camera;
use crate::scene::CameraDesc;
use anyhow::{bail, Result};
use glam::{Quat, Vec3};
use serde::Serialize;

/// One quality setting of a method: sample count (per the method's meaning) and radius in metres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Setting {
    pub samples: u32,
    pub radius: f32,
    /// A slice preset (slices × steps, the method's own) instead of the sample count.
    pub quality: Option<crate::ao::SlicePreset>,
}

impl Setting {
    fn new(samples: u32, radius: f32) -> Setting {
        Setting {
            samples,
            radius,
            quality: None,
        }
    }
    /// A preset of a method that has presets (`MethodInfo::presets`); `samples` is its tap count
    /// (2 sides × slices × steps).
    fn preset(method: AoMethod, q: crate::ao::SlicePreset, radius: f32) -> Setting {
        let slices_steps = method.info().presets.expect("a method with presets");
        let (slices, steps) = slices_steps(q);
        Setting {
            samples: 2 * slices * steps,
            radius,
            quality: Some(q),
        }
    }
    pub fn label(&self) -> String {
        match self.quality {
            Some(q) => format!("{} r{}", q.name(), self.radius),
            None => format!("n{} r{}", self.samples, self.radius),
        }
    }
}

/// The sample counts and radii the lesson's SAO is run with (the grid of both).
const LESSON_SAMPLES: [u32; 5] = [4, 8, 11, 16, 24];
const LESSON_RADII: [f32; 3] = [0.5, 1.0, 2.0];

/// The methods the benchmark knows, by command-line name.
pub fn method_by_name(name: &str) -> Result<AoMethod> {
    match AoMethod::ALL.iter().find(|m| m.name() == name.trim()) {
        Some(m) => Ok(*m),
        None => bail!(
            "unknown AO method '{name}': use one of {}",
            AoMethod::ALL.map(|m| m.name()).join(", ")
        ),
    }
}

/// Settings of `method`, from its row (`MethodInfo`). `samples` / `radii` override the defaults
/// when not empty (then the grid of both is run); for the methods with presets `qualities` does, as
/// the grid of presets and radii (1 m when none is given). Defaults: the lesson's SAO (the one
/// method on the lesson's chain) runs the full grid LESSON_SAMPLES × LESSON_RADII; the other
/// methods run samples 4/8/16 at radius 1 m and radii 0.5/2 m at 8 samples (their cost grows with
/// samples the same way, and the radius mostly moves their error), and their `bench_presets` at 1 m
/// and 0.5 m; a method that traces rays 1/2/4 rays per pixel at 1 m and 2 rays at 0.5/2 m (its
/// samples are rays).
pub(crate) fn settings_for(
    method: AoMethod,
    samples: &[u32],
    radii: &[f32],
    qualities: &[crate::ao::SlicePreset],
) -> Vec<Setting> {
    let grid = |s: &[u32], r: &[f32]| {
        let mut v = Vec::new();
        for &radius in r {
            for &samples in s {
                v.push(Setting::new(samples, radius));
            }
        }
        v
    };
    let info = method.info();
    let has_presets = info.presets.is_some();
    if has_presets && !qualities.is_empty() {
        let r: &[f32] = if radii.is_empty() { &[1.0] } else { radii };
        return r
            .iter()
            .flat_map(|&radius| {
                qualities
                    .iter()
                    .map(move |&q| Setting::preset(method, q, radius))
            })
            .collect();
    }
    if !samples.is_empty() || !radii.is_empty() {
        let s: Vec<u32> = if samples.is_empty() {
            vec![11]
        } else {
            samples.to_vec()
        };
        let r: Vec<f32> = if radii.is_empty() {
            vec![1.0]
        } else {
            radii.to_vec()
        };
        return grid(&s, &r);
    }
    if !info.engine_chain {
        return grid(&LESSON_SAMPLES, &LESSON_RADII);
    }
    if info.rays {
        // Rays per pixel and frame.
        return vec![
            Setting::new(1, 1.0),
            Setting::new(2, 1.0),
            Setting::new(4, 1.0),
            Setting::new(2, 0.5),
            Setting::new(2, 2.0),
        ];
    }
    let mut v = quick_settings();
    for radius in [1.0, 0.5] {
        for &q in info.bench_presets {
            v.push(Setting::preset(method, q, radius));
        }
    }
    v
}

/// The quick grid every method runs in a plain `opengl3d bench`, and the base of the methods
/// without a grid of their own: samples 4/8/16 at radius 1 m, and radii 0.5/2 m at 8 samples.
pub(crate) fn quick_settings() -> Vec<Setting> {
    vec![
        Setting::new(4, 1.0),
        Setting::new(8, 1.0),
        Setting::new(16, 1.0),
        Setting::new(8, 0.5),
        Setting::new(8, 2.0),
    ]
}

/// A fixed camera of a scene.
#[derive(Clone, Debug, Serialize)]
pub struct BenchCamera {
    pub name: String,
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub fov_y: f32,
    /// Used to fit the method's intensity/contrast; the other cameras report the fitted error.
    pub train: bool,
}

impl BenchCamera {
    /// The engine's camera for this view, with the scene's clip planes and +Y up; the ray-traced
    /// reference uses the very same camera, so both see the same pixel centres.
    pub fn camera(&self, scene: &CameraDesc) -> Camera {
        Camera {
            eye: self.eye.into(),
            target: self.target.into(),
            up: Vec3::Y,
            fov_y_deg: self.fov_y,
            near: scene.near,
            far: scene.far,
        }
    }
}

/// The scene's own camera and three variants around its target: orbited left and right (one lower),
/// and a closer, higher view. Cameras 0 and 2 train the fit, 1 and 3 test it.
pub(crate) fn camera_variants(c: &CameraDesc) -> Vec<BenchCamera> {
    let eye = Vec3::from(c.eye);
    let target = Vec3::from(c.target);
    let offset = eye - target;
    let orbit = |deg: f32, height: f32, dist: f32| {
        let o = Quat::from_rotation_y(deg.to_radians()) * offset;
        let o = Vec3::new(o.x * dist, o.y * height * dist, o.z * dist);
        (target + o).to_array()
    };
    let cam = |name: &str, eye: [f32; 3], train: bool| BenchCamera {
        name: name.to_string(),
        eye,
        target: target.to_array(),
        fov_y: c.fov_y,
        train,
    };
    vec![
        cam("scene", eye.to_array(), true),
        cam("orbit-left", orbit(-30.0, 1.0, 0.95), false),
        cam("orbit-right-low", orbit(28.0, 0.6, 0.9), true),
        cam("close-high", orbit(-8.0, 1.6, 0.6), false),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gtao_runs_its_presets_and_explicit_samples_replace_them() {
        let labels: Vec<String> = settings_for(AoMethod::Gtao, &[], &[], &[])
            .iter()
            .map(Setting::label)
            .collect();
        assert!(labels.contains(&"high r1".to_string()), "{labels:?}");
        assert!(labels.contains(&"ultra r0.5".to_string()), "{labels:?}");
        let high = settings_for(AoMethod::Gtao, &[], &[], &[])
            .into_iter()
            .find(|s| s.quality == Some(crate::ao::SlicePreset::High))
            .unwrap();
        assert_eq!(high.samples, 2 * 3 * 6);
        assert!(settings_for(AoMethod::Gtao, &[16], &[], &[])
            .iter()
            .all(|s| s.quality.is_none()));
        assert!(settings_for(AoMethod::Sao, &[], &[], &[])
            .iter()
            .all(|s| s.quality.is_none()));
        let vbao: Vec<String> = settings_for(AoMethod::Vbao, &[], &[], &[])
            .iter()
            .map(Setting::label)
            .collect();
        for label in ["low r1", "medium r0.5", "high r0.5", "ultra r1"] {
            assert!(vbao.contains(&label.to_string()), "{vbao:?}");
        }
        let low = crate::ao::SlicePreset::Low;
        let chosen: Vec<String> = settings_for(AoMethod::Vbao, &[8], &[0.5, 1.0], &[low])
            .iter()
            .map(Setting::label)
            .collect();
        assert_eq!(chosen, ["low r0.5", "low r1"]);
        // Methods without presets keep the samples grid.
        assert_eq!(settings_for(AoMethod::Sao, &[8], &[], &[low]).len(), 1);
    }
}
