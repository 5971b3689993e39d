//! The stress cases: small scenes from procedural meshes at extreme planes, radii, intensities,
//! fields of view, sizes and cameras.

use crate::ao::AoMethod;
use crate::gl::mesh::MeshData;
use crate::scene::{shapes, ObjectDesc, SceneDesc};
use anyhow::{Context as _, Result};
use glam::Vec3;
use std::path::{Path, PathBuf};

/// Meshes the cases use, written once as OBJ into a folder.
pub struct Meshes {
    dir: PathBuf,
}

impl Meshes {
    pub fn new(dir: &Path) -> Result<Meshes> {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        let mut wall = MeshData::default();
        shapes::add_box(
            &mut wall,
            Vec3::new(-1.0, 0.0, -50.0),
            Vec3::new(0.0, 4.0, 50.0),
        );
        let mut cube = MeshData::default();
        shapes::add_box(&mut cube, Vec3::splat(-1.0), Vec3::splat(1.0));
        let mut quad = MeshData::default();
        shapes::add_quad(
            &mut quad,
            [
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::new(1.0, -1.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(-1.0, 1.0, 0.0),
            ],
            Vec3::Z,
        );
        let meshes: [(&str, MeshData); 6] = [
            ("ground", shapes::ground(50.0, 10)),
            ("big-ground", shapes::ground(20000.0, 40)),
            ("wall", wall),
            ("cube", cube),
            ("quad", quad),
            ("sphere", shapes::sphere(0.5, 24, 12)),
        ];
        for (name, m) in meshes {
            let path = dir.join(format!("{name}.obj"));
            std::fs::write(&path, shapes::to_obj(&m, name))
                .with_context(|| format!("cannot write {}", path.display()))?;
        }
        Ok(Meshes {
            dir: dir.to_path_buf(),
        })
    }

    pub fn object(&self, name: &str, position: Vec3, scale: Vec3) -> ObjectDesc {
        ObjectDesc {
            mesh: self.dir.join(format!("{name}.obj")).display().to_string(),
            position: position.to_array(),
            rotation: [0.0; 3],
            scale: scale.to_array(),
            color: [0.8, 0.8, 0.8, 1.0],
        }
    }
}

/// The meshes are temporary: the folder goes with them, also when a case fails.
impl Drop for Meshes {
    fn drop(&mut self) {
        if let Err(e) = std::fs::remove_dir_all(&self.dir) {
            eprintln!("warning: cannot remove {}: {e}", self.dir.display());
        }
    }
}

/// A scene description with no objects and the defaults (no bloom: it does not touch AO).
pub fn base(w: u32, h: u32, eye: Vec3, target: Vec3) -> SceneDesc {
    let mut s = SceneDesc::default();
    s.output.width = w;
    s.output.height = h;
    s.camera.eye = eye.to_array();
    s.camera.target = target.to_array();
    s.bloom.enabled = false;
    s
}

/// Floor, a wall along Z (a 90° crease), a cube and a sphere: occlusion at several scales.
fn crease(m: &Meshes, w: u32, h: u32) -> SceneDesc {
    let mut s = base(w, h, Vec3::new(4.0, 2.5, 4.0), Vec3::new(0.0, 0.5, 0.0));
    s.objects.push(m.object("ground", Vec3::ZERO, Vec3::ONE));
    s.objects.push(m.object("wall", Vec3::ZERO, Vec3::ONE));
    s.objects
        .push(m.object("cube", Vec3::new(1.5, 0.5, -1.0), Vec3::splat(0.5)));
    s.objects
        .push(m.object("sphere", Vec3::new(1.0, 0.0, 1.5), Vec3::ONE));
    s
}

pub struct Case {
    pub category: &'static str,
    pub name: String,
    pub scene: SceneDesc,
    pub methods: Vec<AoMethod>,
    /// Every pixel must be fully visible (sky-only frames).
    pub all_visible: bool,
}

/// Every case, and the names of those left out (the 4096×4096 frame without `large`).
pub fn all_cases(m: &Meshes, large: bool) -> (Vec<Case>, Vec<String>) {
    let all = AoMethod::ALL.to_vec();
    let (w, h) = (160, 90);
    let mut v = Vec::new();
    let mut skipped = Vec::new();
    let mut push = |category: &'static str, name: String, scene: SceneDesc| {
        v.push(Case {
            category,
            name,
            scene,
            methods: all.clone(),
            all_visible: false,
        });
    };
    for near in [0.01f32, 0.1, 0.35, 1.0] {
        for far in [100.0f32, 1e3, 1e4, 1e5, 1e6] {
            let mut s = crease(m, w, h);
            s.camera.near = near;
            s.camera.far = far;
            push("near/far", format!("near {near} far {far}"), s);
        }
    }
    for r in [1e-3f32, 1e-2, 0.1, 1.0, 10.0, 100.0] {
        let mut s = crease(m, w, h);
        s.ao.radius = r;
        push("radius", format!("radius {r} m"), s);
    }
    for i in [0.0f32, 1e-3, 1.0, 5.0, 100.0, 1000.0] {
        let mut s = crease(m, w, h);
        s.ao.intensity = i;
        push("intensity", format!("intensity {i}"), s);
    }
    for b in [0.0f32, 10.0] {
        let mut s = crease(m, w, h);
        s.ao.bias = b;
        push("bias", format!("bias {b} m"), s);
    }
    for n in [1u32, 256] {
        let mut s = crease(m, w, h);
        s.ao.samples = n;
        push("samples", format!("samples {n}"), s);
    }
    for fov in [10.0f32, 30.0, 90.0, 120.0, 150.0] {
        let mut s = crease(m, w, h);
        s.camera.fov_y = fov;
        push("fov", format!("fov {fov}°"), s);
    }
    for (sw, sh) in [(1u32, 1u32), (3, 5), (5, 3), (4097, 3), (3, 4097)] {
        push("size", format!("{sw}×{sh}"), crease(m, sw, sh));
    }
    if large {
        let s = crease(m, 4096, 4096);
        v.push(Case {
            category: "size",
            name: "4096×4096".into(),
            scene: s,
            // One method at this size keeps the stress run within minutes on software GL.
            methods: vec![AoMethod::SaoLesson],
            all_visible: false,
        });
    } else {
        skipped.push("4096×4096 (--no-large)".to_string());
    }
    let mut push = |category: &'static str, name: String, scene: SceneDesc| {
        v.push(Case {
            category,
            name,
            scene,
            methods: all.clone(),
            all_visible: false,
        });
    };
    // Camera inside geometry: inside the cube, inside the wall, and in the floor.
    let mut s = crease(m, w, h);
    s.camera.eye = [1.5, 0.5, -1.0];
    s.camera.target = [0.0, 0.5, 0.0];
    push("inside", "eye inside the cube".into(), s);
    let mut s = crease(m, w, h);
    s.camera.eye = [-0.5, 2.0, 0.0];
    s.camera.target = [3.0, 0.0, 0.0];
    push("inside", "eye inside the wall".into(), s);
    let mut s = crease(m, w, h);
    s.camera.eye = [3.0, 0.0, 3.0];
    s.camera.target = [0.0, 0.5, 0.0];
    push("inside", "eye on the floor plane".into(), s);
    // A facing plane at, just before and just after the near plane.
    for (label, k) in [
        ("0.999", 0.999f32),
        ("exactly", 1.0),
        ("1.001", 1.001),
        ("2×", 2.0),
    ] {
        let mut s = base(w, h, Vec3::ZERO, Vec3::NEG_Z);
        let near = s.camera.near;
        let d = near * k;
        s.objects.push(m.object(
            "quad",
            Vec3::new(0.0, 0.0, -d),
            Vec3::new(4.0 * d, 4.0 * d, 1.0),
        ));
        // And a floor, so that the plane's edge has something to occlude.
        s.objects
            .push(m.object("ground", Vec3::new(0.0, -0.5 * d, 0.0), Vec3::ONE));
        push(
            "near plane",
            format!("facing plane at {label} near ({d} m)"),
            s,
        );
    }
    // Grazing views of a large open plane: eye 1 m up, looking at the ground z metres away.
    for z in [1.0f32, 10.0, 100.0, 1000.0] {
        let mut s = base(w, h, Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.0, -z));
        s.objects
            .push(m.object("big-ground", Vec3::ZERO, Vec3::ONE));
        push("grazing", format!("open plane, look at z = {z} m"), s);
    }
    // Sky only.
    for (sw, sh) in [(64u32, 48u32), (1, 1), (4097, 3)] {
        v.push(Case {
            category: "sky",
            name: format!("sky only {sw}×{sh}"),
            scene: base(sw, sh, Vec3::new(0.0, 1.6, 6.0), Vec3::ZERO),
            methods: all.clone(),
            all_visible: true,
        });
    }
    // One-pixel and sub-pixel objects against the sky and in front of a far wall.
    for (label, dist) in [("about 1 px", 100.0f32), ("about 0.25 px", 400.0)] {
        let mut s = base(w, h, Vec3::new(0.0, 0.5, 0.0), Vec3::new(0.0, 0.5, -1.0));
        s.objects
            .push(m.object("sphere", Vec3::new(0.0, 0.0, -dist), Vec3::ONE));
        v.push(Case {
            category: "tiny object",
            name: format!("sphere {label}, sky behind"),
            scene: s.clone(),
            methods: all.clone(),
            all_visible: false,
        });
        s.objects
            .push(m.object("quad", Vec3::new(0.0, 0.5, -dist - 5.0), Vec3::splat(dist)));
        v.push(Case {
            category: "tiny object",
            name: format!("sphere {label}, wall 5 m behind"),
            scene: s,
            methods: all.clone(),
            all_visible: false,
        });
    }
    (v, skipped)
}
