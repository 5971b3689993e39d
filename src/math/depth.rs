//! The main depth buffer's convention: the course's (DEPTH_COMPONENT32, OpenGL's [-1, 1] clip depth,
//! cleared to 1, LEQUAL) or reversed-Z (DEPTH_COMPONENT32F, glClipControl ZERO_TO_ONE, near → 1 and
//! far → 0, cleared to 0, GEQUAL). Reversed-Z puts the float format's dense values near 0 where the
//! projection crowds distant depths, so far surfaces keep ~f32 relative precision (`bench --stress`,
//! lessons/appendix-c-numerics.md).

use glam::{Mat4, Vec4};
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub enum DepthMode {
    /// The course's DEPTH_COMPONENT32 with OpenGL's default clip depth.
    #[default]
    #[serde(rename = "d32")]
    D32,
    /// DEPTH_COMPONENT32F, reversed-Z (near → 1, far → 0) with glClipControl(LOWER_LEFT, ZERO_TO_ONE).
    #[serde(rename = "d32f-reversed")]
    D32fReversed,
}

impl DepthMode {
    pub const ALL: [DepthMode; 2] = [DepthMode::D32, DepthMode::D32fReversed];

    /// The mode called `name` (as in scene files and on the command line).
    pub fn from_name(name: &str) -> Option<DepthMode> {
        DepthMode::ALL.into_iter().find(|m| m.name() == name)
    }
    pub fn name(self) -> &'static str {
        match self {
            DepthMode::D32 => "d32",
            DepthMode::D32fReversed => "d32f-reversed",
        }
    }
    pub fn reversed(self) -> bool {
        self == DepthMode::D32fReversed
    }
    pub fn internal_format(self) -> u32 {
        match self {
            DepthMode::D32 => glow::DEPTH_COMPONENT32,
            DepthMode::D32fReversed => glow::DEPTH_COMPONENT32F,
        }
    }
    /// The depth buffer's value where nothing was drawn.
    pub fn clear_value(self) -> f32 {
        if self.reversed() {
            0.0
        } else {
            1.0
        }
    }
    /// Depth test that lets nearer (or equally near) fragments pass.
    pub fn nearer_or_equal(self) -> u32 {
        if self.reversed() {
            glow::GEQUAL
        } else {
            glow::LEQUAL
        }
    }
}

/// View distance (metres, f64) of a depth-buffer value `d` written with `mode`'s projection: the exact
/// inverse of `projection` (D32: OpenGL's [-1, 1] clip depth; reversed-Z: [0, 1], near → 1).
/// `d` at the cleared value (sky) gives `far`.
pub fn linearize(mode: DepthMode, d: f64, near: f64, far: f64) -> f64 {
    match mode {
        DepthMode::D32 => {
            let z_ndc = 2.0 * d - 1.0;
            2.0 * far * near / ((far + near) - z_ndc * (far - near))
        }
        DepthMode::D32fReversed if far.is_finite() => near * far / (d * (far - near) + near),
        DepthMode::D32fReversed => near / d.max(f64::MIN_POSITIVE),
    }
}

/// The depth-buffer value `mode`'s projection writes at view distance `z` (metres): the inverse of
/// `linearize`.
pub fn delinearize(mode: DepthMode, z: f64, near: f64, far: f64) -> f64 {
    match mode {
        DepthMode::D32 => {
            let z_ndc = ((far + near) - 2.0 * far * near / z) / (far - near);
            0.5 * z_ndc + 0.5
        }
        DepthMode::D32fReversed if far.is_finite() => near * (far - z) / (z * (far - near)),
        DepthMode::D32fReversed => near / z,
    }
}

/// Perspective projection for `mode`: the course's `perspective_rh_gl`, or its reversed-Z form for a
/// [0, 1] clip depth: z_clip / w_clip = n·(f − d) / (d·(f − n)) at view distance d (near → 1, far → 0;
/// with an infinite far plane, n / d). The z terms are computed in f64 so that f ≫ n loses nothing.
pub fn projection(mode: DepthMode, fov_y_deg: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let standard = glam::camera::rh::proj::opengl::perspective(
        fov_y_deg.to_radians(),
        aspect.max(1e-6),
        near,
        far,
    );
    if !mode.reversed() {
        return standard;
    }
    let (n, f) = (near as f64, far as f64);
    // z_clip = a·z_view + b with z_view = −d and w_clip = d.
    let (a, b) = if f.is_finite() {
        (n / (f - n), n * f / (f - n))
    } else {
        (0.0, n)
    };
    let mut m = standard;
    m.z_axis = Vec4::new(m.z_axis.x, m.z_axis.y, a as f32, m.z_axis.w);
    m.w_axis = Vec4::new(m.w_axis.x, m.w_axis.y, b as f32, m.w_axis.w);
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Window depth of a point at view distance d (clip z / w, [0, 1] range).
    fn window_depth(m: &Mat4, d: f32) -> f32 {
        let c = *m * Vec4::new(0.0, 0.0, -d, 1.0);
        c.z / c.w
    }

    #[test]
    fn reversed_projection_maps_near_to_one_and_far_to_zero() {
        let m = projection(DepthMode::D32fReversed, 60.0, 1.5, 0.35, 1000.0);
        assert!((window_depth(&m, 0.35) - 1.0).abs() < 1e-6);
        assert!(window_depth(&m, 1000.0).abs() < 1e-6);
        // Monotonic: farther is smaller.
        assert!(window_depth(&m, 10.0) > window_depth(&m, 11.0));
        // Independent formula n·(f − d) / (d·(f − n)).
        let (n, f, d) = (0.35f64, 1000.0f64, 40.0f64);
        let want = n * (f - d) / (d * (f - n));
        assert!((window_depth(&m, 40.0) as f64 - want).abs() < 1e-7);
        // x and y are the course's.
        let s = projection(DepthMode::D32, 60.0, 1.5, 0.35, 1000.0);
        assert_eq!(m.x_axis, s.x_axis);
        assert_eq!(m.y_axis, s.y_axis);
        let inf = projection(DepthMode::D32fReversed, 60.0, 1.5, 0.35, f32::INFINITY);
        assert!((window_depth(&inf, 0.7) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn linearize_inverts_the_projection_for_both_modes() {
        let (n, f) = (0.35f64, 1000.0f64);
        for mode in DepthMode::ALL {
            let m = projection(mode, 60.0, 1.5, n as f32, f as f32);
            for z in [0.35, 1.0, 7.5, 40.0, 999.0] {
                // Window depth from the matrix (D32 maps clip [-1, 1] to [0, 1]).
                let c = m * Vec4::new(0.0, 0.0, -z as f32, 1.0);
                let ndc = (c.z / c.w) as f64;
                let d = if mode.reversed() {
                    ndc
                } else {
                    0.5 * ndc + 0.5
                };
                let back = linearize(mode, d, n, f);
                assert!((back - z).abs() / z < 2e-4, "{mode:?} z {z}: got {back}");
                let exact = delinearize(mode, z, n, f);
                assert!((linearize(mode, exact, n, f) - z).abs() / z < 1e-9);
            }
            assert!((linearize(mode, mode.clear_value() as f64, n, f) - f).abs() < 1e-6);
        }
    }

    #[test]
    fn depth_mode_names_round_trip_through_toml() {
        #[derive(Deserialize)]
        struct T {
            depth: DepthMode,
        }
        let t: T = toml::from_str("depth = \"d32f-reversed\"").unwrap();
        assert_eq!(t.depth, DepthMode::D32fReversed);
        assert!(toml::from_str::<T>("depth = \"d24\"").is_err());
    }
}
