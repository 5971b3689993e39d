//! A method of the user's own, from a method file (`--method-file`): its shader, outside `Res/`,
//! built like every engine method's (`ShaderMethod`: `common.glsl`'s uniforms, the packed output
//! and blur), its parameters injected as `#define`s. It runs in the place of `HOST`, the engine
//! method that reads the most inputs, so the engine draws for it whatever its file says it reads.

use crate::ao::method_pass::{method_defines, AoInputs, AoMethodPass, ShaderMethod};
use crate::ao::settings::{AoMethod, AoSettings, NormalSource, SlabHierarchy, Thickness};
use crate::gl::{Gl, ProgramError, ProgramObject, Texture};
use crate::math::Camera;
use crate::res::ResDirs;
use crate::scene::method_file::MethodFile;
use anyhow::Result;
use std::rc::Rc;

/// The engine method whose place a method file takes (its chain, its inputs).
pub const HOST: AoMethod = AoMethod::Vbao;

/// Where the engine's shader headers (`common.glsl` and what it includes) are.
const ENGINE_HEADER: &str = "ao/common.glsl";

pub struct UserMethod {
    inner: ShaderMethod,
    file: MethodFile,
    /// The file's name for the pass and its blur in the frame's statistics, which keep pass names
    /// for the whole run (a few bytes per method file loaded).
    labels: (&'static str, &'static str),
}

impl UserMethod {
    pub fn build(
        file: MethodFile,
        gl: &Gl,
        res: &ResDirs,
        camera: &Camera,
    ) -> Result<UserMethod, ProgramError> {
        let mut defines = method_defines(camera);
        let own = file.defines();
        defines.extend(own.iter().map(|(k, v)| (k.as_str(), v.clone())));
        let headers = res.find(ENGINE_HEADER)?;
        let program = ProgramObject::from_paths(
            gl,
            res.find("simple.vert")?,
            file.shader.clone(),
            &defines,
            headers.parent().map(|p| p.to_path_buf()),
        )?;
        let rules = file.counts;
        let counts =
            Box::new(move |s: &AoSettings| [rules[0].value(s.samples), rules[1].value(s.samples)]);
        let inner = ShaderMethod::with_program(HOST, program, counts, gl, res, camera)?;
        let leak = |s: String| -> &'static str { Box::leak(s.into_boxed_str()) };
        let labels = (
            leak(file.name.clone()),
            leak(format!("{} packed blur", file.name)),
        );
        Ok(UserMethod {
            inner,
            file,
            labels,
        })
    }

    pub fn file(&self) -> &MethodFile {
        &self.file
    }

    /// Sets a parameter (kept in its range); the next `update_defines` rebuilds the shader with it.
    pub fn set_parameter(&mut self, name: &str, value: f32) -> Result<()> {
        self.file.set(name, value)
    }
}

/// The settings as the method file's method sees them: its `[recommended]` configuration where
/// neither the scene nor a flag writes a key, and only the inputs its file says it reads are
/// drawn (`HOST`'s slab hierarchy never: the method's shader does not read it).
pub fn settings_for(file: &MethodFile, settings: &AoSettings) -> AoSettings {
    let mut s = *settings;
    s.method = HOST;
    // The keys the scene and the flags leave unwritten follow the file's recommendation, not the
    // one applied for the scene's own method.
    crate::scene::ao_defaults::apply_from(&mut s, &file.recommended);
    if !file.reads.normals {
        s.normals = NormalSource::Depth;
    }
    if !file.reads.back_faces && s.thickness == Some(Thickness::Backface) {
        s.thickness = None;
    }
    if !file.reads.second_layer {
        s.layers = 1;
    }
    s.slab_hierarchy = SlabHierarchy::Off;
    s
}

impl AoMethodPass for UserMethod {
    fn method(&self) -> AoMethod {
        HOST
    }
    fn own_labels(&self) -> Option<(&'static str, &'static str)> {
        Some(self.labels)
    }
    fn programs_mut(&mut self) -> Vec<&mut ProgramObject> {
        self.inner.programs_mut()
    }
    fn update_defines(&mut self, camera: &Camera, s: &AoSettings) -> Result<(), ProgramError> {
        let own = self.file.defines();
        let extra: Vec<(&str, String)> = own.iter().map(|(k, v)| (k.as_str(), v.clone())).collect();
        self.inner.update_defines_with(camera, s, &extra)
    }
    fn compute(&self, inputs: &AoInputs) -> Result<()> {
        self.inner.compute(inputs)
    }
    fn blur(&self, inputs: &AoInputs) -> Result<()> {
        self.inner.blur(inputs)
    }
    fn textures(&self) -> Vec<Rc<Texture>> {
        self.inner.textures()
    }
    fn release_targets(&mut self) {
        self.inner.release_targets();
    }
}
