//! What the engine's AO methods may read besides the depth chain, each from a pass of its own over
//! the geometry that runs only when the settings ask for it: the back faces' depth (`vbao` with
//! `thickness = "backface"`), the surface normals (`normals = "geometric"`) and a second depth layer
//! (`vbao` with `layers = 2`; with its back faces when both are asked).

use super::back_faces::BackFacePass;
use super::normals::NormalPass;
use super::second_layer::SecondLayerPass;
use crate::gl::{Gl, ProgramObject, Texture};
use crate::res::ResDirs;
use std::rc::Rc;

pub struct SurfacePasses {
    pub back_faces: BackFacePass,
    pub normals: NormalPass,
    pub second_layer: SecondLayerPass,
}

/// What a frame's surface passes produced, at the AO size.
#[derive(Default)]
pub struct SurfaceInputs {
    pub back_depth: Option<Rc<Texture>>,
    pub normals: Option<Rc<Texture>>,
    /// Linear depth of the second layer.
    pub second_depth: Option<Rc<Texture>>,
    /// Linear depth of the second layer's back faces.
    pub second_back_depth: Option<Rc<Texture>>,
    /// The window depth itself, when the chain drew it at the AO size (`ao::sky_skip`).
    pub window_depth: Option<Rc<Texture>>,
}

impl SurfacePasses {
    pub fn new(gl: &Gl, res: &ResDirs) -> anyhow::Result<SurfacePasses> {
        Ok(SurfacePasses {
            back_faces: BackFacePass::new(gl, res)?,
            normals: NormalPass::new(gl, res)?,
            second_layer: SecondLayerPass::new(gl, res)?,
        })
    }

    pub fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        let [a, b] = self.normals.programs_mut();
        let [c, d, e] = self.second_layer.programs_mut();
        let [g, h] = self.back_faces.programs_mut();
        vec![g, h, a, b, c, d, e]
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        let mut t = self.back_faces.textures();
        t.extend(self.normals.textures());
        t.extend(self.second_layer.textures());
        t
    }

    pub fn release_targets(&self) {
        self.back_faces.release_targets();
        self.normals.release_targets();
        self.second_layer.release_targets();
    }
}
