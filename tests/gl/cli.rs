//! The `opengl3d` binary: headless renders, the window under Xvfb, and clear errors on bad input.

use crate::common;
use crate::common::{fails_with, run, stderr};

use opengl3d::io::read_pfm;
use opengl3d::scene::shapes;
use std::path::Path;
use std::process::Command;

#[test]
fn render_writes_the_demo_png_at_the_requested_size() {
    let dir = common::temp_dir("cli-render");
    let out = dir.join("frame.png");
    let o = run(&[
        "render",
        "--width",
        "160",
        "--height",
        "90",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(&out).unwrap();
    assert_eq!((img.width(), img.height()), (160, 90));
}

#[test]
fn ao_view_as_pfm_is_visibility_with_visible_occlusion() {
    let dir = common::temp_dir("cli-ao");
    let out = dir.join("ao.pfm");
    let o = run(&[
        "render",
        "--width",
        "320",
        "--height",
        "180",
        "--view",
        "ao",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, c, v) = read_pfm(&out).unwrap();
    assert_eq!((w, h, c), (320, 180, 1));
    assert!(v.iter().all(|a| a.is_finite() && (0.0..=1.0).contains(a)));
    let occluded = v.iter().filter(|a| **a < 0.8).count();
    assert!(
        occluded > 200,
        "the demo should show AO in creases ({occluded} pixels below 0.8)"
    );
    assert_eq!(v[0], 1.0, "top-left is sky: visibility 1");
}

#[test]
fn linear_depth_pfm_is_metres() {
    // A floor seen from straight above at 5 m: every pixel is 5 m away along the view axis.
    let dir = common::temp_dir("cli-depth");
    let floor = dir.join("floor.obj");
    std::fs::write(&floor, shapes::to_obj(&shapes::ground(50.0, 4), "floor")).unwrap();
    let out = dir.join("depth.pfm");
    let o = run(&[
        "render",
        "--obj",
        floor.to_str().unwrap(),
        "--eye",
        "0,5,0",
        "--target",
        "0,0,0",
        "--near",
        "0.35",
        "--width",
        "64",
        "--height",
        "48",
        "--view",
        "linear-depth",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (_, _, _, v) = read_pfm(&out).unwrap();
    for d in v {
        assert!((d - 5.0).abs() < 5e-4, "depth {d} should be 5 m");
    }
}

fn assert_fails_naming(args: &[&str], needles: &[&str]) {
    fails_with(args, needles);
}

#[test]
fn bad_input_gives_clear_errors() {
    let dir = common::temp_dir("cli-bad");
    let missing = dir.join("nothere.obj");
    assert_fails_naming(
        &["render", "--obj", missing.to_str().unwrap()],
        &["nothere.obj", "not found"],
    );

    let bad_obj = dir.join("broken.obj");
    std::fs::write(&bad_obj, "v 0 0 0\nv 1 0 0\nv zero 1 0\nf 1 2 3\n").unwrap();
    assert_fails_naming(
        &[
            "render",
            "--obj",
            bad_obj.to_str().unwrap(),
            "--out",
            dir.join("x.png").to_str().unwrap(),
        ],
        &["broken.obj"],
    );

    let no_faces = dir.join("empty.obj");
    std::fs::write(&no_faces, "# nothing\nv 0 0 0\n").unwrap();
    assert_fails_naming(
        &["render", "--obj", no_faces.to_str().unwrap()],
        &["empty.obj", "no faces"],
    );

    let res = dir.join("res");
    std::fs::create_dir_all(&res).unwrap();
    let src =
        std::fs::read_to_string(opengl3d::res::project_res_dir().join("sao_blur.frag")).unwrap();
    let line = src
        .lines()
        .position(|l| l.contains("outColor /= totalWeight;"))
        .unwrap()
        + 1;
    std::fs::write(
        res.join("sao_blur.frag"),
        src.replace("outColor /= totalWeight;", "outColor /= totalWeight"),
    )
    .unwrap();
    // The missing ';' is reported on the next token's line or this one.
    let o = run(&[
        "--res",
        res.to_str().unwrap(),
        "render",
        "--width",
        "32",
        "--height",
        "32",
        "--out",
        dir.join("y.png").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let e = stderr(&o);
    let file = res.join("sao_blur.frag").display().to_string();
    assert!(
        e.contains(&format!("{file}:{line}:")) || e.contains(&format!("{file}:{}:", line + 1)),
        "expected {file}:{line}, got:\n{e}"
    );

    assert_fails_naming(&["render", "--width", "0"], &["size"]);
    assert_fails_naming(&["render", "--fov", "500"], &["fov"]);
    assert_fails_naming(&["render", "--near", "10", "--far", "1"], &["near"]);
    assert_fails_naming(&["render", "--eye", "1,2"], &["x,y,z"]);
    assert_fails_naming(
        &[
            "render",
            "--width",
            "16",
            "--height",
            "16",
            "--out",
            dir.join("z.jpg").to_str().unwrap(),
        ],
        &[".png or .pfm"],
    );
}

#[test]
fn demo_meshes_in_res_match_their_generator() {
    let dir = opengl3d::res::project_res_dir().join("meshes");
    for (name, what, mesh) in shapes::demo_meshes() {
        let on_disk = std::fs::read_to_string(dir.join(name)).unwrap_or_default();
        assert_eq!(
            on_disk,
            shapes::to_obj(&mesh, what),
            "Res/meshes/{name} is stale: run `cargo run -- gen-demo`"
        );
    }
}

/// Runs the window under Xvfb for a few frames and compares its last frame with a headless render.
#[test]
fn window_frame_under_xvfb_equals_headless_render() {
    if Command::new("xvfb-run").arg("--help").output().is_err() {
        assert!(
            std::env::var_os("CI").is_none(),
            "xvfb-run is required in CI (.ci/run installs it)"
        );
        eprintln!("xvfb-run not installed: window test not run here (apt-get install xvfb xauth)");
        return;
    }
    let dir = common::temp_dir("window");
    let shot = dir.join("window.png");
    let head = dir.join("headless.png");
    let o = Command::new("xvfb-run")
        .args([
            "-a",
            "-s",
            "-screen 0 640x480x24",
            env!("CARGO_BIN_EXE_opengl3d"),
            "window",
            "--frames",
            "3",
        ])
        .args([
            "--width",
            "200",
            "--height",
            "120",
            "--screenshot",
            shot.to_str().unwrap(),
        ])
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "window run failed:\n{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        stderr(&o)
    );
    let win = image::open(&shot).unwrap().to_rgb8();
    let o = run(&[
        "render",
        "--width",
        &win.width().to_string(),
        "--height",
        &win.height().to_string(),
        "--out",
        head.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let hl = image::open(Path::new(&head)).unwrap().to_rgb8();
    assert_eq!(win.dimensions(), hl.dimensions());
    let max_diff = win
        .pixels()
        .zip(hl.pixels())
        .flat_map(|(a, b)| (0..3).map(move |i| (a[i] as i32 - b[i] as i32).abs()))
        .max()
        .unwrap();
    assert_eq!(
        max_diff, 0,
        "window and headless frames differ (max channel difference {max_diff})"
    );
}

#[test]
fn lesson_start_writes_stubs_that_run_and_never_overwrites() {
    let dir = common::temp_dir("lesson-start");
    let student = dir.join("my-res");
    std::fs::create_dir_all(&student).unwrap();
    std::fs::write(student.join("sao.frag"), "// my own work\n").unwrap();
    let o = run(&["lesson", "start", student.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(student.join("sao.frag")).unwrap(),
        "// my own work\n",
        "existing work must be kept"
    );
    let stub = std::fs::read_to_string(student.join("sao_restore_depth.frag")).unwrap();
    assert!(
        stub.contains("Lesson step 2"),
        "restore shader should be the stub"
    );
    std::fs::remove_file(student.join("sao.frag")).unwrap();
    let o = run(&["lesson", "start", student.to_str().unwrap()]);
    assert!(o.status.success());
    // With the stubs every step runs; step 2's linear depth is the stub's 0 everywhere.
    let out = dir.join("step2.pfm");
    let o = run(&[
        "--res",
        student.to_str().unwrap(),
        "lesson",
        "2",
        "--headless",
        "--width",
        "32",
        "--height",
        "24",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (_, _, _, v) = read_pfm(&out).unwrap();
    assert!(v.iter().all(|d| *d == 0.0));
    for step in ["6", "11", "12"] {
        let out = dir.join(format!("step{step}.png"));
        let o = run(&[
            "--res",
            student.to_str().unwrap(),
            "lesson",
            step,
            "--headless",
            "--width",
            "32",
            "--height",
            "24",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "step {step}: {}", stderr(&o));
    }
    assert_fails_naming(&["lesson", "13", "--headless"], &["1 to 12"]);
}

fn stats(args: &[&str]) -> Vec<(String, String, u64)> {
    let dir = common::temp_dir("cli-stats");
    let out = dir.join(format!(
        "frame{}.png",
        args.join("_").replace(['-', '/', ','], "")
    ));
    let mut all = vec![
        "render",
        "--stats",
        "--width",
        "64",
        "--height",
        "48",
        "--out",
        out.to_str().unwrap(),
    ];
    all.extend_from_slice(args);
    let o = run(&all);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).expect("stdout is JSON");
    json["passes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            assert!(p["ms"].as_f64().unwrap() >= 0.0);
            (
                p["name"].as_str().unwrap().to_string(),
                p["group"].as_str().unwrap().to_string(),
                p["draw_calls"].as_u64().unwrap(),
            )
        })
        .collect()
}

#[test]
fn stats_show_which_passes_run_and_skips() {
    let on = stats(&[]);
    let groups: Vec<&str> = on.iter().map(|p| p.1.as_str()).collect();
    for g in ["shadow", "opaque", "ao", "sky", "bloom", "post"] {
        assert!(groups.contains(&g), "group {g} missing from {on:?}");
    }
    assert!(on.iter().any(|p| p.0 == "sao blur" && p.2 == 1), "{on:?}");
    assert!(
        on.iter().find(|p| p.0 == "opaque").unwrap().2 >= 10,
        "one draw call per demo object"
    );

    let off = stats(&["--ao", "off"]);
    assert!(
        off.iter().all(|p| p.1 != "ao"),
        "AO off must run no AO pass: {off:?}"
    );

    let depth = stats(&["--view", "linear-depth"]);
    let names: Vec<&str> = depth.iter().map(|p| p.0.as_str()).collect();
    assert!(names.contains(&"sao restore depth") && names.contains(&"sao down sampling"));
    for skipped in [
        "sao",
        "sao blur",
        "sao composite",
        "sky",
        "bloom",
        "shadow map",
    ] {
        assert!(
            !names.contains(&skipped),
            "linear-depth view must skip {skipped}: {names:?}"
        );
    }
}

#[test]
fn objects_outside_the_view_are_culled() {
    let all = stats(&[]);
    let opaque_all = all.iter().find(|p| p.0 == "opaque").unwrap().2;
    // Looking out of the courtyard (towards +Z): only the floor and the left wall remain in view.
    let away = stats(&["--eye", "0,1.6,6", "--target", "0,1.6,20"]);
    let opaque_away = away.iter().find(|p| p.0 == "opaque").unwrap().2;
    assert_eq!(opaque_all, 13, "every demo object is in the default view");
    assert!(
        opaque_away < 4,
        "looking away should draw only what is in view ({opaque_away} draw calls)"
    );
}

/// `opengl3d lesson` without a step lists the steps; `lesson start` on a folder whose lesson shaders
/// exist keeps them and says so instead of calling them stubs.
#[test]
fn lesson_without_a_step_lists_them_and_start_keeps_written_shaders() {
    let o = run(&["lesson"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    for want in [
        "lesson start DIR",
        " 1  shows linear depth",
        "12  shows composite",
    ] {
        assert!(out.contains(want), "missing '{want}' in:\n{out}");
    }
    let dir = common::temp_dir("cli-lesson-start").join("mine");
    let dir_s = dir.to_str().unwrap();
    let first = run(&["lesson", "start", dir_s]);
    assert!(first.status.success(), "{}", stderr(&first));
    assert!(String::from_utf8_lossy(&first.stdout).contains("the 5 lesson shaders are stubs"));
    std::fs::write(
        dir.join("sao.frag"),
        "#version 450\n// the student's work\n",
    )
    .unwrap();
    let again = run(&["lesson", "start", dir_s]);
    assert!(again.status.success(), "{}", stderr(&again));
    let said = String::from_utf8_lossy(&again.stdout);
    assert!(
        said.contains("kept, none replaced by a stub") && !said.contains("are stubs"),
        "{said}"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("sao.frag")).unwrap(),
        "#version 450\n// the student's work\n"
    );
}

/// A model in millimetres (a 1 m floor with a 300 mm box on it, written ×1000): `--obj` frames it and
/// picks the AO radius from its size, so the crease around the box darkens; with a radius of 1 unit
/// (1 mm) it does not.
#[test]
fn a_model_in_millimetres_gets_a_radius_of_its_own_scale() {
    let dir = common::temp_dir("cli-mm");
    let mut m = shapes::ground(500.0, 4);
    opengl3d::scene::shapes::add_box(
        &mut m,
        glam::Vec3::new(-150.0, 0.0, -150.0),
        glam::Vec3::new(150.0, 300.0, 150.0),
    );
    let obj = dir.join("mm.obj");
    std::fs::write(&obj, shapes::to_obj(&m, "mm")).unwrap();
    let darkened = |extra: &[&str]| {
        let out = dir.join("ao.pfm");
        let mut args = vec![
            "render",
            "--obj",
            obj.to_str().unwrap(),
            "--method",
            "vbao",
            "--view",
            "ao",
            "--width",
            "320",
            "--height",
            "240",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = run(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let (_, _, _, v) = read_pfm(&out).unwrap();
        (v.iter().filter(|x| **x < 0.9).count(), stderr(&o))
    };
    let (auto, said) = darkened(&[]);
    assert!(said.contains("AO radius"), "{said}");
    let (one_unit, _) = darkened(&["--radius", "1"]);
    assert!(
        auto > 200 && one_unit < 10,
        "darker than 0.9: auto radius {auto}, 1 unit {one_unit}"
    );
}

/// `render --stats` with `env` set: its JSON.
fn stats_json(env: &[(&str, &str)]) -> serde_json::Value {
    let dir = common::temp_dir("cli-stats-clock");
    let out = dir.join(format!("frame{}.png", env.len()));
    let mut cmd = common::bin();
    cmd.envs(env.iter().copied()).args([
        "render", "--stats", "--width", "48", "--height", "32", "--out",
    ]);
    let o = cmd.arg(&out).output().expect("run opengl3d");
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).expect("stdout is JSON")
}

#[test]
fn stats_name_their_clock_and_software_gl_gets_the_wall_clock() {
    // Forced onto Mesa's software device: its timer queries do not measure real time, so every
    // figure is the wall clock around glFinish, and says so.
    let soft = stats_json(&[("OPENGL3D_DEVICE", "software")]);
    let renderer = soft["renderer"].as_str().unwrap().to_ascii_lowercase();
    assert!(
        renderer.contains("llvmpipe") || renderer.contains("softpipe"),
        "{renderer}"
    );
    assert_eq!(soft["clock"], "wall clock", "{soft}");
    assert!(
        soft["timing"].as_str().unwrap().contains("glFinish"),
        "{soft}"
    );
    let passes = soft["passes"].as_array().unwrap();
    assert!(!passes.is_empty());
    for p in passes {
        assert_eq!(p["clock"], "wall clock", "{p}");
        // On the wall clock the figure is the wall time itself.
        assert_eq!(p["ms"], p["wall_ms"], "{p}");
    }
    // Whatever device the machine has, each pass names one of the two clocks, and the GPU timer
    // only off software GL.
    let any = stats_json(&[]);
    let renderer = any["renderer"].as_str().unwrap().to_ascii_lowercase();
    let software = renderer.contains("llvmpipe") || renderer.contains("softpipe");
    let want = if software { "wall clock" } else { "gpu timer" };
    assert_eq!(any["clock"], want, "{any}");
    for p in any["passes"].as_array().unwrap() {
        let clock = p["clock"].as_str().unwrap();
        assert!(clock == "wall clock" || clock == "gpu timer", "{p}");
        assert!(p["ms"].as_f64().unwrap() >= 0.0 && p["wall_ms"].as_f64().unwrap() >= 0.0);
    }
}
