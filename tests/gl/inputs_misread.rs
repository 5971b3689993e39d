//! Inputs that used to be misread: a folder or a broken link standing at a shader's name in `--res`,
//! a symbolic link in a lesson folder, a FIFO as a model or scene, a scene's mesh that is nowhere,
//! `--screenshot` without `--frames`, a display that is not there, a too large shader's message.
//! Each gets one clear message naming the file, never a silent fallback or a hang.

use crate::common::{fails_with, run, stderr, temp_dir};
use std::path::Path;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_folder_or_broken_link_at_a_shader_name_is_named_not_replaced() {
    let dir = temp_dir("misread-res");
    let simple = opengl3d::res::project_res_dir().join("simple.frag");
    let out = dir.join("x.png");
    let folder = dir.join("folder");
    std::fs::create_dir_all(folder.join("sao.frag")).unwrap();
    std::fs::copy(&simple, folder.join("simple.frag")).unwrap();
    fails_with(
        &["render", "--res", s(&folder), "--out", s(&out)],
        &["sao.frag is a folder, not a file"],
    );
    let looped = dir.join("looped");
    std::fs::create_dir_all(&looped).unwrap();
    std::os::unix::fs::symlink("b.link", looped.join("a.link")).unwrap();
    std::os::unix::fs::symlink("a.link", looped.join("b.link")).unwrap();
    std::os::unix::fs::symlink("a.link", looped.join("sao.frag")).unwrap();
    // Only the loop in the folder: named, rather than "holds none of the files".
    fails_with(
        &["render", "--res", s(&looped), "--out", s(&out)],
        &["sao.frag is a symbolic link that leads nowhere or in a loop"],
    );
    assert!(!out.exists());
}

#[test]
fn lesson_start_never_writes_through_a_symbolic_link() {
    let dir = temp_dir("misread-lesson");
    let outside = dir.join("outside.frag");
    let lesson = dir.join("lesson");
    std::fs::create_dir_all(&lesson).unwrap();
    std::os::unix::fs::symlink(&outside, lesson.join("sao.frag")).unwrap();
    let o = run(&["lesson", "start", s(&lesson)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(e.contains("sao.frag") && e.contains("symbolic link"), "{e}");
    assert!(
        !outside.exists(),
        "wrote through the link to {}",
        outside.display()
    );
    assert!(
        lesson.join("simple.frag").is_file(),
        "the other files are written"
    );
}

#[test]
fn a_fifo_as_model_or_scene_is_an_error_not_a_wait() {
    let dir = temp_dir("misread-fifo");
    for name in ["pipe.obj", "pipe.glb", "pipe.toml"] {
        let c = std::ffi::CString::new(s(&dir.join(name))).unwrap();
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    }
    // Nobody writes to the FIFOs: an open that waited for a writer would hang the test.
    for model in ["pipe.obj", "pipe.glb"] {
        fails_with(
            &["render", "--obj", s(&dir.join(model))],
            &[model, "is not a regular file"],
        );
    }
    fails_with(
        &["render", "--scene", s(&dir.join("pipe.toml"))],
        &["pipe.toml", "empty"],
    );
}

#[test]
fn a_missing_mesh_is_named_at_its_line_with_the_folders_searched() {
    let dir = temp_dir("misread-mesh");
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        "[camera]\nfov_y = 50\n\n[[object]]\nmesh = \"nowhere.obj\"\n",
    )
    .unwrap();
    let e = fails_with(
        &["render", "--scene", s(&scene)],
        &["scene.toml:5:8", "nowhere.obj", s(&dir)],
    );
    let res = opengl3d::res::project_res_dir();
    assert!(e.contains(&res.display().to_string()), "{e}");
}

#[test]
fn screenshot_display_and_size_messages_are_plain() {
    // --screenshot needs --frames (the picture is taken when the frames are shown).
    fails_with(&["window", "--screenshot", "shot.png"], &["--frames"]);
    // A display that is not there: the cause and what to do, without winit's source path.
    let o = crate::common::bin()
        .args(["window", "--frames", "1"])
        .env("DISPLAY", ":97")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert!(e.contains("cannot connect to the display"), "{e}");
    assert!(!e.contains(".rs:"), "no source path:\n{e}");
    // A shader over 1 MiB: the refusal is said once.
    let dir = temp_dir("misread-big");
    std::fs::write(dir.join("sao.frag"), vec![b'a'; 2 << 20]).unwrap();
    let e = fails_with(
        &["render", "--res", s(&dir), "--out", s(&dir.join("x.png"))],
        &["sao.frag", "1 MiB"],
    );
    assert_eq!(e.matches("are refused").count(), 1, "{e}");
}

#[test]
fn a_class_report_cell_says_not_submitted_once() {
    let dir = temp_dir("misread-class");
    std::fs::create_dir_all(dir.join("class/bob")).unwrap();
    let report = dir.join("report");
    let o = run(&[
        "grade",
        "--class",
        s(&dir.join("class")),
        "--out",
        s(&report),
    ]);
    assert!(!o.status.success(), "bob passed nothing");
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    assert!(
        html.contains("<b>not submitted</b><div class=\"why\">no sao.frag in"),
        "{html}"
    );
    assert!(!html.contains("<div class=\"why\">not submitted"), "{html}");
}
