//! The planar-patch surface of the screen-space reference ([`super::Surface::Patches`]): each
//! pixel's square footprint holds the plane through its centre with its normal.
//!
//! A plane's inverse depth is affine in screen space, so each patch is three numbers (inverse depth
//! at the centre and its two slopes per pixel) and a ray piece inside one footprint compares two
//! affine functions, exactly as inside one triangle. A surface that is planar across pixels is
//! rebuilt exactly (no staircase for rays to start inside), silhouettes stay sharp (no triangle
//! bridges the foreground to the background, none is dropped at the edge of a thin object), and a
//! board seen edge-on stays solid however far apart its pixels' depths are.

use glam::DVec3;

/// Each pixel's plane as inverse depth: `[at the centre, per pixel along x, per pixel along y]`.
pub(crate) struct Patches {
    planes: Vec<[f64; 3]>,
    /// Per pixel and quadrant of its footprint (`quadrant`), whose plane covers it: `OWN`, or the
    /// horizontal (`ACROSS_X`) or vertical (`ACROSS_Y`) neighbour's on that side (`convex_edges`).
    covers: Vec<[u8; 4]>,
    w: usize,
    h: usize,
}

const OWN: u8 = 0;
const ACROSS_X: u8 = 1;
const ACROSS_Y: u8 = 2;

/// Quadrant of pixel (i, j)'s footprint holding grid point (x, y): bit 0 right of the centre,
/// bit 1 below it.
#[inline]
pub(crate) fn quadrant(i: usize, j: usize, (x, y): (f64, f64)) -> usize {
    (x >= i as f64) as usize | ((y >= j as f64) as usize) << 1
}

/// The largest change of inverse depth from a pixel's centre to a corner, as a fraction of the
/// centre's: a plane seen nearly edge-on would otherwise reach zero (a surface at infinity) or
/// behind the eye inside its own pixel. 0.9 keeps every corner between 0.1 and 1.9 times the
/// centre's inverse depth (depths from 0.53 to 10 times the centre's); a tighter bound cuts
/// grazing planes into steps that their own rays start behind.
pub(crate) const MAX_CORNER_CHANGE: f64 = 0.9;

impl Patches {
    /// `inv`: inverse depth per pixel (0 for sky, rows top-down); `sx`, `sy`: view-space x/−z and
    /// y/−z at the image edges; `point(i, j)`: the pixel centre in view space; `normal(i, j, p)`:
    /// its unit normal facing the camera; `flat`: every footprint at its centre's depth instead
    /// (the normals are not read).
    pub(crate) fn new(
        (w, h): (usize, usize),
        (sx, sy): (f64, f64),
        inv: &[f64],
        point: impl Fn(usize, usize) -> Option<DVec3>,
        normal: impl Fn(usize, usize, DVec3) -> DVec3,
        flat: bool,
    ) -> Patches {
        let mut planes = vec![[0.0; 3]; w * h];
        for j in 0..h {
            for i in 0..w {
                let k = j * w + i;
                let Some(p) = point(i, j) else {
                    continue; // sky: inverse depth 0, never solid
                };
                let centre = inv[k];
                if flat {
                    planes[k] = [centre, 0.0, 0.0];
                    continue;
                }
                let n = normal(i, j, p);
                // Points e(x)·d on the plane: n·(e d − p) = 0, so 1/d = n·e(x) / n·p, and e(x) moves
                // by (2 sx / w, −2 sy / h, 0) per pixel.
                let np = n.dot(p);
                let (mut gx, mut gy) = if np < -1e-12 * p.length() {
                    (
                        n.x * sx * 2.0 / w as f64 / np,
                        -n.y * sy * 2.0 / h as f64 / np,
                    )
                } else {
                    (0.0, 0.0) // seen exactly edge-on (or a normal facing away): flat
                };
                let corner = 0.5 * (gx.abs() + gy.abs());
                let limit = MAX_CORNER_CHANGE * centre;
                // NaN slopes (an odd normal) count as too steep.
                if corner.is_nan() || corner > limit {
                    let scale = if corner.is_finite() {
                        limit / corner
                    } else {
                        0.0
                    };
                    gx *= scale;
                    gy *= scale;
                }
                planes[k] = [centre, gx, gy];
            }
        }
        Patches {
            planes,
            covers: vec![[OWN; 4]; w * h],
            w,
            h,
        }
    }

    /// Convex edges: where a pixel's plane, carried over the half of its footprint towards a
    /// neighbour, comes nearer than that neighbour's plane while the neighbour's lies within this
    /// pixel's slab (in front of its back, `back_ratio(k)`: the back's inverse depth over the front's,
    /// 0 for none) or the neighbour's plane comes nearer than this pixel's centre (the two planes
    /// cross between the centre and the edge), the pixel's centre lies on a face that ends inside
    /// its footprint and the neighbour's face goes on there (the top of a wall seen from above,
    /// spread over the pixel below it, would stand in front of the wall's face and block its upward
    /// rays; seen nearly edge-on, the top's plane reaches far towards the eye, beyond the slab).
    /// There the surface is the farther of the two planes, as at a convex edge between two faces;
    /// it never comes nearer than the pixel's own. A neighbour behind the slab whose plane stays
    /// behind the centre is a silhouette and leaves the pixel's own plane alone (a thin board in
    /// front of a far wall stays whole).
    pub(crate) fn with_convex_edges(mut self, back_ratio: impl Fn(usize) -> f64) -> Patches {
        let (w, h) = (self.w, self.h);
        let mut covers = vec![[OWN; 4]; w * h];
        for j in 0..h {
            for i in 0..w {
                let k = j * w + i;
                if self.planes[k][0] <= 0.0 {
                    continue; // sky
                }
                let ratio = back_ratio(k);
                // Whether the neighbour at (ni, nj), met at the grid point b, is a face this
                // pixel's plane should give way to there.
                let gives_way = |ni: isize, nj: isize, b: (f64, f64)| -> bool {
                    if ni < 0 || nj < 0 || ni >= w as isize || nj >= h as isize {
                        return false;
                    }
                    let (ni, nj) = (ni as usize, nj as usize);
                    if self.planes[nj * w + ni][0] <= 0.0 {
                        return false; // sky
                    }
                    let own = self.inv_of(k, i, j, b);
                    let theirs = self.inv_of(nj * w + ni, ni, nj, b);
                    // Nearer at the edge, and either the neighbour lies in this slab there or its
                    // plane comes nearer than this one at this centre (the two cross in between).
                    let crosses = || {
                        self.inv_of(nj * w + ni, ni, nj, (i as f64, j as f64)) > self.planes[k][0]
                    };
                    own > theirs && (theirs >= own * ratio || crosses())
                };
                for (q, cover) in covers[k].iter_mut().enumerate() {
                    let sx: isize = if q & 1 == 1 { 1 } else { -1 };
                    let sy: isize = if q & 2 == 2 { 1 } else { -1 };
                    let (fi, fj) = (i as f64, j as f64);
                    let across_x =
                        gives_way(i as isize + sx, j as isize, (fi + 0.5 * sx as f64, fj));
                    let across_y =
                        gives_way(i as isize, j as isize + sy, (fi, fj + 0.5 * sy as f64));
                    let corner = (fi + 0.5 * sx as f64, fj + 0.5 * sy as f64);
                    let x_plane = || {
                        let ni = (i as isize + sx) as usize;
                        self.inv_of(j * w + ni, ni, j, corner)
                    };
                    let y_plane = || {
                        let nj = (j as isize + sy) as usize;
                        self.inv_of(nj * w + i, i, nj, corner)
                    };
                    *cover = match (across_x, across_y) {
                        (true, true) if x_plane() < y_plane() => ACROSS_X,
                        (_, true) => ACROSS_Y,
                        (true, false) => ACROSS_X,
                        (false, false) => OWN,
                    };
                }
            }
        }
        self.covers = covers;
        self
    }

    #[inline]
    fn inv_of(&self, k: usize, i: usize, j: usize, (x, y): (f64, f64)) -> f64 {
        let [c, gx, gy] = self.planes[k];
        c + gx * (x - i as f64) + gy * (y - j as f64)
    }

    /// Inverse depths at grid point (x, y) of pixel (i, j)'s own plane and, where quadrant `q` of
    /// its footprint (`quadrant`) meets a convex edge, of the neighbour's plane there: the surface
    /// in that quadrant is the farther of the two (the smaller inverse depth).
    #[inline]
    pub(crate) fn planes_in_quadrant(
        &self,
        i: usize,
        j: usize,
        q: usize,
        p: (f64, f64),
    ) -> (f64, Option<f64>) {
        let k = j * self.w + i;
        let own = self.inv_of(k, i, j, p);
        let theirs = match self.covers[k][q] {
            ACROSS_X => {
                let ni = if q & 1 == 1 { i + 1 } else { i - 1 };
                Some(self.inv_of(j * self.w + ni, ni, j, p))
            }
            ACROSS_Y => {
                let nj = if q & 2 == 2 { j + 1 } else { j - 1 };
                Some(self.inv_of(nj * self.w + i, i, nj, p))
            }
            _ => None,
        };
        (own, theirs)
    }

    /// Inverse depth of pixel (i, j)'s own plane at grid point (x, y) (pixel centres at integers).
    #[cfg(test)]
    pub(crate) fn inv_at(&self, i: usize, j: usize, (x, y): (f64, f64)) -> f64 {
        let [c, gx, gy] = self.planes[j * self.w + i];
        c + gx * (x - i as f64) + gy * (y - j as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tilted plane seen by a 8×6 buffer: each patch reproduces the plane's inverse depth at its
    /// neighbours' centres (computed from the plane directly), so the patches join without steps.
    #[test]
    fn patches_of_a_plane_meet_at_their_neighbours_centres() {
        let (w, h) = (8usize, 6usize);
        let (sx, sy) = (0.8, 0.6);
        let n = DVec3::new(0.3, 0.5, 0.8).normalize();
        let on_plane = DVec3::new(0.0, 0.0, -4.0);
        // Depth of the plane along the ray through grid point (x, y).
        let depth = |x: f64, y: f64| {
            let e = DVec3::new(
                (2.0 * (x + 0.5) / w as f64 - 1.0) * sx,
                (1.0 - 2.0 * (y + 0.5) / h as f64) * sy,
                -1.0,
            );
            n.dot(on_plane) / n.dot(e)
        };
        let inv: Vec<f64> = (0..w * h)
            .map(|k| 1.0 / depth((k % w) as f64, (k / w) as f64))
            .collect();
        let point = |i: usize, j: usize| {
            let d = depth(i as f64, j as f64);
            Some(DVec3::new(
                (2.0 * (i as f64 + 0.5) / w as f64 - 1.0) * sx * d,
                (1.0 - 2.0 * (j as f64 + 0.5) / h as f64) * sy * d,
                -d,
            ))
        };
        let patches = Patches::new((w, h), (sx, sy), &inv, point, |_, _, _| n, false);
        for (i, j) in [(0, 0), (3, 2), (6, 4)] {
            for (x, y) in [(i + 1, j), (i, j + 1), (i + 1, j + 1)] {
                let want = 1.0 / depth(x as f64, y as f64);
                let got = patches.inv_at(i, j, (x as f64, y as f64));
                assert!((got - want).abs() < 1e-9 * want, "{got} vs {want}");
            }
        }
    }

    /// A plane seen edge-on keeps its corners within the documented range, and no patch is NaN.
    /// (The bound is 0.25 · (1 ± MAX_CORNER_CHANGE) at inverse depth 0.25.)
    #[test]
    fn edge_on_planes_stay_finite_and_bounded() {
        let inv = vec![0.25; 4];
        let point = |i: usize, j: usize| Some(DVec3::new(i as f64 * 0.1, j as f64 * 0.1, -4.0));
        let edge_on = |_: usize, _: usize, p: DVec3| p.cross(DVec3::Y).normalize();
        let patches = Patches::new((2, 2), (1.0, 1.0), &inv, point, edge_on, false);
        for corner in [(-0.5, -0.5), (0.5, 0.5), (-0.5, 0.5), (0.5, -0.5)] {
            let v = patches.inv_at(0, 0, corner);
            let (lo, hi) = (
                0.25 * (1.0 - MAX_CORNER_CHANGE),
                0.25 * (1.0 + MAX_CORNER_CHANGE),
            );
            assert!(
                v.is_finite() && (lo - 1e-12..=hi + 1e-12).contains(&v),
                "{v}"
            );
        }
    }
}
