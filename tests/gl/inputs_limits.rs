//! Inputs that are not what they seem: endless or empty files, folders, negative numbers. Each gets
//! a message about that file or value, quickly, and never a read until memory runs out.

use crate::common::{fails_with, temp_dir};
use std::time::{Duration, Instant};

fn s(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn endless_and_empty_files_and_folders_are_named_for_what_they_are() {
    let dir = temp_dir("inputs-limits");
    let out = dir.join("x.png");
    let start = Instant::now();
    for (flag, cap) in [
        ("--scene", "larger than 1 MiB"),
        ("--obj", "is not a regular file"),
    ] {
        fails_with(
            &["render", flag, "/dev/zero", "--out", s(&out)],
            &["/dev/zero", cap],
        );
    }
    assert!(
        start.elapsed() < Duration::from_secs(60),
        "reading /dev/zero must stop at the cap ({:?})",
        start.elapsed()
    );
    let empty = dir.join("empty.toml");
    std::fs::write(&empty, "").unwrap();
    fails_with(
        &["render", "--scene", s(&empty)],
        &["empty.toml", "is empty"],
    );
    fails_with(
        &["render", "--obj", "/dev/null"],
        &["/dev/null", "is not a regular file"],
    );
    let folder = dir.join("model.obj");
    std::fs::create_dir_all(&folder).unwrap();
    let scene_folder = dir.join("scene.toml");
    std::fs::create_dir_all(&scene_folder).unwrap();
    fails_with(
        &["render", "--obj", s(&folder)],
        &["model.obj", "is a folder"],
    );
    fails_with(
        &["render", "--scene", s(&scene_folder)],
        &["scene.toml", "is a folder"],
    );
    let latin1 = dir.join("latin1.toml");
    std::fs::write(&latin1, b"# caf\xe9\n").unwrap();
    fails_with(
        &["render", "--scene", s(&latin1)],
        &["latin1.toml", "not UTF-8", "byte 5"],
    );
    // Root reads any file whatever its mode: the unreadable case only means something as a user.
    if unsafe { libc::geteuid() } != 0 {
        let locked = dir.join("locked.obj");
        std::fs::write(&locked, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o000)).unwrap();
        fails_with(
            &["render", "--obj", s(&locked)],
            &["locked.obj", "permission denied"],
        );
    }
}

#[test]
fn negative_numbers_get_a_message_about_the_value() {
    for (args, needles) in [
        (
            &["grade", "--timeout", "-1"][..],
            &["--timeout -1", "seconds"][..],
        ),
        (&["bench", "--radii", "-1"], &["--radii -1", "above 0"]),
        (&["bench", "--radii", "0.5,-2"], &["--radii -2"]),
        (&["bench", "--samples", "-1"], &["'-1'", "--samples"]),
        (&["bench", "--width", "-5"], &["'-5'", "--width"]),
        (
            &["grade", "--jobs", "-2", "--class", "."],
            &["'-2'", "--jobs"],
        ),
    ] {
        let e = fails_with(args, needles);
        assert!(!e.contains("unexpected argument"), "{args:?}:\n{e}");
    }
}
