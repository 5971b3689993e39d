//! What a reference render computes: the AO quantity and the sampling parameters.

/// Which AO quantity to compute (see the `trace` module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum AoVariant {
    /// Binary visibility within `radius`.
    #[default]
    Visibility,
    /// Ambient obscurance with falloff `(t / radius)^2` clamped to [0, 1].
    Obscurance,
}

/// Render parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefParams {
    /// AO radius in metres. `f32::INFINITY` is allowed (any hit occludes fully). A radius
    /// that is not > 0 (including NaN) means nothing can occlude: ao = 1.
    pub radius: f32,
    /// Rays per pixel; 0 is treated as 1.
    pub rays: u32,
    /// Visibility or obscurance.
    pub variant: AoVariant,
    /// Base seed; each pixel derives its own generator from it and its index.
    pub seed: u64,
    /// Show an indicatif progress bar (rows) on stderr. Nothing is printed when false.
    pub progress: bool,
    /// Each pixel is the mean over its footprint: N×N sub-pixel centres (those of an image N times
    /// wider and taller), each with `rays / N²` rays rounded up. What a render N times larger,
    /// box-averaged by N, estimates: the bench's `--ref-scale N` protocol. 1 (or 0): the centre.
    pub supersample: u32,
}

impl Default for RefParams {
    fn default() -> Self {
        RefParams {
            radius: 1.0,
            rays: 256,
            variant: AoVariant::Visibility,
            seed: 0,
            progress: false,
            supersample: 1,
        }
    }
}

impl RefParams {
    /// One sub-pixel of a footprint: its share of the rays (`rays / supersample²`, rounded up),
    /// traced at its centre.
    pub fn sub_pixel(&self) -> RefParams {
        let n = self.supersample.max(1);
        RefParams {
            rays: self.rays.max(1).div_ceil(n * n),
            supersample: 1,
            ..*self
        }
    }
}
