//! The window's truth view, without a window: the truth traced on its worker thread and the error
//! map of the window's path score the same PSNR as `opengl3d reference` followed by
//! `render --view error --truth`, two separate processes, for the same camera and method.

use crate::common;
use opengl3d::ao::AoMethod;
use opengl3d::platform::window::truth::{truth_size, TruthRequest, TruthState, TruthStatus};
use opengl3d::platform::window::truth_view::{evaluate, view_key};
use opengl3d::scene::SceneDesc;
use opengl3d::tools::error_map;
use opengl3d::tools::window_truth::CpuTruth;
use std::sync::Arc;

const W: u32 = 64;
const H: u32 = 48;

/// PSNR (dB) on `render --view error`'s stdout.
fn psnr_of(stdout: &[u8]) -> f64 {
    let text = String::from_utf8_lossy(stdout);
    text.split("PSNR ")
        .nth(1)
        .and_then(|s| s.split(" dB").next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no PSNR on stdout:\n{text}"))
}

#[test]
fn window_truth_scores_the_psnr_of_render_view_error() {
    let dir = common::temp_dir("window-truth");
    let (tw, th) = truth_size(W, H).unwrap();
    assert_eq!((tw, th), (W / 4, H / 4));
    let size = ["--width", &W.to_string(), "--height", &H.to_string()].map(String::from);
    let truth_size_flags =
        ["--width", &tw.to_string(), "--height", &th.to_string()].map(String::from);

    // The command line: the reference at the truth's size, each pixel the mean over the window
    // pixels the map averages onto it, then the error map of hbao against it.
    let truth_file = dir.join("truth.pfm");
    let mut args = vec!["reference".to_string(), "--out".into()];
    args.push(truth_file.to_str().unwrap().into());
    args.extend(truth_size_flags);
    args.extend(["--supersample".into(), (W / tw).to_string()]);
    let o = common::run(&args);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let mut args = vec![
        "--lang", "en", "render", "--view", "error", "--method", "hbao",
    ]
    .into_iter()
    .map(String::from)
    .collect::<Vec<_>>();
    args.extend(["--truth".into(), truth_file.to_str().unwrap().into()]);
    args.extend([
        "--out".into(),
        dir.join("error.png").to_str().unwrap().into(),
    ]);
    args.extend(size);
    let o = common::run(&args);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let cli_psnr = psnr_of(&o.stdout);

    // The window's path: the same scene in an engine, the truth on the worker thread.
    let mut scene =
        SceneDesc::load(&opengl3d::res::project_res_dir().join("scenes/demo.toml")).unwrap();
    scene.output.width = W;
    scene.output.height = H;
    scene.ao.method = AoMethod::Hbao;
    // As the window's M key and `render --method` do: the method's recommended configuration.
    opengl3d::scene::ao_defaults::apply(&mut scene.ao);
    let ctx = common::context();
    let mut engine = common::engine(&ctx, &scene);
    let backend = Arc::new(CpuTruth {
        cache_dir: None,
        rays: opengl3d::tools::window_truth::TRUTH_RAYS,
    });
    let key = view_key(&engine).unwrap();
    let mut state = TruthState::default();
    let request = TruthRequest {
        camera: engine.camera,
        radius: engine.ao_settings.radius,
        width: tw,
        height: th,
        footprint: W / tw,
        triangles: Arc::new(engine.world_triangles()),
    };
    assert!(state.request(key, request, backend.clone()));
    state.wait();
    let TruthStatus::Ready(truth) = state.status(&key) else {
        panic!("no truth: {:?}", state.status(&key));
    };
    // The traced truth is the reference file's, pixel for pixel.
    let (fw, fh, _, file) = opengl3d::io::read_pfm(&truth_file).unwrap();
    assert_eq!((fw, fh), (tw, th));
    assert_eq!(truth.ao, file);
    let picture = evaluate(&mut engine, &truth, backend.as_ref()).unwrap();
    assert!(
        (picture.psnr - cli_psnr).abs() < 0.006,
        "window {:.3} dB, render --view error {cli_psnr} dB",
        picture.psnr
    );
    // A real comparison, not a picture against itself; the picture is the error map's.
    assert!(
        picture.psnr < 60.0 && picture.psnr > 5.0,
        "{}",
        picture.psnr
    );
    let z = error_map::zoom(tw as usize) as u32;
    assert_eq!(picture.image.width(), tw * z);
    // Another method scores differently against the same truth.
    engine.ao_settings.method = AoMethod::Crytek;
    let other = evaluate(&mut engine, &truth, backend.as_ref()).unwrap();
    assert!(
        (other.psnr - picture.psnr).abs() > 0.01,
        "{} {}",
        other.psnr,
        picture.psnr
    );
}
