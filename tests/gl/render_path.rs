//! `render --camera-path N`: numbered frames along the bench's path; the first is the frame
//! `render` writes without a path (the same frames before it), the others see the scene move.

use crate::common::{fails_with, run, stderr, temp_dir};

#[test]
fn a_camera_path_writes_numbered_frames_that_start_where_render_stands() {
    let dir = temp_dir("render-path");
    let common = [
        "render",
        "--method",
        "vbao",
        "--accumulate",
        "4",
        "--width",
        "160",
        "--height",
        "90",
        "--view",
        "ao",
    ];
    let out = dir.join("f.png");
    let mut args = common.to_vec();
    args.extend_from_slice(&["--camera-path", "3", "--out", out.to_str().unwrap()]);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let frames: Vec<Vec<u8>> = (0..3)
        .map(|i| std::fs::read(dir.join(format!("f-00{i}.png"))).unwrap())
        .collect();
    assert!(!dir.join("f.png").exists() && !dir.join("f-003.png").exists());
    let still = dir.join("still.png");
    let mut args = common.to_vec();
    args.extend_from_slice(&["--out", still.to_str().unwrap()]);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        frames[0] == std::fs::read(&still).unwrap(),
        "the path's first frame is not the frame render writes"
    );
    assert!(
        frames[1] != frames[0] && frames[2] != frames[1],
        "the camera did not move"
    );
    // The error view needs a truth per frame: the bench's camera path traces them.
    fails_with(
        &["render", "--camera-path", "2", "--view", "error"],
        &["bench --camera-path"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}
