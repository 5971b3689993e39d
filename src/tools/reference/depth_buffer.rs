//! The input of the screen-space reference: a depth buffer, the projection it was rendered with,
//! how thick its surfaces are taken to be (one thickness, or each pixel's own from a depth render of
//! the back faces), and how many of its pixels lie outside the visible image (a guard band rendered
//! over a wider field of view).

use anyhow::{bail, Result};

use super::hash::Fnv64;
use super::image::RefImage;
use crate::math::Camera;

/// What `DepthBuffer::capture` reads from the engine besides the depth.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Capture {
    /// The back faces' depth (`vbao`'s `--thickness backface`).
    pub back_faces: bool,
    /// The surface normals (`--normals geometric`).
    pub normals: bool,
    /// The second depth layer (`vbao`'s `--layers 2`), beginning this many metres behind the first;
    /// with `back_faces`, its own back faces too (as `vbao` reads them).
    pub second_layer: Option<f32>,
}

/// A depth buffer and the projection it was rendered with.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthBuffer {
    /// Size of the whole buffer, guard band included.
    pub width: u32,
    pub height: u32,
    /// View distance (−z_view, metres) at each pixel centre, rows top-down; `f32::INFINITY` (or
    /// anything not finite and > 0) for sky.
    pub linear_depth: Vec<f32>,
    /// Vertical field of view of the whole buffer in degrees; the aspect ratio is width / height.
    pub fov_y_deg: f32,
    /// Near clip distance (metres): the buffer knows nothing closer.
    pub near: f32,
    /// How far (linear depth, metres) behind its surface each pixel is taken to be solid:
    /// `f32::INFINITY` is the heightfield (everything behind a stored surface is solid), a finite
    /// value the slab model `vbao` uses (see the `heightfield` module). With [`Self::back_depth`]:
    /// the thickness of the pixels that have no back face behind them.
    pub thickness: f32,
    /// Linear depth (m) of the nearest back face along each pixel's ray (`vbao`'s
    /// `--thickness backface`): the pixel's slab reaches from its surface to there. Where that is
    /// not a depth behind the surface (`f32::INFINITY`: no back face, as for an open plane or the
    /// sky; or one not deeper than the surface), the slab is [`Self::thickness`] thick, as in
    /// `vbao` (an infinite one: everything behind them is solid, as in the heightfield). `None`:
    /// every slab is `thickness` thick.
    pub back_depth: Option<Vec<f32>>,
    /// The surface's own normal at each pixel (view space, unit length, rows top-down), from the
    /// engine's surface-normal pass: the ceiling of a method reading geometric normals. `None`:
    /// normals rebuilt from the depths, as methods reading only depth must.
    pub normals: Option<Vec<[f32; 3]>>,
    /// Linear depth (m) of the second layer along each pixel's ray, rows top-down: the nearest front
    /// face a minimum separation behind the first surface (`vbao`'s `--layers 2`), a slab of
    /// [`Self::thickness`] like the first layer's; `f32::INFINITY` where none. `None`: one layer.
    pub second_layer: Option<Vec<f32>>,
    /// Linear depth (m) of the back face that closes the second layer's surface, rows top-down
    /// (`vbao` with `--thickness backface` and `--layers 2`): that slab reaches there, never
    /// thinner than [`crate::ao::LAYER2_MIN_THICKNESS_OF_SET`] of [`Self::thickness`];
    /// `f32::INFINITY` where none (the slab is then [`Self::thickness`] thick). `None`: every
    /// second-layer slab is [`Self::thickness`] thick.
    pub second_back_depth: Option<Vec<f32>>,
    /// Pixels on each side that lie outside the visible image: they can occlude, but the
    /// reference is only computed for the inner (width − 2g) × (height − 2g) pixels.
    pub guard_band: u32,
    /// How the surface is rebuilt between pixel centres (see the `heightfield` module).
    pub surface: Surface,
}

/// How the screen-space reference rebuilds the surface from the pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Surface {
    /// Two triangles per 2×2 cell of pixel centres, a triangle solid only where its three pixels'
    /// slabs overlap, back faces never closer than the set thickness: the surface `vbao` and its
    /// taps rebuild, so the reference is the ceiling of that method.
    #[default]
    Triangles,
    /// Each pixel's footprint holds the plane through its centre with its normal, solid from
    /// there to its back face exactly (the set thickness where it has none): what the buffer
    /// knows, rebuilt with no connectivity rule and no minimum thickness.
    Patches,
    /// Each pixel's footprint at its own depth, solid from there to its back face: the second
    /// layer's patches, which have no normal of their own. Normals rebuilt from a second layer's
    /// depth (a patchwork of whatever lies hidden, every pixel a silhouette) tilt its patches until
    /// a corner reaches half the centre's depth, in front of the first surface that hides it; a
    /// flat footprint is the slab `vbao` takes at a tap of that layer.
    FlatPatches,
}

impl Surface {
    /// The surface a ceiling rebuilds for a method reading these normals: the patches need each
    /// pixel's own plane, which normals rebuilt from depth bend across every silhouette and crease
    /// (a thin slat's patches tilt), so those keep the triangles.
    pub fn for_normals(geometric: bool) -> Surface {
        if geometric {
            Surface::Patches
        } else {
            Surface::Triangles
        }
    }
}

impl DepthBuffer {
    /// Checks the buffer's size and projection (clear errors instead of NaN later).
    pub(crate) fn validate(&self) -> Result<()> {
        let n = self.width as usize * self.height as usize;
        if self.linear_depth.len() != n {
            bail!(
                "depth buffer of {} values does not match its {}x{} size",
                self.linear_depth.len(),
                self.width,
                self.height
            );
        }
        if !(self.fov_y_deg > 0.0 && self.fov_y_deg < 180.0) {
            bail!(
                "field of view {}° of the depth buffer: use (0, 180)",
                self.fov_y_deg
            );
        }
        if !(self.near > 0.0 && self.near.is_finite()) {
            bail!("near plane {} of the depth buffer: use > 0", self.near);
        }
        if self.thickness.is_nan() || self.thickness <= 0.0 {
            bail!(
                "thickness {} m of the depth buffer's surfaces: use > 0 (infinity for a heightfield)",
                self.thickness
            );
        }
        if let Some(back) = &self.back_depth {
            if back.len() != n {
                bail!(
                    "back-face depth of {} values does not match the {}x{} depth buffer",
                    back.len(),
                    self.width,
                    self.height
                );
            }
        }
        for (what, layer) in [
            ("second layer", &self.second_layer),
            ("second layer's back-face depth", &self.second_back_depth),
        ] {
            if let Some(values) = layer {
                if values.len() != n {
                    bail!(
                        "{what} of {} values does not match the {}x{} depth buffer",
                        values.len(),
                        self.width,
                        self.height
                    );
                }
            }
        }
        if self.second_back_depth.is_some() && self.second_layer.is_none() {
            bail!("the second layer's back faces were given without the second layer");
        }
        if let Some(normals) = &self.normals {
            if normals.len() != n {
                bail!(
                    "normals of {} pixels do not match the {}x{} depth buffer",
                    normals.len(),
                    self.width,
                    self.height
                );
            }
        }
        let g = self.guard_band as u64 * 2;
        if g > 0 && (g >= self.width as u64 || g >= self.height as u64) {
            bail!(
                "guard band of {} pixels leaves nothing visible in a {}x{} depth buffer",
                self.guard_band,
                self.width,
                self.height
            );
        }
        Ok(())
    }

    /// Size of the visible image (the buffer less its guard band).
    pub fn visible_size(&self) -> (u32, u32) {
        let g = 2 * self.guard_band;
        (self.width.saturating_sub(g), self.height.saturating_sub(g))
    }

    /// The same buffer with its surfaces taken to be `thickness` metres thick (builder style).
    pub fn with_thickness(self, thickness: f32) -> DepthBuffer {
        DepthBuffer { thickness, ..self }
    }

    /// The second layer as a buffer of its own (same projection, thickness and guard band; its own
    /// back faces when they were captured, each slab at least `vbao`'s minimum deep; no normals, so
    /// flat patches where the first layer has patches):
    /// the screen-space reference's second field of slabs.
    pub(crate) fn second_layer_buffer(&self) -> Option<DepthBuffer> {
        let front = self.second_layer.clone()?;
        let least = crate::ao::LAYER2_MIN_THICKNESS_OF_SET * self.thickness;
        let back_depth = self.second_back_depth.as_ref().map(|back| {
            front
                .iter()
                .zip(back)
                .map(|(&f, &b)| {
                    if f.is_finite() && b.is_finite() && b > f {
                        b.max(f + least)
                    } else {
                        f32::INFINITY
                    }
                })
                .collect()
        });
        Some(DepthBuffer {
            linear_depth: front,
            back_depth,
            normals: None,
            second_layer: None,
            second_back_depth: None,
            surface: match self.surface {
                Surface::Triangles => Surface::Triangles,
                Surface::Patches | Surface::FlatPatches => Surface::FlatPatches,
            },
            ..self.clone()
        })
    }

    /// The depth buffer of a ray-traced reference image (its `linear_depth`, same pixel centres).
    pub fn from_reference(img: &RefImage, cam: &Camera) -> DepthBuffer {
        DepthBuffer {
            width: img.width,
            height: img.height,
            linear_depth: img.linear_depth.clone(),
            fov_y_deg: cam.fov_y_deg,
            near: cam.near,
            thickness: f32::INFINITY,
            back_depth: None,
            normals: None,
            second_layer: None,
            second_back_depth: None,
            guard_band: 0,
            surface: Surface::Triangles,
        }
    }

    /// Converts raw window-space depth values D in [0, 1] (rows top-down) written with `mode`'s
    /// projection and these planes; the mode's cleared value (1 for D32, 0 for reversed-Z) is sky.
    fn from_window_depth(
        width: u32,
        height: u32,
        window_depth: &[f32],
        mode: crate::math::DepthMode,
        fov_y_deg: f32,
        near: f32,
        far: f32,
    ) -> Result<DepthBuffer> {
        if !(far > near && far.is_finite()) {
            bail!("far plane {far} must be finite and beyond the near plane {near}");
        }
        let linear_depth = window_depth
            .iter()
            .map(|&d| {
                if d.is_finite() && (0.0..=1.0).contains(&d) && d != mode.clear_value() {
                    let z = crate::math::depth::linearize(mode, d as f64, near as f64, far as f64);
                    if z.is_finite() && z > 0.0 {
                        return z as f32;
                    }
                }
                f32::INFINITY
            })
            .collect();
        let buf = DepthBuffer {
            width,
            height,
            linear_depth,
            fov_y_deg,
            near,
            thickness: f32::INFINITY,
            back_depth: None,
            normals: None,
            second_layer: None,
            second_back_depth: None,
            guard_band: 0,
            surface: Surface::Triangles,
        };
        buf.validate()?;
        Ok(buf)
    }

    /// The engine's full-resolution depth buffer at its current camera and size: renders the
    /// opaque pass (through the linear-depth view, which runs no AO method) and reads the main
    /// framebuffer's depth texture back.
    pub fn from_engine(engine: &mut crate::render::Engine) -> Result<DepthBuffer> {
        engine.render_values(crate::render::View::LinearDepth)?;
        let Some(tex) = engine.fbo_main.depth_texture() else {
            bail!("the engine's main framebuffer has no depth texture");
        };
        let (w, h) = (tex.width(), tex.height());
        let mut raw = tex.read_f32(0, 1);
        if let Some(e) = crate::gl::take_error(engine.gl()) {
            bail!("{e} while reading the depth buffer");
        }
        crate::gl::readback::flip_rows(&mut raw, w as usize, h as usize);
        let cam = engine.camera;
        let mode = engine.depth_mode();
        DepthBuffer::from_window_depth(w, h, &raw, mode, cam.fov_y_deg, cam.near, cam.far)
    }

    /// Like [`DepthBuffer::from_engine`], with `guard_band` extra pixels on each side: the engine
    /// renders at (w + 2g) × (h + 2g) with a field of view widened so that the pixels keep their
    /// size and the inner pixels their centres, so that surfaces just off the visible screen exist
    /// in the buffer. The engine's size and camera are restored afterwards (also on error).
    pub fn from_engine_with_guard_band(
        engine: &mut crate::render::Engine,
        guard_band: u32,
    ) -> Result<DepthBuffer> {
        DepthBuffer::capture(engine, guard_band, Capture::default())
    }

    /// Like [`DepthBuffer::from_engine_with_guard_band`], with [`Self::back_depth`] from the
    /// back-face pass `vbao` reads at full AO resolution (`Engine::render_back_face_depth`), over the
    /// same pixels. Give it the thickness of the pixels without a back face with
    /// [`Self::with_thickness`] (`vbao`'s is `AoSettings::thickness_metres`).
    pub fn from_engine_with_back_faces(
        engine: &mut crate::render::Engine,
        guard_band: u32,
    ) -> Result<DepthBuffer> {
        let what = Capture {
            back_faces: true,
            ..Capture::default()
        };
        DepthBuffer::capture(engine, guard_band, what)
    }

    /// The depth buffer of the engine at its camera, `guard_band` pixels wider on each side, with
    /// the back faces' depth and the surface normals when `what` asks for them.
    pub fn capture(
        engine: &mut crate::render::Engine,
        guard_band: u32,
        what: Capture,
    ) -> Result<DepthBuffer> {
        let read = |engine: &mut crate::render::Engine| -> Result<DepthBuffer> {
            let mut buf = DepthBuffer::from_engine(engine)?;
            if what.normals {
                buf.normals = Some(engine.render_surface_normals()?);
            }
            // The passes write exactly `far` where nothing lies behind the pixel.
            let far = engine.camera.far;
            let behind = |depths: Vec<f32>| -> Vec<f32> {
                depths
                    .into_iter()
                    .map(|d| {
                        if d.is_finite() && d > 0.0 && d < far {
                            d
                        } else {
                            f32::INFINITY
                        }
                    })
                    .collect()
            };
            if what.back_faces {
                buf.back_depth = Some(behind(engine.render_back_face_depth()?));
            }
            if let Some(separation) = what.second_layer {
                let (layer, back) =
                    engine.render_second_layer_depths(separation, what.back_faces)?;
                buf.second_layer = Some(behind(layer));
                buf.second_back_depth = back.map(behind);
            }
            Ok(buf)
        };
        if guard_band == 0 {
            return read(engine);
        }
        let (w, h) = engine.size();
        let (gw, gh) = guard_band
            .checked_mul(2)
            .and_then(|g| Some((w.checked_add(g)?, h.checked_add(g)?)))
            .filter(|(gw, gh)| *gw <= 16384 && *gh <= 16384)
            .ok_or_else(|| {
                anyhow::anyhow!(
                    "guard band of {guard_band} pixels: the depth buffer would exceed 16384 pixels"
                )
            })?;
        let camera = engine.camera;
        let half = (camera.fov_y_deg as f64).to_radians() * 0.5;
        let wide = 2.0 * (half.tan() * gh as f64 / h.max(1) as f64).atan();
        if wide.is_nan() || wide.to_degrees() >= 179.0 {
            bail!(
                "guard band of {guard_band} pixels widens the {}° field of view past 179°",
                camera.fov_y_deg
            );
        }
        let result = (|| -> Result<DepthBuffer> {
            engine.resize(gw, gh)?;
            engine.camera.fov_y_deg = wide.to_degrees() as f32;
            engine.sync_shader_constants()?;
            let mut buf = read(engine)?;
            buf.guard_band = guard_band;
            buf.validate()?;
            Ok(buf)
        })();
        engine.camera = camera;
        let restored = engine
            .resize(w, h)
            .and_then(|_| engine.sync_shader_constants());
        let buf = result?;
        restored?;
        Ok(buf)
    }

    /// Stable content hash (every depth value's bits and the projection; the thickness, the guard
    /// band and the back faces only when they differ from the heightfield's defaults, so that
    /// earlier cache keys stay valid), for cache keys.
    pub(crate) fn content_hash(&self) -> u64 {
        let mut h = Fnv64::new();
        h.u32(self.width);
        h.u32(self.height);
        h.f32(self.fov_y_deg);
        h.f32(self.near);
        for d in &self.linear_depth {
            h.f32(*d);
        }
        if self.thickness != f32::INFINITY {
            h.bytes(b"thickness");
            h.f32(self.thickness);
        }
        if self.guard_band != 0 {
            h.bytes(b"guard band");
            h.u32(self.guard_band);
        }
        if let Some(back) = &self.back_depth {
            h.bytes(b"back faces");
            for d in back {
                h.f32(*d);
            }
        }
        if let Some(second) = &self.second_layer {
            h.bytes(b"second layer");
            for d in second {
                h.f32(*d);
            }
        }
        if let Some(back) = &self.second_back_depth {
            h.bytes(b"second layer's back faces");
            for d in back {
                h.f32(*d);
            }
        }
        match self.surface {
            Surface::Triangles => {}
            Surface::Patches => h.bytes(b"planar patches"),
            Surface::FlatPatches => h.bytes(b"flat patches"),
        }
        if let Some(normals) = &self.normals {
            h.bytes(b"surface normals");
            for n in normals.iter().flatten() {
                h.f32(*n);
            }
        }
        h.0
    }
}
