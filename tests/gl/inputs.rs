//! Inputs that never mislead: `--res` checks, `--obj` framing, scene-relative meshes, scene values
//! with file:line:col errors, output paths, non-UTF-8 file names, and mesh loading in O(N).

use crate::common;
use crate::common::{bin, fails_with, run, stderr};

use glam::Vec3;
use opengl3d::gl::mesh::{MeshBuffer, MeshData};
use opengl3d::io::read_pfm;
use opengl3d::scene::{shapes, SceneDesc};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};

fn s(p: &Path) -> &OsStr {
    p.as_os_str()
}

#[test]
fn res_that_is_missing_a_file_or_empty_is_named_for_every_command() {
    let dir = common::temp_dir("inputs-res");
    let missing = dir.join("no-such-res");
    let file = dir.join("a-file");
    std::fs::write(&file, "not a folder").unwrap();
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let out = dir.join("x.png");
    let ref_out = dir.join("r.pfm");
    let commands: Vec<Vec<&OsStr>> = vec![
        vec!["render".as_ref(), "--out".as_ref(), s(&out)],
        vec!["window".as_ref(), "--frames".as_ref(), "1".as_ref()],
        vec!["lesson".as_ref(), "2".as_ref(), "--headless".as_ref()],
        vec!["reference".as_ref(), "--out".as_ref(), s(&ref_out)],
        vec!["bench".as_ref()],
    ];
    for c in &commands {
        let with = |res: &Path| {
            let mut a: Vec<PathBuf> = vec!["--res".into(), res.into()];
            a.extend(c.iter().map(PathBuf::from));
            a
        };
        let m = missing.display().to_string();
        fails_with(&with(&missing), &[&m, "no such folder"]);
        let f = file.display().to_string();
        fails_with(&with(&file), &[&f, "is a file"]);
        let e = empty.display().to_string();
        fails_with(&with(&empty), &[&e, "holds none"]);
    }
    // A lesson step names the shaders it reads.
    std::fs::write(empty.join("standard.frag"), "// not a lesson shader\n").unwrap();
    fails_with(
        &[
            "--res".as_ref(),
            s(&empty),
            "lesson".as_ref(),
            "4".as_ref(),
            "--headless".as_ref(),
        ],
        &["sao_restore_depth.frag", "sao_down_sampling.frag"],
    );
    let m = missing.display().to_string();
    fails_with(&["--res".as_ref(), s(&missing), "gen-demo".as_ref()], &[&m]);
}

#[test]
fn gen_demo_writes_into_the_res_folder() {
    let dir = common::temp_dir("inputs-gen-demo");
    let o = run(&["--res".as_ref(), s(&dir), "gen-demo".as_ref()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for (name, what, mesh) in shapes::demo_meshes() {
        let written = std::fs::read_to_string(dir.join("meshes").join(name)).unwrap();
        assert_eq!(written, shapes::to_obj(&mesh, what), "{name}");
    }
}

/// Fraction of pixels of a linear-depth PFM nearer than the farthest value (the sky).
fn covered(path: &Path) -> f32 {
    let (_, _, _, v) = read_pfm(path).unwrap();
    common::assert_finite("linear depth", &v);
    let far = v.iter().copied().fold(0.0f32, f32::max);
    v.iter().filter(|d| **d < far * 0.999).count() as f32 / v.len() as f32
}

#[test]
fn obj_of_any_size_fills_the_frame() {
    let dir = common::temp_dir("inputs-obj-size");
    // A 6 m room exported in millimetres, a 2 mm part in metres, a 3 km terrain block.
    for (name, half) in [("mm", 3000.0f32), ("tiny", 0.001), ("km", 1500.0)] {
        let mut m = MeshData::default();
        shapes::add_box(
            &mut m,
            Vec3::splat(-half),
            Vec3::new(half, half * 0.5, half),
        );
        let obj = dir.join(format!("{name}.obj"));
        std::fs::write(&obj, shapes::to_obj(&m, name)).unwrap();
        let out = dir.join(format!("{name}.pfm"));
        let o = run(&[
            "render".as_ref(),
            "--obj".as_ref(),
            s(&obj),
            "--view".as_ref(),
            "linear-depth".as_ref(),
            "--width".as_ref(),
            "64".as_ref(),
            "--height".as_ref(),
            "48".as_ref(),
            "--out".as_ref(),
            s(&out),
        ]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let c = covered(&out);
        assert!(c > 0.1, "{name}: the model covers only {c} of the frame");
    }
}

#[test]
fn scene_meshes_resolve_beside_the_scene_file_not_in_the_working_folder() {
    let dir = common::temp_dir("inputs-scene-relative");
    let scene_dir = dir.join("scene");
    let cwd = dir.join("elsewhere");
    for d in [scene_dir.join("meshes"), cwd.join("meshes")] {
        std::fs::create_dir_all(d).unwrap();
    }
    let mut own = MeshData::default();
    shapes::add_box(
        &mut own,
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(1.0, 2.0, 1.0),
    );
    std::fs::write(
        scene_dir.join("meshes/thing.obj"),
        shapes::to_obj(&own, "own"),
    )
    .unwrap();
    // Same name in the working folder: a flat plate far below.
    let mut other = MeshData::default();
    shapes::add_box(
        &mut other,
        Vec3::new(-9.0, -5.0, -9.0),
        Vec3::new(9.0, -4.9, 9.0),
    );
    std::fs::write(
        cwd.join("meshes/thing.obj"),
        shapes::to_obj(&other, "other"),
    )
    .unwrap();
    let scene = "[camera]\neye = [0.0, 1.0, 6.0]\ntarget = [0.0, 1.0, 0.0]\n\n[[object]]\nmesh = \"meshes/thing.obj\"\n";
    let scene_file = scene_dir.join("scene.toml");
    std::fs::write(&scene_file, scene).unwrap();
    let abs = scene_dir.join("meshes/thing.obj").canonicalize().unwrap();
    let abs_scene = dir.join("absolute.toml");
    std::fs::write(
        &abs_scene,
        scene.replace("meshes/thing.obj", &abs.display().to_string()),
    )
    .unwrap();

    let loaded = SceneDesc::load(&scene_file).unwrap();
    assert_eq!(Path::new(&loaded.objects[0].mesh), abs.as_path());

    let render = |scene: &Path, out: &Path| {
        let o = bin()
            .current_dir(&cwd)
            .args([
                "render",
                "--view",
                "linear-depth",
                "--width",
                "48",
                "--height",
                "32",
            ])
            .arg("--scene")
            .arg(scene)
            .arg("--out")
            .arg(out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        read_pfm(out).unwrap().3
    };
    let relative = render(&scene_file, &dir.join("relative.pfm"));
    let absolute = render(&abs_scene, &dir.join("absolute.pfm"));
    assert!(
        relative == absolute,
        "the scene's own meshes/thing.obj must be drawn, not the working folder's"
    );
}

fn write_scene(dir: &Path, name: &str, body: &str) -> PathBuf {
    let p = dir.join(name);
    let text = format!("[output]\nwidth = 32\nheight = 24\n\n{body}");
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn bad_scene_values_name_their_file_line_and_column_or_flag() {
    let dir = common::temp_dir("inputs-scene-values");
    let out = dir.join("x.png");
    let cases = [
        (
            "nan-light.toml",
            "[light]\ncolor = [1.0, nan, 1.0]\n",
            "light.color[1]",
            6,
            15,
        ),
        (
            "inf-bloom.toml",
            "[bloom]\nstrength = inf\n",
            "bloom.strength",
            6,
            12,
        ),
        ("near.toml", "[camera]\nnear = 1e-30\n", "camera.near", 6, 8),
        (
            "scale.toml",
            "[[object]]\nmesh = \"meshes/crate.obj\"\nscale = [1.0, 1.0, -inf]\n",
            "object[0].scale[2]",
            7,
            20,
        ),
    ];
    for (name, body, key, line, col) in cases {
        let scene = write_scene(&dir, name, body);
        let place = format!("{}:{line}:{col}", scene.display());
        for command in ["render", "reference"] {
            fails_with(
                &[
                    command.as_ref(),
                    "--scene".as_ref(),
                    s(&scene),
                    "--out".as_ref(),
                    s(&out),
                ],
                &[&place, key],
            );
        }
    }
    // A default that no longer fits is named as such, at its table.
    let far = write_scene(&dir, "far.toml", "[camera]\nfar = 1e12\n");
    let place = format!("{}:5:1", far.display());
    fails_with(
        &[
            "render".as_ref(),
            "--scene".as_ref(),
            s(&far),
            "--out".as_ref(),
            s(&out),
        ],
        &[&place, "camera.near", "the default", "far/near"],
    );
    // A flag that sets the value is named instead of the file.
    let fine = write_scene(
        &dir,
        "fine.toml",
        "[[object]]\nmesh = \"meshes/crate.obj\"\n",
    );
    for command in ["render", "reference"] {
        let e = fails_with(
            &[
                command.as_ref(),
                "--scene".as_ref(),
                s(&fine),
                "--near".as_ref(),
                "1e-30".as_ref(),
                "--out".as_ref(),
                s(&out),
            ],
            &["--near 1e-30", "far/near"],
        );
        assert!(!e.contains("fine.toml:"), "the file is not to blame:\n{e}");
    }
    // A negative colour is clamped with a warning naming the key; the frame is written.
    let neg = write_scene(
        &dir,
        "negative.toml",
        "[light]\nambient = [-0.5, 0.5, 0.5]\n\n[[object]]\nmesh = \"meshes/crate.obj\"\n",
    );
    let o = run(&[
        "render".as_ref(),
        "--scene".as_ref(),
        s(&neg),
        "--out".as_ref(),
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    let place = format!("{}:6:12", neg.display());
    assert!(
        e.contains("warning") && e.contains(&place) && e.contains("light.ambient[0]"),
        "{e}"
    );
}

#[test]
fn negative_numbers_reach_the_range_check() {
    let e = fails_with(
        &["render", "--fov", "-30"],
        &["--fov -30", "between 0 and 179"],
    );
    assert!(!e.contains("unexpected argument"), "{e}");
    fails_with(&["render", "--near", "-1"], &["--near -1"]);
    fails_with(&["render", "--radius", "-2"], &["--radius -2"]);
    fails_with(&["render", "--width", "-30"], &["--width", "-30"]);
}

#[test]
fn unsupported_output_is_refused_before_anything_is_loaded_or_rendered() {
    let dir = common::temp_dir("inputs-out-ext");
    // The scene does not exist: if the output were checked after loading, that error would show.
    let scene = dir.join("missing.toml");
    for (command, flag) in [
        ("render", "--out"),
        ("reference", "--out"),
        ("lesson", "--out"),
    ] {
        let mut args: Vec<&OsStr> = vec![command.as_ref()];
        if command == "lesson" {
            args.extend(["12".as_ref(), "--headless".as_ref() as &OsStr]);
        }
        let out = dir.join("x.jpg");
        args.extend([flag.as_ref(), s(&out), "--scene".as_ref(), s(&scene)]);
        let e = fails_with(&args, &["x.jpg", ".png or .pfm"]);
        assert!(
            !e.contains("missing.toml"),
            "{command}: checked too late:\n{e}"
        );
    }
    let shot = dir.join("shot.pfm");
    fails_with(
        &[
            "window".as_ref(),
            "--frames".as_ref(),
            "1".as_ref(),
            "--screenshot".as_ref(),
            s(&shot),
        ],
        &["shot.pfm", ".png"],
    );
}

#[test]
fn write_errors_name_the_file_and_the_cause() {
    let dir = common::temp_dir("inputs-io");
    // The output is a folder.
    let folder = dir.join("frame.png");
    std::fs::create_dir_all(&folder).unwrap();
    let f = folder.display().to_string();
    fails_with(
        &["render", "--width", "16", "--height", "16", "--out", &f],
        &[&f, "is a folder"],
    );
    // A file is where the output's folder should be.
    let blocker = dir.join("blocker");
    std::fs::write(&blocker, "").unwrap();
    let inside = blocker.join("frame.pfm");
    let b = blocker.display().to_string();
    fails_with(
        &[
            "render",
            "--width",
            "16",
            "--height",
            "16",
            "--out",
            &inside.display().to_string(),
        ],
        &[&b, "cannot create the folder"],
    );
    // Library writes name the file and the missing folder.
    let nowhere = dir.join("no-folder").join("v.pfm");
    for e in [
        opengl3d::io::write_pfm_gray(&nowhere, 1, 1, &[0.5]).unwrap_err(),
        opengl3d::io::gray_to_png(&nowhere, 1, 1, &[0.5], 1.0).unwrap_err(),
        opengl3d::io::read_pfm(&nowhere).unwrap_err(),
    ] {
        let e = format!("{e:#}");
        assert!(e.contains(&nowhere.display().to_string()), "{e}");
        assert!(e.contains("does not exist"), "{e}");
    }
}

#[cfg(unix)]
#[test]
fn shift_jis_file_names_work() {
    use std::os::unix::ffi::OsStrExt;
    let dir = common::temp_dir("inputs-sjis");
    // "テスト" and "箱" in Shift-JIS: not UTF-8.
    let folder = dir.join(OsStr::from_bytes(b"\x83e\x83X\x83g"));
    std::fs::create_dir_all(&folder).unwrap();
    let obj = folder.join(OsStr::from_bytes(b"\x94\xa0.obj"));
    assert!(obj.to_str().is_none());
    // A box on a floor: the crease between them is occluded.
    let mut m = shapes::ground(3.0, 2);
    shapes::add_box(&mut m, Vec3::ZERO, Vec3::ONE);
    std::fs::write(&obj, shapes::to_obj(&m, "box on a floor")).unwrap();
    // A scene file with a Shift-JIS name, written to a Shift-JIS output.
    let scene = folder.join(OsStr::from_bytes(b"\x83V\x81[\x83\x93.toml"));
    std::fs::write(
        &scene,
        "[output]\nwidth = 32\nheight = 24\n\n[[object]]\nmesh = \"meshes/crate.obj\"\n",
    )
    .unwrap();
    let png = folder.join(OsStr::from_bytes(b"\x89\xe6.png"));
    let o = run(&[
        "render".as_ref(),
        "--scene".as_ref(),
        s(&scene),
        "--out".as_ref(),
        s(&png),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(png.is_file());
    // `--obj` with a Shift-JIS name: the ray-traced reference loads it.
    let pfm = folder.join(OsStr::from_bytes(b"\x89\xe6.pfm"));
    let o = run(&[
        "reference".as_ref(),
        "--obj".as_ref(),
        s(&obj),
        "--rays".as_ref(),
        "4".as_ref(),
        "--width".as_ref(),
        "16".as_ref(),
        "--height".as_ref(),
        "12".as_ref(),
        "--cache".as_ref(),
        s(&folder.join("cache")),
        "--out".as_ref(),
        s(&pfm),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, _, v) = read_pfm(&pfm).unwrap();
    assert_eq!((w, h), (16, 12));
    assert!(v.iter().any(|a| *a < 1.0), "the box shows");
    // Errors about such a file name it (lossily) instead of failing to print.
    let missing = folder.join(OsStr::from_bytes(b"\x96\xb3.obj"));
    fails_with(
        &["render".as_ref(), "--obj".as_ref(), s(&missing)],
        &["not found"],
    );
}

/// A sphere of radius 0.3 at `at`, its vertices already moved there (so separate and merged meshes
/// hold bit-identical positions).
fn sphere_at(at: Vec3) -> MeshData {
    let mut m = shapes::sphere(0.3, 24, 12);
    for v in &mut m.vertices {
        v.position = (Vec3::from(v.position) + at).to_array();
    }
    m
}

#[test]
fn many_meshes_draw_like_one_and_upload_each_byte_once() {
    let dir = common::temp_dir("inputs-meshes");
    let n = 60;
    let spheres: Vec<MeshData> = (0..n)
        .map(|i| {
            sphere_at(Vec3::new(
                (i % 10) as f32 - 4.5,
                0.3 + (i / 10) as f32 * 0.7,
                0.0,
            ))
        })
        .collect();
    let mut merged = MeshData::default();
    for m in &spheres {
        let base = merged.vertices.len() as u32;
        merged.vertices.extend_from_slice(&m.vertices);
        merged.indices.extend(m.indices.iter().map(|i| i + base));
    }
    let ctx = common::context();

    // Bytes sent from the CPU are exactly the meshes' bytes; growth copies stay below the total.
    let mut buffer = MeshBuffer::new(&ctx.gl).unwrap();
    let start = buffer.upload_counts();
    let mut total = 0u64;
    for (i, m) in spheres.iter().cycle().take(300).enumerate() {
        total += (m.vertices.len() * 32 + m.indices.len() * 4) as u64;
        buffer.add(&format!("sphere{i}"), m.clone()).unwrap();
    }
    let counts = buffer.upload_counts();
    assert_eq!(counts.uploaded - start.uploaded, total, "{counts:?}");
    // Doubling: what was copied at each growth sums to less than twice the final contents.
    assert!(counts.copied <= 2 * (total + start.uploaded), "{counts:?}");
    assert!(counts.grows <= 2 * 16, "{counts:?}");

    // N separate objects draw exactly like one mesh holding them all.
    let scene_with = |objects: Vec<opengl3d::scene::ObjectDesc>| {
        let mut s = SceneDesc {
            objects,
            ..Default::default()
        };
        s.camera.eye = [0.0, 2.5, 9.0];
        s.camera.target = [0.0, 2.0, 0.0];
        s.output.width = 96;
        s.output.height = 64;
        s
    };
    let separate = scene_with(
        spheres
            .iter()
            .enumerate()
            .map(|(i, m)| common::object(&dir, &format!("s{i}"), m, Vec3::ZERO, Vec3::ONE))
            .collect(),
    );
    let one = scene_with(vec![common::object(
        &dir,
        "all",
        &merged,
        Vec3::ZERO,
        Vec3::ONE,
    )]);
    let a = common::engine(&ctx, &separate).render_image().unwrap();
    let b = common::engine(&ctx, &one).render_image().unwrap();
    assert!(
        a == b,
        "{n} meshes drawn one by one differ from the same triangles as one mesh"
    );
}
