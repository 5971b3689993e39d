//! What the benchmark runs: the AO methods by name with their quality settings, and the fixed
//! cameras of each scene (some train the fit of a method's intensity/contrast, the others test it).
//!
//! A method is any `AoMethod` the engine knows: adding one to `AoMethod::ALL` (with its name and
//! shader) makes it available here as `--methods NAME`; its settings come from [`settings_for`].

use crate::ao::AoMethod;
use crate::scene::CameraDesc;
use anyhow::{bail, Result};
use glam::{Quat, Vec3};
use serde::Serialize;

/// One quality setting of a method: sample count (per the method's meaning) and radius in metres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Setting {
    pub samples: u32,
    pub radius: f32,
}

impl Setting {
    pub fn label(&self) -> String {
        format!("n{} r{}", self.samples, self.radius)
    }
}

/// The sample counts and radii the lesson's SAO is run with (the grid of both).
pub const LESSON_SAMPLES: [u32; 5] = [4, 8, 11, 16, 24];
pub const LESSON_RADII: [f32; 3] = [0.5, 1.0, 2.0];

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

/// Settings of `method`. `samples` / `radii` override the defaults when not empty (then the grid of
/// both is run). Defaults: the lesson's SAO runs the full grid LESSON_SAMPLES × LESSON_RADII; the
/// other methods run samples 4/8/16 at radius 1 m and radii 0.5/2 m at 8 samples (their cost
/// grows with samples the same way, and the radius mostly moves their error).
pub fn settings_for(method: AoMethod, samples: &[u32], radii: &[f32]) -> Vec<Setting> {
    let grid = |s: &[u32], r: &[f32]| {
        let mut v = Vec::new();
        for &radius in r {
            for &samples in s {
                v.push(Setting { samples, radius });
            }
        }
        v
    };
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
    match method {
        AoMethod::SaoLesson => grid(&LESSON_SAMPLES, &LESSON_RADII),
        _ => vec![
            Setting {
                samples: 4,
                radius: 1.0,
            },
            Setting {
                samples: 8,
                radius: 1.0,
            },
            Setting {
                samples: 16,
                radius: 1.0,
            },
            Setting {
                samples: 8,
                radius: 0.5,
            },
            Setting {
                samples: 8,
                radius: 2.0,
            },
        ],
    }
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

/// The scene's own camera and three variants around its target: orbited left and right (one lower),
/// and a closer, higher view. Cameras 0 and 2 train the fit, 1 and 3 test it.
pub fn camera_variants(c: &CameraDesc) -> Vec<BenchCamera> {
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
