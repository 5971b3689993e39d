//! The depth buffer as geometry: a heightfield of infinite thickness, or slabs of finite thickness,
//! and the exact test of whether a ray segment passes through it (see `screen.rs` for the surface,
//! the normals and the march).
//!
//! **Slabs.** With a finite thickness T, the solid at a screen point is the interval of linear
//! depth [z(x), z(x) + T] behind the front surface z(x) (the same triangulated surface as the
//! heightfield's), along that point's camera ray: the model `vbao` uses for each depth sample. Each
//! triangle of the surface is solid only where its three pixels' slabs overlap, that is when their
//! depths differ by at most T; otherwise nothing joins them (a silhouette, or a wall seen so edge-on
//! that neighbouring pixels are more than T apart) and the triangle is empty, so a ray can pass
//! behind a thin foreground object. With T = ∞ every triangle is solid and every point behind the
//! surface blocked: the heightfield, marched by the original code path so that its output does not
//! change. Along one march segment (inside one triangle) the ray's and the surface's inverse depths
//! are affine, so "behind the front" is an affine inequality and "within T of it"
//! (1/w_ray − 1/w_surface ≤ T, times both) a quadratic one: their roots split the segment into
//! pieces of constant sign, and testing each piece decides the segment exactly.
//!
//! **Back faces.** With each pixel's back depth b (the nearest back face behind it, `vbao`'s
//! `--thickness backface`), the pixel's slab is [z, max(b, z + T)]: the back face extends a slab,
//! never thins it below the set thickness (a tap stands for the texels up to the next one, which a
//! back face a few centimetres behind one texel says nothing about); a pixel without one (an open
//! plane) keeps [z, z + T], as `vbao` does. The back surface is triangulated like the
//! front, with inverse depth affine in each triangle (a planar back face is rebuilt exactly), and a
//! triangle is solid where its three pixels' slabs overlap (deepest front ≤ shallowest back; with
//! one thickness everywhere that is the rule above). Inside it a point is solid when it lies behind
//! the front and in front of the back: two affine inequalities, decided exactly the same way. A
//! triangle none of whose pixels has a back face is the fixed-thickness slab above, unchanged.

use glam::DVec3;

use super::depth_buffer::{DepthBuffer, Surface};
use super::patches::Patches;

/// Inverse depths of the buffer and its projection, in f64.
pub(crate) struct Heightfield {
    pub(crate) w: usize,
    pub(crate) h: usize,
    /// 1 / depth per pixel (rows top-down); 0 for sky (a surface at infinity blocks nothing).
    inv: Vec<f64>,
    /// tan(fov/2) · aspect and tan(fov/2): view-space x/−z and y/−z at the image edges.
    sx: f64,
    sy: f64,
    pub(crate) near: f64,
    /// Thickness of every surface in linear depth (m); `f64::INFINITY` for the heightfield. With
    /// `back`: that of the pixels without a back face.
    thickness: f64,
    /// Each pixel's back surface, when the buffer has back faces (module docs).
    back: Option<BackSurface>,
    /// Each pixel's own normal (view space), when the buffer carries the surface normals.
    normals: Option<Vec<DVec3>>,
    /// Distance from the eye beyond which no solid point lies (for unbounded rays).
    max_dist: f64,
    /// Each pixel's plane, for [`Surface::Patches`]; `None`: the triangulated surface.
    patches: Option<Patches>,
    /// Grid coordinates covered by the surface: pixel centres for the triangles, whole pixels for
    /// the patches.
    lo: f64,
    hi: (f64, f64),
}

impl Heightfield {
    pub(crate) fn new(buf: &DepthBuffer) -> Heightfield {
        let (w, h) = (buf.width as usize, buf.height as usize);
        let sy = (buf.fov_y_deg as f64).to_radians() * 0.5;
        let sy = sy.tan();
        let sx = sy * w as f64 / h.max(1) as f64;
        let inv: Vec<f64> = buf
            .linear_depth
            .iter()
            .map(|&d| {
                if d.is_finite() && d > 0.0 {
                    1.0 / d as f64
                } else {
                    0.0
                }
            })
            .collect();
        let max_depth = buf
            .linear_depth
            .iter()
            .filter(|d| d.is_finite() && **d > 0.0)
            .fold(0.0f64, |m, d| m.max(*d as f64));
        let thickness = buf.thickness as f64;
        let patched = matches!(buf.surface, Surface::Patches | Surface::FlatPatches);
        let flat = buf.surface == Surface::FlatPatches;
        let back = buf
            .back_depth
            .as_ref()
            .map(|b| BackSurface::new(&buf.linear_depth, b, thickness, patched));
        // With back faces, the deepest solid point is the deepest back (a fallback slab's included).
        let max_depth = match &back {
            Some(b) => max_depth.max(b.max_depth),
            None => max_depth,
        };
        // An on-screen point at distance ℓ from the eye has a depth of at least ℓ / k.
        let k = (1.0 + sx * sx + sy * sy).sqrt();
        // A patch's corners reach 1 / (1 − MAX_CORNER_CHANGE) times its centre's depth.
        let k = if patched {
            k / (1.0 - super::patches::MAX_CORNER_CHANGE)
        } else {
            k
        };
        let lo = if patched { -0.5 } else { 0.0 };
        let mut field = Heightfield {
            w,
            h,
            inv,
            sx,
            sy,
            near: buf.near as f64,
            thickness,
            max_dist: if thickness.is_finite() || back.is_some() {
                (max_depth + thickness) * k
            } else {
                max_depth * k
            },
            back,
            normals: buf.normals.as_ref().map(|ns| {
                ns.iter()
                    .map(|n| DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64))
                    .collect()
            }),
            patches: None,
            lo,
            hi: ((w as f64 - 1.0) - lo, (h as f64 - 1.0) - lo),
        };
        if patched {
            let f = &field;
            let patches = Patches::new(
                (w, h),
                (sx, sy),
                &f.inv,
                |i, j| f.point(i, j),
                |i, j, p| f.normal(i, j, p),
                flat,
            );
            // The back's inverse depth over the front's at each pixel (as `blocked_by_patches`
            // scales the front to its back): the measured back face, else the set thickness.
            let back_ratio = |k: usize| -> f64 {
                let front = f.inv[k];
                match &f.back {
                    Some(b) if b.measured[k] => b.inv[k] / front,
                    _ if f.thickness.is_finite() => 1.0 / (1.0 + f.thickness * front),
                    _ => 0.0,
                }
            };
            let patches = if flat {
                patches
            } else {
                patches.with_convex_edges(back_ratio)
            };
            field.patches = Some(patches);
        }
        field
    }

    #[inline]
    pub(crate) fn inv_at(&self, i: usize, j: usize) -> f64 {
        self.inv[j * self.w + i]
    }

    /// View-space position of pixel (i, j)'s centre; `None` for sky.
    pub(crate) fn point(&self, i: usize, j: usize) -> Option<DVec3> {
        let inv = self.inv_at(i, j);
        if inv <= 0.0 {
            return None;
        }
        let ndc_x = 2.0 * (i as f64 + 0.5) / self.w as f64 - 1.0;
        let ndc_y = 1.0 - 2.0 * (j as f64 + 0.5) / self.h as f64;
        Some(DVec3::new(ndc_x * self.sx, ndc_y * self.sy, -1.0) / inv)
    }

    /// Grid coordinates (pixel centre (i, j) at (i, j)) and inverse depth of a view-space point
    /// in front of the camera.
    #[inline]
    fn project(&self, q: DVec3) -> (f64, f64, f64) {
        let inv = 1.0 / -q.z;
        let ndc_x = q.x * inv / self.sx;
        let ndc_y = q.y * inv / self.sy;
        (
            (ndc_x + 1.0) * 0.5 * self.w as f64 - 0.5,
            (1.0 - ndc_y) * 0.5 * self.h as f64 - 0.5,
            inv,
        )
    }

    /// Inverse depth of the triangulated surface at grid point (x, y), inside [0, w−1]×[0, h−1].
    #[inline]
    fn surface(&self, x: f64, y: f64) -> f64 {
        self.interpolate(&self.inv, x, y)
    }

    /// Per-pixel `values` interpolated linearly over the triangle holding grid point (x, y).
    #[inline]
    fn interpolate(&self, values: &[f64], x: f64, y: f64) -> f64 {
        let i = (x.floor() as isize).clamp(0, self.w as isize - 2) as usize;
        let j = (y.floor() as isize).clamp(0, self.h as isize - 2) as usize;
        let (fx, fy) = (x - i as f64, y - j as f64);
        let at = |i: usize, j: usize| values[j * self.w + i];
        let a = at(i, j);
        let d = at(i + 1, j + 1);
        if fx >= fy {
            let b = at(i + 1, j);
            a + fx * (b - a) + fy * (d - b)
        } else {
            let c = at(i, j + 1);
            a + fy * (c - a) + fx * (d - c)
        }
    }

    /// Error of predicting pixel k's inverse depth from the next two pixels in direction `step`
    /// along one axis (`None` if the neighbour is missing or sky; large if only one exists).
    fn side_error(&self, at: &dyn Fn(isize) -> Option<f64>, step: isize) -> Option<f64> {
        let c = at(0)?;
        let n1 = at(step)?;
        Some(match at(2 * step) {
            Some(n2) => (c - (2.0 * n1 - n2)).abs(),
            None => f64::MAX,
        })
    }

    /// Unit normal at pixel (i, j), facing the camera: the surface's own when the buffer carries
    /// normals, else rebuilt from the depth buffer (see the module docs).
    pub(crate) fn normal(&self, i: usize, j: usize, p: DVec3) -> DVec3 {
        let facing = -p.normalize_or(DVec3::Z);
        if let Some(normals) = &self.normals {
            // The surface's own normal, turned towards the camera as the ray tracer turns its hit.
            return match normals[j * self.w + i].try_normalize() {
                Some(n) if n.dot(facing) < 0.0 => -n,
                Some(n) => n,
                None => facing,
            };
        }
        let tangent = |horizontal: bool| -> Option<DVec3> {
            let at = |k: isize| -> Option<f64> {
                let (x, y) = if horizontal {
                    (i as isize + k, j as isize)
                } else {
                    (i as isize, j as isize + k)
                };
                if x < 0 || y < 0 || x >= self.w as isize || y >= self.h as isize {
                    return None;
                }
                let v = self.inv_at(x as usize, y as usize);
                (v > 0.0).then_some(v)
            };
            let fwd = self.side_error(&at, 1);
            let back = self.side_error(&at, -1);
            let use_fwd = match (fwd, back) {
                (Some(f), Some(b)) => f <= b,
                (Some(_), None) => true,
                (None, Some(_)) => false,
                (None, None) => return None,
            };
            let (x, y) = match (horizontal, use_fwd) {
                (true, true) => (i + 1, j),
                (true, false) => (i - 1, j),
                (false, true) => (i, j + 1),
                (false, false) => (i, j - 1),
            };
            let q = self.point(x, y)?;
            Some(if use_fwd { q - p } else { p - q })
        };
        let n = match (tangent(true), tangent(false)) {
            (Some(tx), Some(ty)) => tx.cross(ty).try_normalize(),
            _ => None,
        };
        match n {
            Some(n) if n.dot(facing) < 0.0 => -n,
            Some(n) => n,
            // A pixel without usable neighbours on an axis: assume it faces the camera.
            None => facing,
        }
    }

    /// Whether the segment `o + t·d`, t in (0, t_max], passes through the solid (see the module
    /// docs). `d` is a unit vector, `o` lies in front of the near plane.
    pub(crate) fn blocked(&self, o: DVec3, d: DVec3, t_max: f64) -> bool {
        let Some(seg) = self.clip(o, d, t_max) else {
            return false;
        };
        if let Some(patches) = &self.patches {
            self.blocked_by_patches(&seg, patches)
        } else if self.thickness.is_finite() || self.back.is_some() {
            self.blocked_by_slabs(&seg)
        } else {
            self.blocked_by_heightfield(&seg)
        }
    }

    /// The segment in grid coordinates, clipped to the near plane and the grid; `None` when
    /// nothing of it is left.
    fn clip(&self, o: DVec3, d: DVec3, t_max: f64) -> Option<GridSegment> {
        if self.patches.is_none() && (self.w < 2 || self.h < 2) {
            return None; // no cell between pixel centres: no surface to pass behind
        }
        // Beyond max_dist + |o| from o, every point is deeper than any solid point, so the first
        // crossing (if any) happened before: the cap loses nothing.
        let mut t1 = t_max.min(2.0 * (self.max_dist + o.length()));
        let near_z = -self.near;
        if d.z > 0.0 {
            t1 = t1.min((near_z - o.z) / d.z);
        }
        if t1.is_nan() || t1 <= 0.0 || o.z > near_z {
            return None;
        }
        let (ax, ay, aw) = self.project(o);
        let (bx, by, bw) = self.project(o + d * t1);
        let (dx, dy, dw) = (bx - ax, by - ay, bw - aw);
        // Clip s in [0, 1] to the grid [lo, hi.0] × [lo, hi.1].
        let (mut s0, mut s1) = (0.0f64, 1.0f64);
        let lo = self.lo;
        for (start, delta, hi) in [(ax, dx, self.hi.0), (ay, dy, self.hi.1)] {
            if delta == 0.0 {
                if start < lo || start > hi {
                    return None;
                }
                continue;
            }
            let (ta, tb) = ((lo - start) / delta, (hi - start) / delta);
            s0 = s0.max(ta.min(tb));
            s1 = s1.min(ta.max(tb));
        }
        if s0.is_nan() || s1.is_nan() || s0 > s1 {
            return None;
        }
        Some(GridSegment {
            ax,
            ay,
            aw,
            dx,
            dy,
            dw,
            s0,
            s1,
        })
    }

    /// Grid point of the segment at s, clamped to the grid.
    #[inline]
    fn grid_at(&self, seg: &GridSegment, s: f64) -> (f64, f64) {
        (
            (seg.ax + s * seg.dx).clamp(self.lo, self.hi.0),
            (seg.ay + s * seg.dy).clamp(self.lo, self.hi.1),
        )
    }

    /// Calls `visit` with every s in (s0, s1) where the segment crosses a cell edge (x = integer,
    /// y = integer, x − y = integer), in increasing order, until it returns true; then returns
    /// whether it did.
    fn any_edge_crossing(seg: &GridSegment, visit: impl FnMut(f64) -> bool) -> bool {
        let families = [
            EdgeFamily::new(seg.ax, seg.dx, seg.s0),
            EdgeFamily::new(seg.ay, seg.dy, seg.s0),
            EdgeFamily::new(seg.ax - seg.ay, seg.dx - seg.dy, seg.s0),
        ];
        Self::any_crossing(seg, families, visit)
    }

    /// Like [`Self::any_edge_crossing`] for the crossings of `families` (each gives evenly spaced
    /// s; they are merged in increasing order).
    fn any_crossing<const N: usize>(
        seg: &GridSegment,
        mut families: [EdgeFamily; N],
        mut visit: impl FnMut(f64) -> bool,
    ) -> bool {
        loop {
            let (k, s) = families
                .iter()
                .enumerate()
                .map(|(k, f)| (k, f.next_s))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            if s.is_nan() || seg.s1.is_nan() || s >= seg.s1 {
                return false;
            }
            if visit(s) {
                return true;
            }
            families[k].advance();
        }
    }

    /// Infinite thickness: along the segment both inverse depths are piecewise affine with breaks
    /// only at cell edges, so comparing them at the edges and the two ends decides exactly whether
    /// the ray passes behind the surface.
    fn blocked_by_heightfield(&self, seg: &GridSegment) -> bool {
        let behind = |s: f64| -> bool {
            let (x, y) = self.grid_at(seg, s);
            seg.aw + s * seg.dw < self.surface(x, y)
        };
        behind(seg.s0) || Self::any_edge_crossing(seg, behind) || behind(seg.s1)
    }

    /// Finite thickness: each piece between consecutive cell-edge crossings lies in one triangle;
    /// it is tested against that triangle's slab (module docs).
    fn blocked_by_slabs(&self, seg: &GridSegment) -> bool {
        let surface_at = |s: f64| {
            let (x, y) = self.grid_at(seg, s);
            self.surface(x, y)
        };
        let mut prev = (seg.s0, surface_at(seg.s0));
        let mut piece = |s: f64| -> bool {
            let f = surface_at(s);
            let hit = self.piece_in_slab(seg, prev, (s, f));
            prev = (s, f);
            hit
        };
        Self::any_edge_crossing(seg, &mut piece) || piece(seg.s1)
    }

    /// Whether the piece of the segment from s = a.0 to b.0 (surface inverse depths a.1, b.1 at
    /// its ends, inside one triangle) passes through that triangle's slab.
    fn piece_in_slab(&self, seg: &GridSegment, a: (f64, f64), b: (f64, f64)) -> bool {
        let corners = self.triangle_at(self.grid_at(seg, 0.5 * (a.0 + b.0)));
        if !self.triangle_is_solid(corners) {
            return false;
        }
        let back = self.back.as_ref().and_then(|back| {
            corners
                .iter()
                .any(|&(i, j)| back.measured[j * self.w + i])
                .then(|| {
                    (
                        back.at_grid(self, self.grid_at(seg, a.0)),
                        back.at_grid(self, self.grid_at(seg, b.0)),
                    )
                })
        });
        self.piece_through(seg, a, b, back)
    }

    /// Planar patches: each piece between consecutive pixel-boundary crossings lies in one pixel's
    /// footprint and is tested against that pixel's slab, from its plane to its back face (the
    /// back plane: the front's depths scaled by the pixel's back-to-front ratio), or the thickness.
    fn blocked_by_patches(&self, seg: &GridSegment, patches: &Patches) -> bool {
        // Footprint edges, and the centre lines between a footprint's quadrants (each may take a
        // neighbour's plane at a convex edge: `Patches::with_convex_edges`).
        let families = [
            EdgeFamily::new(seg.ax - 0.5, seg.dx, seg.s0),
            EdgeFamily::new(seg.ay - 0.5, seg.dy, seg.s0),
            EdgeFamily::new(seg.ax, seg.dx, seg.s0),
            EdgeFamily::new(seg.ay, seg.dy, seg.s0),
        ];
        let mut prev = seg.s0;
        let mut piece = |s: f64| -> bool {
            let (a, b) = (prev, s);
            prev = s;
            let (mx, my) = self.grid_at(seg, 0.5 * (a + b));
            let i = (mx.round().max(0.0) as usize).min(self.w - 1);
            let j = (my.round().max(0.0) as usize).min(self.h - 1);
            let k = j * self.w + i;
            if self.inv[k] <= 0.0 {
                return false; // sky
            }
            let (ga, gb) = (self.grid_at(seg, a), self.grid_at(seg, b));
            let q = super::patches::quadrant(i, j, (mx, my));
            let (own_a, theirs_a) = patches.planes_in_quadrant(i, j, q, ga);
            let (own_b, theirs_b) = patches.planes_in_quadrant(i, j, q, gb);
            let ratio = self
                .back
                .as_ref()
                .filter(|back| back.measured[k])
                .map(|back| back.inv[k] / self.inv[k]);
            let through = |(a, fa): (f64, f64), (b, fb): (f64, f64)| {
                let back = ratio.map(|r| (fa * r, fb * r));
                self.piece_through(seg, (a, fa), (b, fb), back)
            };
            let (Some(ta), Some(tb)) = (theirs_a, theirs_b) else {
                return through((a, own_a), (b, own_b));
            };
            // The farther of two affine functions: affine on each side of where they cross.
            let (da, db) = (own_a - ta, own_b - tb);
            if da * db >= 0.0 {
                let use_own = da + db <= 0.0;
                let (fa, fb) = if use_own { (own_a, own_b) } else { (ta, tb) };
                return through((a, fa), (b, fb));
            }
            let u = da / (da - db);
            let s = a + (b - a) * u;
            let f = own_a + (own_b - own_a) * u;
            through((a, own_a.min(ta)), (s, f)) || through((s, f), (b, own_b.min(tb)))
        };
        Self::any_crossing(seg, families, &mut piece) || piece(seg.s1)
    }

    /// Whether the piece from s = a.0 to b.0, whose surface's inverse depths at the ends are a.1
    /// and b.1 (affine between), passes behind the surface and in front of its back: the back
    /// surface's inverse depths at the ends, or the thickness where `back` is `None`.
    fn piece_through(
        &self,
        seg: &GridSegment,
        a: (f64, f64),
        b: (f64, f64),
        back: Option<(f64, f64)>,
    ) -> bool {
        let (ra, rb) = (seg.aw + a.0 * seg.dw, seg.aw + b.0 * seg.dw);
        if let Some((ga, gb)) = back {
            return piece_between(a.1 - ra, b.1 - rb, ra - ga, rb - gb);
        }
        let t = self.thickness;
        if t.is_infinite() {
            // No back face and infinitely thick: solid wherever it is behind the front.
            return piece_between(a.1 - ra, b.1 - rb, 1.0, 1.0);
        }
        let (fa, df, dr) = (a.1, b.1 - a.1, rb - ra);
        // u in [0, 1] along the piece: front(u) = f − r > 0 (behind the surface) and
        // within(u) = T·r·f − (f − r) >= 0 (less than T behind it).
        let (a0, a1) = (fa - ra, df - dr);
        let (c2, c1, c0) = (t * dr * df, t * (ra * df + fa * dr) - a1, t * ra * fa - a0);
        let inside = |u: f64| -> bool {
            let front = a0 + u * a1;
            let within = (c2 * u + c1) * u + c0;
            front > 0.0 && within >= 0.0
        };
        let mut cuts = [0.0f64, 1.0, f64::NAN, f64::NAN, f64::NAN];
        if a1 != 0.0 {
            cuts[2] = -a0 / a1;
        }
        let (r1, r2) = quadratic_roots(c2, c1, c0);
        cuts[3] = r1;
        cuts[4] = r2;
        let mut cuts: Vec<f64> = cuts
            .into_iter()
            .filter(|u| (0.0..=1.0).contains(u))
            .collect();
        cuts.sort_by(f64::total_cmp);
        cuts.iter().any(|&u| inside(u)) || cuts.windows(2).any(|p| inside(0.5 * (p[0] + p[1])))
    }

    /// The three pixels of the triangle holding grid point (x, y) (the split of `surface`).
    fn triangle_at(&self, (x, y): (f64, f64)) -> [(usize, usize); 3] {
        let i = (x.floor() as isize).clamp(0, self.w as isize - 2) as usize;
        let j = (y.floor() as isize).clamp(0, self.h as isize - 2) as usize;
        let third = if x - i as f64 >= y - j as f64 {
            (i + 1, j)
        } else {
            (i, j + 1)
        };
        [(i, j), (i + 1, j + 1), third]
    }

    /// Whether a triangle is solid: its three pixels are surface and their slabs overlap (with one
    /// thickness: their depths lie within it of each other; module docs).
    pub(crate) fn triangle_is_solid(&self, corners: [(usize, usize); 3]) -> bool {
        let inv = corners.map(|(i, j)| self.inv_at(i, j));
        if inv.iter().any(|w| *w <= 0.0) {
            return false; // sky: no slab
        }
        let depth = inv.map(|w| 1.0 / w);
        let (lo, hi) = depth.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), z| {
            (lo.min(*z), hi.max(*z))
        });
        match &self.back {
            Some(back) => {
                let shallowest_back = corners
                    .iter()
                    .map(|&(i, j)| back.depth_at(self.w, i, j))
                    .fold(f64::INFINITY, f64::min);
                hi <= shallowest_back
            }
            None => hi - lo <= self.thickness,
        }
    }
}

/// Whether u in [0, 1] exists where both affine functions (given at u = 0 and u = 1) satisfy
/// front(u) > 0 and back(u) ≥ 0: the piece of a ray between a triangle's front (ray behind it) and
/// its back (ray in front of it), both in inverse depth.
fn piece_between(front0: f64, front1: f64, back0: f64, back1: f64) -> bool {
    let inside = |u: f64| -> bool {
        front0 + u * (front1 - front0) > 0.0 && back0 + u * (back1 - back0) >= 0.0
    };
    let root = |v0: f64, v1: f64| if v0 != v1 { v0 / (v0 - v1) } else { f64::NAN };
    let mut cuts: Vec<f64> = [0.0, 1.0, root(front0, front1), root(back0, back1)]
        .into_iter()
        .filter(|u| (0.0..=1.0).contains(u))
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.iter().any(|&u| inside(u)) || cuts.windows(2).any(|p| inside(0.5 * (p[0] + p[1])))
}

/// Each pixel's back surface: inverse depth of the back face behind it, or of its surface plus the
/// thickness where it has none (module docs).
struct BackSurface {
    inv: Vec<f64>,
    /// Whether the pixel has a back face behind it (else its slab has the set thickness).
    measured: Vec<bool>,
    /// Deepest back over the surface pixels (m).
    max_depth: f64,
}

impl BackSurface {
    /// `exact`: a back face is the slab's end however close (the planar patches); else never
    /// closer than `thickness` (the triangles, as `vbao`).
    fn new(front: &[f32], back: &[f32], thickness: f64, exact: bool) -> BackSurface {
        let mut max_depth = 0.0f64;
        let (inv, measured) = front
            .iter()
            .zip(back)
            .map(|(&z, &b)| {
                if !(z.is_finite() && z > 0.0) {
                    return (0.0, false); // sky: never in a solid triangle
                }
                // The same rule as vbao.frag: a back face deeper than the surface extends the slab to
                // it, never below the set thickness; without one, the thickness.
                let has_back = b.is_finite() && b > z;
                let depth = if has_back && exact {
                    b as f64
                } else if has_back {
                    (b as f64).max(z as f64 + thickness)
                } else {
                    z as f64 + thickness
                };
                max_depth = max_depth.max(depth);
                (1.0 / depth, has_back)
            })
            .unzip();
        BackSurface {
            inv,
            measured,
            max_depth,
        }
    }

    /// Depth (m) of pixel (i, j)'s back (infinite where it is infinitely thick).
    fn depth_at(&self, w: usize, i: usize, j: usize) -> f64 {
        1.0 / self.inv[j * w + i]
    }

    /// Inverse depth of the back surface at grid point (x, y).
    fn at_grid(&self, field: &Heightfield, (x, y): (f64, f64)) -> f64 {
        field.interpolate(&self.inv, x, y)
    }
}

/// A ray segment in grid coordinates: point (ax, ay) at inverse depth aw plus s·(dx, dy, dw), with
/// s in [s0, s1] inside the grid.
struct GridSegment {
    ax: f64,
    ay: f64,
    aw: f64,
    dx: f64,
    dy: f64,
    dw: f64,
    s0: f64,
    s1: f64,
}

/// Real roots of c2·u² + c1·u + c0 (NaN where there is none), without cancellation.
fn quadratic_roots(c2: f64, c1: f64, c0: f64) -> (f64, f64) {
    if c2 == 0.0 {
        return (if c1 != 0.0 { -c0 / c1 } else { f64::NAN }, f64::NAN);
    }
    let disc = c1 * c1 - 4.0 * c2 * c0;
    if disc.is_nan() || disc < 0.0 {
        return (f64::NAN, f64::NAN);
    }
    let q = -0.5 * (c1 + disc.sqrt().copysign(c1));
    (q / c2, if q != 0.0 { c0 / q } else { f64::NAN })
}

/// The crossings of `u(s) = u0 + s·du` with the integers, in increasing s from `s_from`.
pub(crate) struct EdgeFamily {
    u0: f64,
    du: f64,
    /// Next integer to cross.
    k: f64,
    pub(crate) next_s: f64,
}

impl EdgeFamily {
    pub(crate) fn new(u0: f64, du: f64, s_from: f64) -> EdgeFamily {
        if du == 0.0 || !du.is_finite() {
            return EdgeFamily {
                u0,
                du,
                k: 0.0,
                next_s: f64::INFINITY,
            };
        }
        let u = u0 + s_from * du;
        let k = if du > 0.0 {
            u.floor() + 1.0
        } else {
            u.ceil() - 1.0
        };
        EdgeFamily {
            u0,
            du,
            k,
            next_s: (k - u0) / du,
        }
    }

    pub(crate) fn advance(&mut self) {
        self.k += self.du.signum();
        self.next_s = (self.k - self.u0) / self.du;
    }
}
