//! `Texture`: an immutable-storage 2D texture with explicit sampling state.
//!
//! The course's constructor silently sets MIN_FILTER = LINEAR (which makes `textureLod` ignore the mip
//! chain) and COMPARE_MODE on every depth texture (undefined when read through a plain sampler2D).
//! Here every caller states filter, wrap and compare mode.

use super::Gl;
use anyhow::{bail, Context as _, Result};
use glow::HasContext;
use std::path::Path;

/// How a texture is created: size, format, level count and sampling state.
#[derive(Clone, Debug)]
pub struct TextureDesc {
    pub name: String,
    pub width: u32,
    pub height: u32,
    /// Sized internal format, e.g. `glow::R32F`, `glow::DEPTH_COMPONENT32`.
    pub internal_format: u32,
    /// Number of mip levels (a count, not a max index).
    pub levels: u32,
    pub min_filter: u32,
    pub mag_filter: u32,
    pub wrap: u32,
    /// `true` sets COMPARE_REF_TO_TEXTURE (for sampler2DShadow); `false` sets NONE (raw depth reads).
    pub compare: bool,
}

impl TextureDesc {
    /// A single-level render target with nearest filtering, clamped at the edges, compare mode off.
    pub fn target(name: &str, width: u32, height: u32, internal_format: u32) -> Self {
        TextureDesc {
            name: name.to_string(),
            width,
            height,
            internal_format,
            levels: 1,
            min_filter: glow::NEAREST,
            mag_filter: glow::NEAREST,
            wrap: glow::CLAMP_TO_EDGE,
            compare: false,
        }
    }
    pub fn levels(mut self, levels: u32) -> Self {
        self.levels = levels;
        self
    }
    pub fn filter(mut self, min: u32, mag: u32) -> Self {
        self.min_filter = min;
        self.mag_filter = mag;
        self
    }
    pub fn wrap(mut self, wrap: u32) -> Self {
        self.wrap = wrap;
        self
    }
    pub fn compare(mut self, on: bool) -> Self {
        self.compare = on;
        self
    }
}

/// Number of mip levels a `width`×`height` image can have (1 for 1×1).
pub fn max_levels(width: u32, height: u32) -> u32 {
    32 - width.max(height).max(1).leading_zeros()
}

/// Size of mip `level` of a `width`×`height` image (never 0).
pub fn level_size(width: u32, height: u32, level: u32) -> (u32, u32) {
    ((width >> level).max(1), (height >> level).max(1))
}

pub struct Texture {
    gl: Gl,
    id: glow::Texture,
    desc: TextureDesc,
}

impl Texture {
    /// Creates an empty texture with `desc.levels` levels (clamped to what the size allows).
    pub fn new(gl: &Gl, mut desc: TextureDesc) -> Result<Texture> {
        if desc.width == 0 || desc.height == 0 {
            bail!(
                "texture '{}': size {}x{} is empty",
                desc.name,
                desc.width,
                desc.height
            );
        }
        let max_size = unsafe { gl.get_parameter_i32(glow::MAX_TEXTURE_SIZE) } as u32;
        if desc.width > max_size || desc.height > max_size {
            bail!(
                "texture '{}': size {}x{} exceeds GL_MAX_TEXTURE_SIZE {}",
                desc.name,
                desc.width,
                desc.height,
                max_size
            );
        }
        desc.levels = desc.levels.clamp(1, max_levels(desc.width, desc.height));
        unsafe {
            let id = gl
                .create_named_texture(glow::TEXTURE_2D)
                .map_err(|e| anyhow::anyhow!("glCreateTextures failed: {e}"))?;
            gl.texture_storage_2d(
                id,
                desc.levels as i32,
                desc.internal_format,
                desc.width as i32,
                desc.height as i32,
            );
            let tex = Texture {
                gl: gl.clone(),
                id,
                desc,
            };
            tex.apply_sampling();
            if let Some(err) = super::take_error(gl) {
                bail!(
                    "texture '{}': {err} while allocating storage",
                    tex.desc.name
                );
            }
            Ok(tex)
        }
    }

    /// Loads an 8-bit RGBA texture from an image file, with a full mip chain and trilinear filtering.
    pub fn from_file(gl: &Gl, path: &Path) -> Result<Texture> {
        let img = image::open(path)
            .with_context(|| format!("cannot load texture image {}", path.display()))?
            .flipv()
            .to_rgba8();
        let (w, h) = img.dimensions();
        let desc = TextureDesc {
            name: path.display().to_string(),
            width: w,
            height: h,
            internal_format: glow::SRGB8_ALPHA8,
            levels: max_levels(w, h),
            min_filter: glow::LINEAR_MIPMAP_LINEAR,
            mag_filter: glow::LINEAR,
            wrap: glow::REPEAT,
            compare: false,
        };
        let tex = Texture::new(gl, desc)?;
        unsafe {
            gl.texture_sub_image_2d(
                tex.id,
                0,
                0,
                0,
                w as i32,
                h as i32,
                glow::RGBA,
                glow::UNSIGNED_BYTE,
                glow::PixelUnpackData::Slice(Some(img.as_raw())),
            );
            gl.generate_texture_mipmap(tex.id);
        }
        Ok(tex)
    }

    fn apply_sampling(&self) {
        let d = &self.desc;
        unsafe {
            let gl = &self.gl;
            gl.texture_parameter_i32(self.id, glow::TEXTURE_MIN_FILTER, d.min_filter as i32);
            gl.texture_parameter_i32(self.id, glow::TEXTURE_MAG_FILTER, d.mag_filter as i32);
            gl.texture_parameter_i32(self.id, glow::TEXTURE_WRAP_S, d.wrap as i32);
            gl.texture_parameter_i32(self.id, glow::TEXTURE_WRAP_T, d.wrap as i32);
            gl.texture_parameter_i32(self.id, glow::TEXTURE_BASE_LEVEL, 0);
            gl.texture_parameter_i32(self.id, glow::TEXTURE_MAX_LEVEL, d.levels as i32 - 1);
            let mode = if d.compare {
                glow::COMPARE_REF_TO_TEXTURE
            } else {
                glow::NONE
            };
            gl.texture_parameter_i32(self.id, glow::TEXTURE_COMPARE_MODE, mode as i32);
            if d.compare {
                gl.texture_parameter_i32(self.id, glow::TEXTURE_COMPARE_FUNC, glow::LEQUAL as i32);
            }
        }
    }

    /// Sets the four swizzle sources (e.g. R,G,B ← 0 and A ← R for the lesson's AO blend).
    pub fn set_swizzle(&self, rgba: [u32; 4]) {
        unsafe {
            self.gl
                .texture_parameter_i32(self.id, glow::TEXTURE_SWIZZLE_R, rgba[0] as i32);
            self.gl
                .texture_parameter_i32(self.id, glow::TEXTURE_SWIZZLE_G, rgba[1] as i32);
            self.gl
                .texture_parameter_i32(self.id, glow::TEXTURE_SWIZZLE_B, rgba[2] as i32);
            self.gl
                .texture_parameter_i32(self.id, glow::TEXTURE_SWIZZLE_A, rgba[3] as i32);
        }
    }

    /// Restricts which levels sampling may touch (used while a pass writes one level and reads another).
    pub fn set_level_range(&self, base: u32, max: u32) {
        unsafe {
            self.gl
                .texture_parameter_i32(self.id, glow::TEXTURE_BASE_LEVEL, base as i32);
            self.gl
                .texture_parameter_i32(self.id, glow::TEXTURE_MAX_LEVEL, max as i32);
        }
    }

    pub fn id(&self) -> glow::Texture {
        self.id
    }
    pub fn desc(&self) -> &TextureDesc {
        &self.desc
    }
    pub fn width(&self) -> u32 {
        self.desc.width
    }
    pub fn height(&self) -> u32 {
        self.desc.height
    }
    pub fn levels(&self) -> u32 {
        self.desc.levels
    }
    /// Size of mip `level`.
    pub fn size_at(&self, level: u32) -> (u32, u32) {
        level_size(self.desc.width, self.desc.height, level)
    }

    /// Binds the texture to texture image unit `unit` (the shader's `layout(binding=unit)`).
    pub fn bind(&self, unit: u32) {
        unsafe { self.gl.bind_texture_unit(unit, Some(self.id)) }
    }

    /// Pixel format for reading or writing `channels` values per texel (depth textures: DEPTH_COMPONENT).
    fn transfer_format(&self, channels: u32) -> u32 {
        match (channels, is_depth_format(self.desc.internal_format)) {
            (_, true) => glow::DEPTH_COMPONENT,
            (1, false) => glow::RED,
            (2, false) => glow::RG,
            (3, false) => glow::RGB,
            _ => glow::RGBA,
        }
    }

    /// Reads one level back as f32 values, `channels` per texel (1 = RED or DEPTH, 4 = RGBA). Rows bottom-up.
    pub fn read_f32(&self, level: u32, channels: u32) -> Vec<f32> {
        let (w, h) = self.size_at(level);
        let format = self.transfer_format(channels);
        let n = (w * h * channels) as usize;
        let mut bytes = vec![0u8; n * 4];
        unsafe {
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
            self.gl.bind_texture(glow::TEXTURE_2D, Some(self.id));
            self.gl.get_tex_image(
                glow::TEXTURE_2D,
                level as i32,
                format,
                glow::FLOAT,
                glow::PixelPackData::Slice(Some(&mut bytes)),
            );
            self.gl.bind_texture(glow::TEXTURE_2D, None);
        }
        bytes
            .chunks_exact(4)
            .map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]]))
            .collect()
    }

    /// Uploads f32 data (one channel, or depth) to a level. Rows bottom-up. Used by tests and tools.
    pub fn upload_f32(&self, level: u32, channels: u32, data: &[f32]) -> Result<()> {
        let (w, h) = self.size_at(level);
        if data.len() != (w * h * channels) as usize {
            bail!(
                "texture '{}': upload of {} values to a {w}x{h}x{channels} level",
                self.desc.name,
                data.len()
            );
        }
        let format = self.transfer_format(channels);
        let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_ne_bytes()).collect();
        unsafe {
            self.gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
            self.gl.texture_sub_image_2d(
                self.id,
                level as i32,
                0,
                0,
                w as i32,
                h as i32,
                format,
                glow::FLOAT,
                glow::PixelUnpackData::Slice(Some(&bytes)),
            );
        }
        Ok(())
    }
}

pub fn is_depth_format(f: u32) -> bool {
    matches!(
        f,
        glow::DEPTH_COMPONENT16
            | glow::DEPTH_COMPONENT24
            | glow::DEPTH_COMPONENT32
            | glow::DEPTH_COMPONENT32F
            | glow::DEPTH24_STENCIL8
            | glow::DEPTH32F_STENCIL8
    )
}

impl Drop for Texture {
    fn drop(&mut self) {
        unsafe { self.gl.delete_texture(self.id) }
    }
}
