//! Procedural meshes of the bench's two other scenes, written to `Res/meshes/` by `opengl3d gen-demo`
//! with the courtyard's: thin things (`Res/scenes/thin.toml`: chairs, a table on thin legs, open
//! shelving, a slatted bench, a picket fence) and an interior with overhangs (`Res/scenes/room.toml`:
//! a room with a ceiling and beams, an arcade of round arches, wall shelves). Thin boards, legs and
//! slats are what a depth buffer of infinite thickness gets most wrong; ceilings, arches and shelves
//! are overhangs that shade what lies under them.

use super::primitives::add_box;
use crate::gl::mesh::MeshData;
use glam::Vec3;

/// A box from its centre's x and z, its bottom and top, and its width (x) and depth (z).
fn post(m: &mut MeshData, x: f32, z: f32, y0: f32, y1: f32, wx: f32, wz: f32) {
    add_box(
        m,
        Vec3::new(x - 0.5 * wx, y0, z - 0.5 * wz),
        Vec3::new(x + 0.5 * wx, y1, z + 0.5 * wz),
    );
}

/// A chair facing +Z: a 45 cm seat 2.5 cm thick on four 3.5 cm legs, and a back of four vertical
/// slats between two uprights on the −Z side.
pub fn chair() -> MeshData {
    let mut m = MeshData::default();
    let (half, seat, leg) = (0.22, 0.45, 0.035);
    post(&mut m, 0.0, 0.0, seat - 0.025, seat, 2.0 * half, 2.0 * half);
    for (x, z) in [
        (-half + leg, -half + leg),
        (half - leg, -half + leg),
        (-half + leg, half - leg),
        (half - leg, half - leg),
    ] {
        let top = if z < 0.0 { 0.95 } else { seat - 0.025 };
        post(&mut m, x, z, 0.0, top, leg, leg);
    }
    // Back: a top rail and four slats 4 cm wide with 4.5 cm gaps.
    let z = -half + leg;
    post(&mut m, 0.0, z, 0.88, 0.95, 2.0 * half - 2.0 * leg, 0.02);
    for k in 0..4 {
        let x = -0.128 + 0.085 * k as f32;
        post(&mut m, x, z, seat, 0.88, 0.04, 0.015);
    }
    m
}

/// A table with a 1.2 × 0.7 m top 2.5 cm thick on four 3.5 cm legs and a thin rail under the top.
pub fn thin_table() -> MeshData {
    let mut m = MeshData::default();
    let (hx, hz, top) = (0.6, 0.35, 0.74);
    post(&mut m, 0.0, 0.0, top - 0.025, top, 2.0 * hx, 2.0 * hz);
    let leg = 0.035;
    for (x, z) in [
        (-hx + 0.06, -hz + 0.06),
        (hx - 0.06, -hz + 0.06),
        (-hx + 0.06, hz - 0.06),
        (hx - 0.06, hz - 0.06),
    ] {
        post(&mut m, x, z, 0.0, top - 0.025, leg, leg);
    }
    // Rails between the legs, 2 cm thick, 8 cm high.
    for z in [-hz + 0.06, hz - 0.06] {
        post(
            &mut m,
            0.0,
            z,
            top - 0.105,
            top - 0.025,
            2.0 * hx - 0.12,
            0.02,
        );
    }
    m
}

/// Open shelving 1.2 m wide, 0.35 m deep and 1.8 m high: two side boards and five shelves, all
/// 2 cm thick, no back.
pub fn shelving() -> MeshData {
    let mut m = MeshData::default();
    let (hx, depth, height, board) = (0.6, 0.35, 1.8, 0.02);
    for x in [-hx + 0.5 * board, hx - 0.5 * board] {
        post(&mut m, x, 0.0, 0.0, height, board, depth);
    }
    for k in 0..5 {
        let y = 0.05 + k as f32 * (height - 0.07) / 4.0;
        post(
            &mut m,
            0.0,
            0.0,
            y,
            y + board,
            2.0 * hx - 2.0 * board,
            depth,
        );
    }
    m
}

/// A slatted bench 1.6 m long along X: six 6 cm slats 2.5 cm thick with 2 cm gaps, on two
/// trestles of 4 cm legs.
pub fn slatted_bench() -> MeshData {
    let mut m = MeshData::default();
    let (hx, seat) = (0.8, 0.44);
    for k in 0..6 {
        let z = -0.2 + 0.08 * k as f32;
        post(&mut m, 0.0, z, seat - 0.025, seat, 2.0 * hx, 0.06);
    }
    for x in [-hx + 0.15, hx - 0.15] {
        for z in [-0.19, 0.19] {
            post(&mut m, x, z, 0.0, seat - 0.025, 0.04, 0.04);
        }
        // Cross bar under the slats.
        post(&mut m, x, 0.0, seat - 0.085, seat - 0.025, 0.04, 0.42);
    }
    m
}

/// A picket fence 3 m long along X: two rails and 21 pickets 6 cm wide, 2 cm thick, 1 m high, with
/// 8.5 cm gaps, on three posts.
pub fn picket_fence() -> MeshData {
    let mut m = MeshData::default();
    let hx = 1.5;
    for x in [-hx, 0.0, hx] {
        post(&mut m, x, 0.0, 0.0, 1.05, 0.07, 0.07);
    }
    for y in [0.25, 0.8] {
        post(&mut m, 0.0, -0.045, y, y + 0.07, 2.0 * hx, 0.02);
    }
    for k in 0..21 {
        let x = -hx + 0.03 + k as f32 * 0.1455;
        post(&mut m, x, -0.065, 0.0, 1.0, 0.06, 0.02);
    }
    m
}

/// The room: a 10 × 10 m floor (x −5..5, z −5.5..4.5), four walls 3.2 m high and 0.2 m thick, a
/// ceiling slab, and three beams 0.2 m wide hanging 0.3 m under it (overhangs along the ceiling).
pub fn room() -> MeshData {
    let mut m = MeshData::default();
    let (x0, x1, z0, z1, h, t) = (-5.0, 5.0, -5.5, 4.5, 3.2, 0.2);
    add_box(
        &mut m,
        Vec3::new(x0 - t, -t, z0 - t),
        Vec3::new(x1 + t, 0.0, z1 + t),
    );
    add_box(
        &mut m,
        Vec3::new(x0 - t, h, z0 - t),
        Vec3::new(x1 + t, h + t, z1 + t),
    );
    add_box(
        &mut m,
        Vec3::new(x0 - t, 0.0, z0 - t),
        Vec3::new(x1 + t, h, z0),
    );
    add_box(
        &mut m,
        Vec3::new(x0 - t, 0.0, z1),
        Vec3::new(x1 + t, h, z1 + t),
    );
    add_box(&mut m, Vec3::new(x0 - t, 0.0, z0), Vec3::new(x0, h, z1));
    add_box(&mut m, Vec3::new(x1, 0.0, z0), Vec3::new(x1 + t, h, z1));
    for z in [-1.5, 0.8, 3.0] {
        add_box(
            &mut m,
            Vec3::new(x0, h - 0.3, z - 0.1),
            Vec3::new(x1, h, z + 0.1),
        );
    }
    m
}

/// An arcade across the room at z = −3 (0.4 m thick): four piers 0.4 m square and three round
/// arches of 1 m radius springing at 1.8 m, the wall above them up to the ceiling at 3.2 m, and solid
/// wall to the side walls. The arches' undersides are built from 0.1 m wide steps.
pub fn arcade() -> MeshData {
    let mut m = MeshData::default();
    let (z, half_t, top, spring, r) = (-3.0, 0.2, 3.2, 1.8, 1.0);
    let piers = [-3.6, -1.2, 1.2, 3.6];
    for x in piers {
        post(&mut m, x, z, 0.0, top, 0.4, 2.0 * half_t);
    }
    for x in [-4.4, 4.4] {
        post(&mut m, x, z, 0.0, top, 1.2, 2.0 * half_t);
    }
    let steps = 20;
    for pair in piers.windows(2) {
        let centre = 0.5 * (pair[0] + pair[1]);
        for k in 0..steps {
            // Step k spans [u0, u1] of the 2 m opening; its underside follows the arch at its middle.
            let u0 = -r + 2.0 * r * k as f32 / steps as f32;
            let u1 = u0 + 2.0 * r / steps as f32;
            let u = 0.5 * (u0 + u1);
            let y = spring + (r * r - u * u).max(0.0).sqrt();
            add_box(
                &mut m,
                Vec3::new(centre + u0, y, z - half_t),
                Vec3::new(centre + u1, top, z + half_t),
            );
        }
    }
    m
}

/// Three wall shelves 1.6 m long and 0.3 m deep (boards 3 cm thick) on thin brackets, their backs
/// against a wall at z = 0 facing +Z: overhangs at 0.9, 1.4 and 1.9 m.
pub fn wall_shelves() -> MeshData {
    let mut m = MeshData::default();
    for y in [0.9, 1.4, 1.9] {
        add_box(
            &mut m,
            Vec3::new(-0.8, y, 0.0),
            Vec3::new(0.8, y + 0.03, 0.3),
        );
        for x in [-0.6, 0.6] {
            add_box(
                &mut m,
                Vec3::new(x - 0.015, y - 0.2, 0.0),
                Vec3::new(x + 0.015, y, 0.25),
            );
        }
    }
    m
}

/// The meshes of the thin-things and room scenes: (file name under `Res/meshes/`, description, mesh).
pub fn scene_meshes() -> Vec<(&'static str, &'static str, MeshData)> {
    vec![
        (
            "chair.obj",
            "chair on thin legs with a slatted back",
            chair(),
        ),
        (
            "thin_table.obj",
            "table with a thin top on thin legs",
            thin_table(),
        ),
        ("shelving.obj", "open shelving of thin boards", shelving()),
        (
            "slatted_bench.obj",
            "slatted bench on trestles",
            slatted_bench(),
        ),
        ("picket_fence.obj", "picket fence, 3 m", picket_fence()),
        ("room.obj", "room with ceiling and beams", room()),
        ("arcade.obj", "arcade of three round arches", arcade()),
        (
            "wall_shelves.obj",
            "three wall shelves on brackets",
            wall_shelves(),
        ),
    ]
}
