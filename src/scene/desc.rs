//! What a scene holds: output, camera, light, AO, bloom and objects, as read from a scene file.

use super::ao_settings::AoSettings;
use crate::math::camera as camera_defaults;
use crate::res::ResDirs;
use anyhow::{Context as _, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;

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
impl CameraDesc {
    /// The camera this description places (+Y up).
    pub fn camera(&self) -> crate::math::Camera {
        crate::math::Camera {
            eye: self.eye.into(),
            target: self.target.into(),
            up: glam::Vec3::Y,
            fov_y_deg: self.fov_y,
            near: self.near,
            far: self.far,
        }
    }
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
    /// Model path (OBJ, or glTF `.gltf`/`.glb`): absolute, or relative to the scene file's folder, else
    /// to `Res/`.
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
    /// Files already found for mesh names when the scene was loaded (a mesh next to its scene file,
    /// or an `--obj` whose path is not UTF-8 and so cannot be spelled in `mesh`). Not part of the file.
    #[serde(skip)]
    pub mesh_files: BTreeMap<String, PathBuf>,
}

impl SceneDesc {
    /// A scene holding one OBJ with identity transform and the demo's lighting and AO settings.
    /// The path is kept as given, so a file name that is not UTF-8 still loads.
    pub fn single_obj(path: &std::path::Path) -> SceneDesc {
        let name = path.to_string_lossy().into_owned();
        let mut mesh_files = BTreeMap::new();
        mesh_files.insert(name.clone(), path.to_path_buf());
        SceneDesc {
            objects: vec![ObjectDesc {
                mesh: name,
                position: [0.0; 3],
                rotation: [0.0; 3],
                scale: [1.0; 3],
                color: grey(),
            }],
            mesh_files,
            ..Default::default()
        }
    }

    /// The file an object's `mesh` names: the one found at load time, else `Res/`'s lookup.
    pub fn mesh_path(&self, mesh: &str, res: &ResDirs) -> Result<PathBuf, crate::res::NotFound> {
        match self.mesh_files.get(mesh) {
            Some(p) => Ok(p.clone()),
            None => res.resolve_data(std::path::Path::new(mesh)),
        }
    }

    /// Every object's triangles in world space, loaded on the CPU (for the ray-traced reference).
    pub fn world_triangles(&self, res: &ResDirs) -> Result<Vec<[glam::Vec3; 3]>> {
        let mut out = Vec::new();
        for (i, o) in self.objects.iter().enumerate() {
            let what = || format!("scene object {} ({})", i + 1, o.mesh);
            let path = self.mesh_path(&o.mesh, res).with_context(what)?;
            let data = crate::gl::mesh::MeshData::load_model(&path).with_context(what)?;
            let m = crate::scene::game_object::model_matrix(
                o.position.into(),
                o.rotation.into(),
                o.scale.into(),
            );
            out.extend(data.triangles().map(|t| t.map(|p| m.transform_point3(p))));
        }
        Ok(out)
    }
}
