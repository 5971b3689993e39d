//! A method file's method in the engine: built with the engine's camera, run in the place of the
//! engine method that reads the most inputs, with the settings narrowed to what the file reads.

use super::Engine;
use crate::ao::user_method::{settings_for, UserMethod};
use crate::scene::method_file::MethodFile;
use anyhow::Result;

impl Engine {
    /// Runs `file`'s method from the next frame on (shader errors name the file and line).
    pub fn use_method_file(&mut self, file: MethodFile) -> Result<()> {
        let method = UserMethod::build(file, &self.gl, &self.res, &self.camera)?;
        self.ao_settings = settings_for(method.file(), &self.ao_settings);
        self.ao.set_user_method(Some(method));
        self.sync_shader_constants()
    }
}
