//! Mesh building blocks shared by the generated scenes (`shapes.rs`, `furniture.rs`): boxes and quads
//! with flat normals.

use crate::gl::mesh::{MeshData, Vertex};
use glam::{Vec2, Vec3};

/// Appends an axis-aligned box with flat normals (24 vertices, outward faces, CCW).
pub fn add_box(m: &mut MeshData, min: Vec3, max: Vec3) {
    let c = |x: bool, y: bool, z: bool| {
        Vec3::new(
            if x { max.x } else { min.x },
            if y { max.y } else { min.y },
            if z { max.z } else { min.z },
        )
    };
    // Each face: normal and four corners counter-clockwise seen from outside.
    let faces = [
        (
            Vec3::X,
            [
                c(true, false, true),
                c(true, false, false),
                c(true, true, false),
                c(true, true, true),
            ],
        ),
        (
            Vec3::NEG_X,
            [
                c(false, false, false),
                c(false, false, true),
                c(false, true, true),
                c(false, true, false),
            ],
        ),
        (
            Vec3::Y,
            [
                c(false, true, true),
                c(true, true, true),
                c(true, true, false),
                c(false, true, false),
            ],
        ),
        (
            Vec3::NEG_Y,
            [
                c(false, false, false),
                c(true, false, false),
                c(true, false, true),
                c(false, false, true),
            ],
        ),
        (
            Vec3::Z,
            [
                c(false, false, true),
                c(true, false, true),
                c(true, true, true),
                c(false, true, true),
            ],
        ),
        (
            Vec3::NEG_Z,
            [
                c(true, false, false),
                c(false, false, false),
                c(false, true, false),
                c(true, true, false),
            ],
        ),
    ];
    for (n, q) in faces {
        add_quad(m, q, n);
    }
}

/// Appends a quad (two triangles) with one normal.
pub fn add_quad(m: &mut MeshData, q: [Vec3; 4], n: Vec3) {
    let base = m.vertices.len() as u32;
    let uv = [
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(0.0, 1.0),
    ];
    for (p, t) in q.iter().zip(uv) {
        m.vertices.push(Vertex {
            position: p.to_array(),
            texcoord: t.to_array(),
            normal: n.to_array(),
        });
    }
    m.indices
        .extend_from_slice(&[base, base + 1, base + 2, base + 2, base + 3, base]);
}
