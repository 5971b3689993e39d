//! Scene descriptions: small TOML files in `Res/scenes/`, and the generator of the demo meshes.

pub mod game_object;
pub mod shapes;

use crate::ao::AoSettings;
use crate::math::camera as camera_defaults;
use anyhow::{bail, Context as _, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct OutputDesc {
    pub width: u32,
    pub height: u32,
    /// Main depth buffer: "d32" (the course's) or "d32f-reversed" (reversed-Z, float depth).
    pub depth: crate::math::DepthMode,
}
impl Default for OutputDesc {
    fn default() -> Self {
        OutputDesc {
            width: 1280,
            height: 720,
            depth: crate::math::DepthMode::D32,
        }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct CameraDesc {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    /// Vertical field of view in degrees.
    pub fov_y: f32,
    pub near: f32,
    pub far: f32,
}
impl Default for CameraDesc {
    fn default() -> Self {
        CameraDesc {
            eye: [0.0, 1.6, 6.0],
            target: [0.0, 1.0, 0.0],
            fov_y: camera_defaults::FOV_Y_DEG,
            near: camera_defaults::NEAR,
            far: camera_defaults::FAR,
        }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct LightDesc {
    /// Direction from the scene towards the light (need not be normalised).
    pub direction: [f32; 3],
    pub color: [f32; 3],
    pub ambient: [f32; 3],
    pub shadow: bool,
}
impl Default for LightDesc {
    fn default() -> Self {
        LightDesc {
            direction: [0.45, 0.8, 0.35],
            color: [2.2, 2.0, 1.8],
            ambient: [0.55, 0.6, 0.7],
            shadow: true,
        }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct BloomDesc {
    pub enabled: bool,
    pub threshold: f32,
    pub strength: f32,
}
impl Default for BloomDesc {
    fn default() -> Self {
        BloomDesc {
            enabled: true,
            threshold: 1.0,
            strength: 0.25,
        }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ObjectDesc {
    /// OBJ path, relative to `Res/` (or absolute).
    pub mesh: String,
    #[serde(default)]
    pub position: [f32; 3],
    /// Euler angles in degrees, applied Y (yaw), then X (pitch), then Z (roll).
    #[serde(default)]
    pub rotation: [f32; 3],
    #[serde(default = "one3")]
    pub scale: [f32; 3],
    #[serde(default = "grey")]
    pub color: [f32; 4],
}
fn one3() -> [f32; 3] {
    [1.0; 3]
}
fn grey() -> [f32; 4] {
    [0.8, 0.8, 0.8, 1.0]
}

#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct SceneDesc {
    pub output: OutputDesc,
    pub camera: CameraDesc,
    pub light: LightDesc,
    pub ao: AoSettings,
    pub bloom: BloomDesc,
    #[serde(rename = "object")]
    pub objects: Vec<ObjectDesc>,
}

impl SceneDesc {
    pub fn load(path: &Path) -> Result<SceneDesc> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("{}: cannot read scene file", path.display()))?;
        Self::parse(&text).with_context(|| format!("{}: invalid scene file", path.display()))
    }

    pub fn parse(text: &str) -> Result<SceneDesc> {
        let desc: SceneDesc = toml::from_str(text)?;
        desc.validate()?;
        Ok(desc)
    }

    /// A scene holding one OBJ with identity transform and the demo's lighting and AO settings,
    /// the camera framing its bounds.
    pub fn single_obj(mesh: &str) -> SceneDesc {
        SceneDesc {
            objects: vec![ObjectDesc {
                mesh: mesh.to_string(),
                position: [0.0; 3],
                rotation: [0.0; 3],
                scale: [1.0; 3],
                color: grey(),
            }],
            ..Default::default()
        }
    }

    /// Every object's triangles in world space, loaded on the CPU (for the ray-traced reference).
    pub fn world_triangles(&self, res: &crate::res::ResDirs) -> Result<Vec<[glam::Vec3; 3]>> {
        let mut out = Vec::new();
        for (i, o) in self.objects.iter().enumerate() {
            let what = || format!("scene object {} ({})", i + 1, o.mesh);
            let path = res.resolve_data(Path::new(&o.mesh)).with_context(what)?;
            let data = crate::gl::mesh::MeshData::load_obj(&path).with_context(what)?;
            let m = crate::scene::game_object::model_matrix(
                o.position.into(),
                o.rotation.into(),
                o.scale.into(),
            );
            out.extend(data.triangles().map(|t| t.map(|p| m.transform_point3(p))));
        }
        Ok(out)
    }

    pub fn validate(&self) -> Result<()> {
        let c = &self.camera;
        let finite = |v: &[f32]| v.iter().all(|x| x.is_finite());
        if !finite(&c.eye) || !finite(&c.target) {
            bail!("camera eye/target must be finite numbers");
        }
        if c.eye == c.target {
            bail!("camera eye and target are the same point");
        }
        if !(c.fov_y > 0.0 && c.fov_y < 179.0) {
            bail!("camera fov_y {} must be between 0 and 179 degrees", c.fov_y);
        }
        if !(c.near > 0.0 && c.far > c.near && c.far.is_finite()) {
            bail!(
                "camera planes must satisfy 0 < near < far (got near {}, far {})",
                c.near,
                c.far
            );
        }
        if self.output.width == 0
            || self.output.height == 0
            || self.output.width > 16384
            || self.output.height > 16384
        {
            bail!(
                "output size {}x{} must be between 1 and 16384",
                self.output.width,
                self.output.height
            );
        }
        for (i, o) in self.objects.iter().enumerate() {
            if !finite(&o.position)
                || !finite(&o.rotation)
                || !finite(&o.scale)
                || !finite(&o.color)
            {
                bail!(
                    "object {} ({}): non-finite transform or colour",
                    i + 1,
                    o.mesh
                );
            }
        }
        Ok(())
    }
}
