//! `StorageBuffer`: an immutable shader storage buffer (std430 data written once, read by shaders),
//! deleted on drop.

use super::Gl;
use anyhow::{anyhow, bail, Result};
use glow::HasContext;

pub struct StorageBuffer {
    gl: Gl,
    id: glow::Buffer,
    bytes: u64,
}

impl StorageBuffer {
    /// Uploads `words` (at least one word is stored: GL has no empty buffer storage).
    pub fn new(gl: &Gl, label: &str, words: &[u32]) -> Result<StorageBuffer> {
        let data: Vec<u8> = if words.is_empty() {
            vec![0; 4]
        } else {
            words.iter().flat_map(|w| w.to_ne_bytes()).collect()
        };
        // SAFETY: a buffer this function creates, filled from a slice that outlives the call.
        unsafe {
            let id = gl
                .create_named_buffer()
                .map_err(|e| anyhow!("glCreateBuffers failed: {e}"))?;
            let buffer = StorageBuffer {
                gl: gl.clone(),
                id,
                bytes: data.len() as u64,
            };
            gl.object_label(glow::BUFFER, id.0.get(), Some(label));
            gl.named_buffer_data_u8_slice(id, &data, glow::STATIC_DRAW);
            if let Some(err) = super::take_error(gl) {
                bail!(
                    "storage buffer '{label}': {err} while uploading {} bytes",
                    data.len()
                );
            }
            Ok(buffer)
        }
    }

    /// Binds the buffer to `layout(std430, binding = index)`.
    pub fn bind(&self, index: u32) {
        // SAFETY: binding a live buffer to an indexed target.
        unsafe {
            self.gl
                .bind_buffer_base(glow::SHADER_STORAGE_BUFFER, index, Some(self.id))
        };
    }

    /// The buffer's contents (after a `glMemoryBarrier` when a shader wrote them).
    pub fn read_words(&self) -> Vec<u32> {
        let mut bytes = vec![0u8; self.bytes as usize];
        // SAFETY: reading a live buffer into a slice of its size.
        unsafe {
            self.gl
                .bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(self.id));
            self.gl
                .get_buffer_sub_data(glow::SHADER_STORAGE_BUFFER, 0, &mut bytes);
            self.gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, None);
        }
        bytes
            .chunks_exact(4)
            .map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
            .collect()
    }

    pub fn bytes(&self) -> u64 {
        self.bytes
    }
}

impl Drop for StorageBuffer {
    fn drop(&mut self) {
        // SAFETY: the buffer is owned by this value and deleted once.
        unsafe { self.gl.delete_buffer(self.id) };
    }
}
