//! Procedural meshes for the demo courtyard, written to `Res/meshes/*.obj` by `opengl3d gen-demo`.
//! Everything the demo shows is made here: nothing is downloaded.

pub use super::primitives::{add_box, add_quad};
use crate::gl::mesh::{MeshData, Vertex};
use glam::Vec3;
use std::fmt::Write as _;

/// A horizontal ground plane of half-size `h`, split into `n`×`n` quads (keeps interpolation well behaved).
pub fn ground(h: f32, n: u32) -> MeshData {
    let mut m = MeshData::default();
    let step = 2.0 * h / n as f32;
    for i in 0..n {
        for j in 0..n {
            let x0 = -h + i as f32 * step;
            let z0 = -h + j as f32 * step;
            let (x1, z1) = (x0 + step, z0 + step);
            add_quad(
                &mut m,
                [
                    Vec3::new(x0, 0.0, z1),
                    Vec3::new(x1, 0.0, z1),
                    Vec3::new(x1, 0.0, z0),
                    Vec3::new(x0, 0.0, z0),
                ],
                Vec3::Y,
            );
        }
    }
    m
}

/// Back and left walls of the courtyard, with a ledge (an overhang) along the back wall.
pub fn walls() -> MeshData {
    let mut m = MeshData::default();
    add_box(
        &mut m,
        Vec3::new(-8.0, 0.0, -6.4),
        Vec3::new(8.0, 4.0, -6.0),
    ); // back wall
    add_box(
        &mut m,
        Vec3::new(-8.0, 0.0, -6.0),
        Vec3::new(-7.6, 4.0, 6.0),
    ); // left wall
    add_box(
        &mut m,
        Vec3::new(-7.6, 2.4, -6.0),
        Vec3::new(8.0, 2.6, -4.8),
    ); // ledge
    m
}

/// A square pillar with a plinth and a capital (creases at both ends).
pub fn pillar() -> MeshData {
    let mut m = MeshData::default();
    add_box(
        &mut m,
        Vec3::new(-0.45, 0.0, -0.45),
        Vec3::new(0.45, 0.3, 0.45),
    );
    add_box(
        &mut m,
        Vec3::new(-0.25, 0.3, -0.25),
        Vec3::new(0.25, 2.7, 0.25),
    );
    add_box(&mut m, Vec3::new(-0.4, 2.7, -0.4), Vec3::new(0.4, 3.0, 0.4));
    m
}

/// Four steps rising along −Z, 1.2 m wide.
pub fn steps() -> MeshData {
    let mut m = MeshData::default();
    for i in 0..4 {
        let h = 0.18 * (i + 1) as f32;
        let z = -0.3 * i as f32;
        add_box(&mut m, Vec3::new(-0.6, 0.0, z - 0.3), Vec3::new(0.6, h, z));
    }
    m
}

/// A unit crate centred on the floor (0..1 in Y).
pub fn crate_box() -> MeshData {
    let mut m = MeshData::default();
    add_box(&mut m, Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 1.0, 0.5));
    m
}

/// A table: a top on four legs (the top is an overhang over the floor).
pub fn table() -> MeshData {
    let mut m = MeshData::default();
    add_box(
        &mut m,
        Vec3::new(-0.8, 0.72, -0.45),
        Vec3::new(0.8, 0.8, 0.45),
    );
    for (x, z) in [(-0.7, -0.35), (0.7, -0.35), (-0.7, 0.35), (0.7, 0.35)] {
        add_box(
            &mut m,
            Vec3::new(x - 0.04, 0.0, z - 0.04),
            Vec3::new(x + 0.04, 0.72, z + 0.04),
        );
    }
    m
}

/// A UV sphere of radius `r` resting on the floor (centre at y = r).
pub fn sphere(r: f32, slices: u32, stacks: u32) -> MeshData {
    let mut m = MeshData::default();
    for j in 0..=stacks {
        let v = j as f32 / stacks as f32;
        let theta = v * std::f32::consts::PI;
        for i in 0..=slices {
            let u = i as f32 / slices as f32;
            let phi = u * std::f32::consts::TAU;
            let n = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            );
            m.vertices.push(Vertex {
                position: (n * r + Vec3::Y * r).to_array(),
                texcoord: [u, v],
                normal: n.to_array(),
            });
        }
    }
    let row = slices + 1;
    for j in 0..stacks {
        for i in 0..slices {
            let a = j * row + i;
            let (b, c, d) = (a + 1, a + row, a + row + 1);
            if j != 0 {
                m.indices.extend_from_slice(&[a, c, b]);
            }
            if j != stacks - 1 {
                m.indices.extend_from_slice(&[b, c, d]);
            }
        }
    }
    m
}

/// A torus lying on the floor (ring radius `big`, tube radius `small`).
pub fn torus(big: f32, small: f32, seg: u32, tube: u32) -> MeshData {
    let mut m = MeshData::default();
    for i in 0..=seg {
        let a = i as f32 / seg as f32 * std::f32::consts::TAU;
        let centre = Vec3::new(a.cos() * big, small, -a.sin() * big);
        let out = Vec3::new(a.cos(), 0.0, -a.sin());
        for j in 0..=tube {
            let b = j as f32 / tube as f32 * std::f32::consts::TAU;
            let n = out * b.cos() + Vec3::Y * b.sin();
            m.vertices.push(Vertex {
                position: (centre + n * small).to_array(),
                texcoord: [i as f32 / seg as f32, j as f32 / tube as f32],
                normal: n.to_array(),
            });
        }
    }
    let row = tube + 1;
    for i in 0..seg {
        for j in 0..tube {
            let a = i * row + j;
            let (b, c, d) = (a + row, a + 1, a + row + 1);
            m.indices.extend_from_slice(&[a, b, d, d, c, a]);
        }
    }
    m
}

/// OBJ text of a mesh (positions, texcoords, normals; 1-based indices).
pub fn to_obj(m: &MeshData, comment: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# {comment}\n# generated by `opengl3d gen-demo`; regenerate rather than edit"
    );
    for v in &m.vertices {
        let _ = writeln!(s, "v {} {} {}", v.position[0], v.position[1], v.position[2]);
    }
    for v in &m.vertices {
        let _ = writeln!(s, "vt {} {}", v.texcoord[0], v.texcoord[1]);
    }
    for v in &m.vertices {
        let _ = writeln!(s, "vn {} {} {}", v.normal[0], v.normal[1], v.normal[2]);
    }
    for t in m.indices.chunks_exact(3) {
        let _ = writeln!(
            s,
            "f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}",
            t[0] + 1,
            t[1] + 1,
            t[2] + 1
        );
    }
    s
}

/// Every generated mesh: the courtyard's and those of the bench's thin-things and room scenes
/// (`furniture.rs`): (file name under `Res/meshes/`, description, mesh).
pub fn demo_meshes() -> Vec<(&'static str, &'static str, MeshData)> {
    let mut meshes = vec![
        (
            "ground.obj",
            "courtyard floor, 24 m square",
            ground(12.0, 12),
        ),
        ("walls.obj", "back and left walls with a ledge", walls()),
        ("pillar.obj", "pillar with plinth and capital", pillar()),
        ("steps.obj", "four steps", steps()),
        ("crate.obj", "unit crate", crate_box()),
        ("table.obj", "table with four legs", table()),
        (
            "sphere.obj",
            "sphere of radius 0.7 resting on the floor",
            sphere(0.7, 32, 16),
        ),
        (
            "torus.obj",
            "torus lying on the floor",
            torus(0.6, 0.22, 40, 16),
        ),
    ];
    meshes.extend(super::furniture::scene_meshes());
    meshes
}

/// Writes the demo meshes into `dir` (normally `Res/meshes`).
pub fn write_demo_meshes(dir: &std::path::Path) -> anyhow::Result<Vec<std::path::PathBuf>> {
    crate::io::create_dir_all(dir)?;
    let mut out = Vec::new();
    for (name, what, mesh) in demo_meshes() {
        let p = dir.join(name);
        crate::io::write_file(&p, to_obj(&mesh, what).as_bytes())?;
        out.push(p);
    }
    Ok(out)
}
