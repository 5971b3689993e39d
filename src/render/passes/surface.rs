//! What the engine's AO methods may read besides the depth chain, each from a pass of its own over
//! the geometry that runs only when the settings ask for it: the back faces' depth (`vbao` with
//! `thickness = "backface"`) and the surface normals (`normals = "geometric"`).

use super::back_faces::BackFacePass;
use super::normals::NormalPass;
use crate::gl::{Gl, ProgramObject, Texture};
use crate::res::ResDirs;
use std::rc::Rc;

pub struct SurfacePasses {
    pub back_faces: BackFacePass,
    pub normals: NormalPass,
}

/// What a frame's surface passes produced, at the AO size.
#[derive(Default)]
pub struct SurfaceInputs {
    pub back_depth: Option<Rc<Texture>>,
    pub normals: Option<Rc<Texture>>,
}

impl SurfacePasses {
    pub fn new(gl: &Gl, res: &ResDirs) -> anyhow::Result<SurfacePasses> {
        Ok(SurfacePasses {
            back_faces: BackFacePass::new(gl, res)?,
            normals: NormalPass::new(gl, res)?,
        })
    }

    pub fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        let [a, b] = self.normals.programs_mut();
        vec![self.back_faces.program_mut(), a, b]
    }

    pub fn textures(&self) -> Vec<Rc<Texture>> {
        let mut t = self.back_faces.textures();
        t.extend(self.normals.textures());
        t
    }

    pub fn release_targets(&self) {
        self.back_faces.release_targets();
        self.normals.release_targets();
    }
}
