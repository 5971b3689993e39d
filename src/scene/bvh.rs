//! The scene's world-space triangles in a binary BVH laid out for shader storage buffers, the
//! structure `rtao` (and `reference --gpu`) traverse in GLSL. Built with obvhs's `Bvh2` (PLOC, Meister
//! and Bittner 2018), whose nodes already have the two-children-side-by-side form a short-stack
//! traversal wants; the triangles are reordered into leaf order so a leaf names a contiguous range.
//!
//! **std430 layout** (`Res/ao/rtao.frag` declares the same):
//!
//! ```text
//! struct BvhNode {      // 32 bytes, words:
//!   vec3 lo;  uint count;   // 0..2 box minimum, 3: triangles in a leaf (0 = inner node)
//!   vec3 hi;  uint first;   // 4..6 box maximum, 7: inner: first child (the second is first + 1);
//! };                        //                       leaf: first triangle
//! struct BvhTriangle {  // 48 bytes: v0, e1 = v1 - v0, e2 = v2 - v0, each a vec4 with w = 0
//!   vec4 v0; vec4 e1; vec4 e2;
//! };
//! ```
//!
//! Node 0 is the root. Triangles that cannot have a normal (a non-finite vertex, or an area that is
//! rounding noise next to the edges) are left out, as the CPU reference leaves them out
//! ([`usable_triangle`]).

use anyhow::{bail, Result};
use glam::{DVec3, Vec3};
use obvhs::{bvh2::builder::build_bvh2_from_tris, triangle::Triangle, BvhBuildParams};
use std::time::{Duration, Instant};

/// 32-bit words per node and per triangle in the storage buffers.
pub const NODE_WORDS: usize = 8;
pub const TRIANGLE_WORDS: usize = 12;

/// The traversal stack of the shader (`BVH_STACK` in `Res/ao/rtao.frag`): a BVH deeper than this
/// is refused at build time instead of being traversed wrongly.
pub const MAX_STACK: usize = 64;

/// Whether a triangle has a well-defined unit normal, and that normal (f64): the rule the CPU
/// reference and the GPU BVH share.
pub fn usable_triangle(t: &[Vec3; 3]) -> Option<DVec3> {
    if !t.iter().all(|v| v.is_finite()) {
        return None;
    }
    let v0 = t[0].as_dvec3();
    let e1 = t[1].as_dvec3() - v0;
    let e2 = t[2].as_dvec3() - v0;
    let c = e1.cross(e2);
    let len = c.length();
    // Relative test: a sliver whose cross product is tiny compared to its edges has a normal
    // dominated by rounding, so it is treated like a zero-area triangle.
    let scale = e1.length_squared().max(e2.length_squared());
    if !len.is_finite() || len <= 1e-12 * scale {
        return None;
    }
    Some(c / len)
}

/// What a BVH on the GPU costs (`render --stats`).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct BvhStats {
    pub triangles: usize,
    pub nodes: usize,
    pub depth: usize,
    /// Storage-buffer bytes (nodes and triangles).
    pub bytes: u64,
    /// CPU time of the last build (ms), and how many builds the scene needed so far.
    pub build_ms: f64,
    pub builds: u32,
}

/// One node as the shader sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatNode {
    pub lo: [f32; 3],
    pub hi: [f32; 3],
    /// Triangles in the leaf; 0 for an inner node.
    pub count: u32,
    /// Inner: first child; leaf: first triangle.
    pub first: u32,
}

/// The flattened BVH: nodes and triangles in leaf order, plus what it cost.
#[derive(Clone, Debug, Default)]
pub struct FlatBvh {
    pub nodes: Vec<FlatNode>,
    /// (v0, v1, v2) in leaf order.
    pub triangles: Vec<[Vec3; 3]>,
    /// Input triangles left out as unusable.
    pub skipped: usize,
    /// Deepest leaf (root = 0).
    pub depth: usize,
    pub build_time: Duration,
}

impl FlatBvh {
    /// Builds the BVH over `triangles` (world space). An empty or fully degenerate list gives an
    /// empty BVH, which every ray misses.
    pub fn build(triangles: &[[Vec3; 3]]) -> Result<FlatBvh> {
        let start = Instant::now();
        if triangles.len() >= u32::MAX as usize / 2 {
            bail!("too many triangles for the BVH: {}", triangles.len());
        }
        let kept: Vec<[Vec3; 3]> = triangles
            .iter()
            .filter(|t| usable_triangle(t).is_some())
            .copied()
            .collect();
        let skipped = triangles.len() - kept.len();
        if kept.is_empty() {
            return Ok(FlatBvh {
                skipped,
                build_time: start.elapsed(),
                ..Default::default()
            });
        }
        let tris: Vec<Triangle> = kept
            .iter()
            .map(|t| Triangle {
                v0: t[0].to_array().into(),
                v1: t[1].to_array().into(),
                v2: t[2].to_array().into(),
            })
            .collect();
        let bvh = build_bvh2_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let nodes: Vec<FlatNode> = bvh
            .nodes
            .iter()
            .map(|n| FlatNode {
                lo: n.aabb.min.to_array(),
                hi: n.aabb.max.to_array(),
                count: n.prim_count,
                first: n.first_index,
            })
            .collect();
        let triangles: Vec<[Vec3; 3]> = bvh
            .primitive_indices
            .iter()
            .map(|&i| kept[i as usize])
            .collect();
        let mut flat = FlatBvh {
            nodes,
            triangles,
            skipped,
            depth: 0,
            build_time: Duration::ZERO,
        };
        flat.depth = flat.check()?;
        if flat.depth >= MAX_STACK {
            bail!(
                "the scene's BVH is {} levels deep; the shader's stack holds {MAX_STACK}",
                flat.depth
            );
        }
        flat.build_time = start.elapsed();
        Ok(flat)
    }

    /// Walks the tree once: every index in range, every triangle in exactly one leaf. Returns the
    /// depth of the deepest leaf.
    fn check(&self) -> Result<usize> {
        let mut seen = vec![false; self.triangles.len()];
        let mut depth = 0;
        let mut stack = vec![(0usize, 0usize)];
        let mut visited = 0usize;
        while let Some((i, d)) = stack.pop() {
            visited += 1;
            if visited > self.nodes.len() {
                bail!("the BVH has a cycle");
            }
            let n = self
                .nodes
                .get(i)
                .ok_or_else(|| anyhow::anyhow!("BVH node {i} is out of range"))?;
            depth = depth.max(d);
            let first = n.first as usize;
            if n.count == 0 {
                if first + 1 >= self.nodes.len() {
                    bail!("BVH node {i} has children out of range");
                }
                stack.push((first, d + 1));
                stack.push((first + 1, d + 1));
            } else {
                for t in first..first + n.count as usize {
                    match seen.get_mut(t) {
                        Some(s) if !*s => *s = true,
                        _ => bail!("BVH leaf {i} names triangle {t} twice or out of range"),
                    }
                }
            }
        }
        if seen.iter().any(|s| !s) {
            bail!("the BVH leaves out some triangles");
        }
        Ok(depth)
    }

    /// The node buffer's words (std430 `BvhNode[]`).
    pub fn node_words(&self) -> Vec<u32> {
        let mut w = Vec::with_capacity(self.nodes.len() * NODE_WORDS);
        for n in &self.nodes {
            w.extend(n.lo.map(f32::to_bits));
            w.push(n.count);
            w.extend(n.hi.map(f32::to_bits));
            w.push(n.first);
        }
        w
    }

    /// The triangle buffer's words (std430 `BvhTriangle[]`).
    pub fn triangle_words(&self) -> Vec<u32> {
        let mut w = Vec::with_capacity(self.triangles.len() * TRIANGLE_WORDS);
        for t in &self.triangles {
            for v in [t[0], t[1] - t[0], t[2] - t[0]] {
                w.extend(v.to_array().map(f32::to_bits));
                w.push(0);
            }
        }
        w
    }

    /// Its size and build time (`builds` left at 0 for the owner to count).
    pub fn stats(&self) -> BvhStats {
        BvhStats {
            triangles: self.triangles.len(),
            nodes: self.nodes.len(),
            depth: self.depth,
            bytes: self.gpu_bytes(),
            build_ms: self.build_time.as_secs_f64() * 1e3,
            builds: 0,
        }
    }

    /// Bytes the two buffers take on the GPU.
    pub fn gpu_bytes(&self) -> u64 {
        4 * (self.nodes.len() * NODE_WORDS + self.triangles.len() * TRIANGLE_WORDS) as u64
    }

    /// Any hit within `[0, t_max]` along unit `dir`: the shader's traversal on the CPU, over the same
    /// flattened data (for tests of the layout and of the GLSL).
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let inv = safe_recip(dir);
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let n = &self.nodes[i];
            if !box_hit(n, origin, inv, t_max) {
                continue;
            }
            let first = n.first as usize;
            if n.count == 0 {
                stack.push(first);
                stack.push(first + 1);
            } else if self.triangles[first..first + n.count as usize]
                .iter()
                .any(|t| triangle_hit(t, origin, dir, t_max))
            {
                return true;
            }
        }
        false
    }
}

/// 1/d with zero components replaced by a tiny value of their sign: the slab test then never
/// computes 0 × inf (the shader does the same).
pub fn safe_recip(d: Vec3) -> Vec3 {
    d.map(|c| {
        if c.abs() < 1e-20 {
            1e-20f32.copysign(c)
        } else {
            c
        }
    })
    .recip()
}

fn box_hit(n: &FlatNode, o: Vec3, inv: Vec3, t_max: f32) -> bool {
    let t0 = (Vec3::from(n.lo) - o) * inv;
    let t1 = (Vec3::from(n.hi) - o) * inv;
    let near = t0.min(t1).max_element().max(0.0);
    let far = t0.max(t1).min_element().min(t_max);
    near <= far
}

/// Möller–Trumbore in f32 with the shader's edge tolerance.
fn triangle_hit(t: &[Vec3; 3], o: Vec3, d: Vec3, t_max: f32) -> bool {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return false;
    }
    let inv = 1.0 / det;
    let s = o - t[0];
    let u = s.dot(p) * inv;
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    let hit_t = e2.dot(q) * inv;
    const EPS: f32 = 1e-6;
    u >= -EPS && v >= -EPS && u + v <= 1.0 + EPS && hit_t >= 0.0 && hit_t <= t_max
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize) -> Vec<[Vec3; 3]> {
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let (x, z) = (i as f32, j as f32);
                let y = ((i * 7 + j * 3) % 5) as f32 * 0.3;
                let a = Vec3::new(x, y, z);
                tris.push([a, a + Vec3::X, a + Vec3::Z]);
                tris.push([a + Vec3::X, a + Vec3::new(1.0, 0.5, 1.0), a + Vec3::Z]);
            }
        }
        tris
    }

    #[test]
    fn every_triangle_in_one_leaf_and_boxes_contain_their_contents() {
        let mut tris = grid(12);
        tris.push([Vec3::ZERO; 3]);
        tris.push([Vec3::NAN, Vec3::X, Vec3::Y]);
        let bvh = FlatBvh::build(&tris).unwrap();
        assert_eq!(bvh.skipped, 2);
        assert_eq!(bvh.triangles.len(), 12 * 12 * 2);
        assert!(
            bvh.depth > 3 && bvh.depth < MAX_STACK,
            "depth {}",
            bvh.depth
        );
        for n in &bvh.nodes {
            let inside = |p: Vec3| {
                p.cmpge(Vec3::from(n.lo) - 1e-6).all() && p.cmple(Vec3::from(n.hi) + 1e-6).all()
            };
            if n.count == 0 {
                for c in [n.first, n.first + 1] {
                    let c = &bvh.nodes[c as usize];
                    assert!(inside(c.lo.into()) && inside(c.hi.into()));
                }
            } else {
                let range = n.first as usize..(n.first + n.count) as usize;
                assert!(bvh.triangles[range].iter().flatten().all(|&p| inside(p)));
            }
        }
    }

    #[test]
    fn words_follow_the_documented_layout() {
        let bvh = FlatBvh::build(&grid(3)).unwrap();
        let nodes = bvh.node_words();
        let tris = bvh.triangle_words();
        assert_eq!(nodes.len(), bvh.nodes.len() * NODE_WORDS);
        assert_eq!(tris.len(), bvh.triangles.len() * TRIANGLE_WORDS);
        assert_eq!(bvh.gpu_bytes(), 4 * (nodes.len() + tris.len()) as u64);
        let f = |w: u32| f32::from_bits(w);
        for (i, n) in bvh.nodes.iter().enumerate() {
            let w = &nodes[i * NODE_WORDS..][..NODE_WORDS];
            assert_eq!([f(w[0]), f(w[1]), f(w[2])], n.lo);
            assert_eq!((w[3], w[7]), (n.count, n.first));
            assert_eq!([f(w[4]), f(w[5]), f(w[6])], n.hi);
        }
        let t = bvh.triangles[1];
        let w = &tris[TRIANGLE_WORDS..][..TRIANGLE_WORDS];
        assert_eq!(Vec3::new(f(w[0]), f(w[1]), f(w[2])), t[0]);
        assert_eq!(Vec3::new(f(w[4]), f(w[5]), f(w[6])), t[1] - t[0]);
        assert_eq!(Vec3::new(f(w[8]), f(w[9]), f(w[10])), t[2] - t[0]);
        assert_eq!((w[3], w[7], w[11]), (0, 0, 0));
    }

    #[test]
    fn traversal_agrees_with_brute_force() {
        let tris = grid(10);
        let bvh = FlatBvh::build(&tris).unwrap();
        let mut state = 12345u32;
        let mut next = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32
        };
        let mut hits = 0;
        for _ in 0..2000 {
            let o = Vec3::new(next() * 10.0, 2.5 * next() - 0.5, next() * 10.0);
            let d = (Vec3::new(next(), next(), next()) * 2.0 - 1.0).normalize();
            let brute = tris.iter().any(|t| triangle_hit(t, o, d, 1.5));
            assert_eq!(bvh.occluded(o, d, 1.5), brute, "origin {o} dir {d}");
            hits += brute as u32;
        }
        assert!(hits > 200 && hits < 1800, "{hits} hits");
        assert!(!FlatBvh::build(&[])
            .unwrap()
            .occluded(Vec3::ZERO, Vec3::X, 1.0));
    }
}
