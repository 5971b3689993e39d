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

/// `bench --camera-path` over a scene file and a model (`--obj`): every configuration on every
/// test camera of both, finite figures, the model's radius scaled to its size as the bench's rows
/// are, and the accumulated `rtao` nearer the truth standing still than its single frame.
#[test]
fn the_bench_s_camera_path_runs_scenes_and_models() {
    let dir = temp_dir("bench-camera-path");
    let model = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("Res/meshes/chair.obj");
    let o = run(&[
        "bench",
        "--camera-path",
        "--scene",
        "Res/scenes/demo.toml",
        "--obj",
        model.to_str().unwrap(),
        "--width",
        "160",
        "--height",
        "90",
        "--ref-scale",
        "2",
        "--ref-rays",
        "64",
        "--frames",
        "6",
        "--accumulate",
        "16",
        "--path-rows",
        "rtao-quarter-4",
        "--cache",
        dir.join("cache").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("camera-path.json")).unwrap())
            .unwrap();
    let runs = report["runs"].as_array().unwrap();
    // Two test cameras, three configurations (the lesson, rtao one frame and accumulated), each.
    for scene in ["demo", "chair"] {
        let of: Vec<&serde_json::Value> = runs.iter().filter(|r| r["scene"] == scene).collect();
        assert_eq!(of.len(), 6, "{scene}: {} runs", of.len());
        for r in &of {
            for key in ["still_psnr", "moving_psnr", "moving_flicker", "cost_ratio"] {
                let v = r["summary"][key].as_f64().unwrap();
                assert!(v.is_finite() && v >= 0.0, "{scene} {key} = {v}");
            }
        }
        let still = |label: &str| -> f64 {
            of.iter()
                .filter(|r| r["setting"]["label"] == label)
                .map(|r| r["summary"]["still_psnr"].as_f64().unwrap())
                .sum()
        };
        assert!(
            still("rtao quarter 4 rays ×16") > still("rtao quarter 4 rays"),
            "{scene}: accumulating did not bring rtao nearer the truth"
        );
    }
    let lesson_of = |scene: &str| {
        runs.iter()
            .find(|r| r["scene"] == scene && r["setting"]["label"] == "sao-lesson")
            .map(|r| r["setting"]["settings"].as_str().unwrap().to_string())
            .unwrap()
    };
    assert!(lesson_of("demo").contains("R 1 m"), "{}", lesson_of("demo"));
    assert!(
        !lesson_of("chair").contains("R 1 m"),
        "{}",
        lesson_of("chair")
    );
    assert!(dir.join("camera-path.md").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}
