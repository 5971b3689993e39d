//! The benchmark's metrics on known inputs, tiny runs of `bench` and `bench --stress` that must
//! produce complete, finite reports, and the inputs `bench` refuses. Speed is never asserted.

use opengl3d::ao::AoMethod;
use opengl3d::res::ResDirs;
use opengl3d::tools::bench::metrics::{self, Fit, Gray};
use opengl3d::tools::bench::{perf, stress};
use std::path::{Path, PathBuf};

fn temp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    if d.exists() {
        std::fs::remove_dir_all(&d).unwrap();
    }
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A smooth test pattern in [0, 1] with some structure (for SSIM and FLIP).
fn pattern(w: usize, h: usize) -> Vec<f32> {
    (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f32, (i / w) as f32);
            0.5 + 0.4 * (x * 0.3).sin() * (y * 0.2).cos()
        })
        .collect()
}

#[test]
fn identical_images_have_zero_error_and_ssim_one() {
    let (w, h) = (40, 30);
    let a = pattern(w, h);
    let m = metrics::compare(Gray::new(w, h, &a), Gray::new(w, h, &a), None, true);
    assert_eq!(m.rmse, 0.0);
    assert_eq!(m.mae, 0.0);
    assert_eq!(m.psnr, metrics::PSNR_CAP_DB);
    assert!((m.ssim - 1.0).abs() < 1e-12, "ssim {}", m.ssim);
    assert!(m.flip.abs() < 1e-6, "flip {}", m.flip);
    assert_eq!(m.pixels, w * h);
}

#[test]
fn known_offset_gives_known_rmse_psnr_and_ssim() {
    let (w, h) = (32, 24);
    let a = vec![0.5f32; w * h];
    let b = vec![0.6f32; w * h];
    let m = metrics::compare(Gray::new(w, h, &a), Gray::new(w, h, &b), None, true);
    let d = 0.6f32 as f64 - 0.5f32 as f64;
    assert!((m.rmse - d).abs() < 1e-9, "rmse {}", m.rmse);
    assert!((m.mae - d).abs() < 1e-9, "mae {}", m.mae);
    // PSNR = 10·log10(1 / 0.01) = 20 dB.
    assert!((m.psnr - 20.0).abs() < 1e-5, "psnr {}", m.psnr);
    // Constant images: SSIM is the luminance term (2·μx·μy + C1) / (μx² + μy² + C1).
    let (x, y, c1) = (0.5f64, 0.6f32 as f64, 1e-4);
    let expected = (2.0 * x * y + c1) / (x * x + y * y + c1);
    assert!(
        (m.ssim - expected).abs() < 1e-9,
        "ssim {} vs {expected}",
        m.ssim
    );
    assert!(m.flip > 0.0 && m.flip < 1.0, "flip {}", m.flip);
    // A larger offset is a larger error in every metric.
    let c = vec![0.9f32; w * h];
    let m2 = metrics::compare(Gray::new(w, h, &a), Gray::new(w, h, &c), None, true);
    assert!(m2.rmse > m.rmse && m2.psnr < m.psnr && m2.ssim < m.ssim && m2.flip > m.flip);
}

#[test]
fn masked_pixels_are_ignored() {
    let (w, h) = (16, 16);
    let a = pattern(w, h);
    let mut b = a.clone();
    let mut mask = vec![true; w * h];
    for i in 0..w {
        b[i] = 1.0 - a[i]; // the first row differs...
        mask[i] = false; // ...and is masked out
    }
    let (mse, mae, n) = metrics::mse_mae(&a, &b, Some(&mask));
    assert_eq!((mse, mae, n), (0.0, 0.0, w * (h - 1)));
    let m = metrics::compare(Gray::new(w, h, &a), Gray::new(w, h, &b), Some(&mask), false);
    assert_eq!(m.rmse, 0.0);
    assert_eq!(m.flip, 0.0, "FLIP off reports 0");
}

#[test]
fn fit_maps_a_biased_method_onto_the_reference() {
    // The reference is v^2 · 0.95: the fit must find it and remove almost all the error.
    let v: Vec<f32> = (0..2000).map(|i| (i as f32 + 0.5) / 2000.0).collect();
    let r: Vec<f32> = v.iter().map(|x| 0.95 * x * x).collect();
    let pairs: Vec<(f32, f32)> = v.iter().copied().zip(r.iter().copied()).collect();
    let fit = metrics::fit_power(&pairs);
    let fitted = fit.apply_all(&v);
    let (before, _, _) = metrics::mse_mae(&r, &v, None);
    let (after, _, _) = metrics::mse_mae(&r, &fitted, None);
    assert!(after < before * 1e-3, "fit {fit:?}: mse {before} → {after}");
    assert_eq!(Fit::IDENTITY.apply(0.25), 0.25);
}

fn assert_all_finite(path: &str, v: &serde_json::Value) {
    match v {
        serde_json::Value::Null => panic!("{path} is null (a NaN or Inf serialised)"),
        serde_json::Value::Number(n) => {
            let f = n.as_f64().unwrap();
            assert!(f.is_finite(), "{path} = {f}");
        }
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                assert_all_finite(&format!("{path}[{i}]"), x);
            }
        }
        serde_json::Value::Object(o) => {
            for (k, x) in o {
                assert_all_finite(&format!("{path}.{k}"), x);
            }
        }
        _ => {}
    }
}

#[test]
fn tiny_bench_writes_a_complete_finite_report() {
    let out = temp_dir("bench-tiny");
    let cfg = perf::PerfConfig {
        scenes: Vec::new(),
        models: Vec::new(),
        width: 96,
        height: 54,
        out: out.clone(),
        methods: vec![AoMethod::SaoLesson, AoMethod::Gtao],
        samples: vec![4, 8],
        radii: vec![1.0],
        qualities: Vec::new(),
        ref_rays: 8,
        screen_rays: 8,
        ref_scale: 1,
        cache: out.join("cache"),
        warmup: 0,
        frames: 2,
        flip: true,
        charts: true,
        progress: false,
        ceilings: true,
        grid: perf::Grid::Full,
        scaled: Vec::new(),
    };
    let report = perf::run(&ResDirs::default(), &cfg).expect("bench run");
    assert_eq!(report.rows.len(), 4);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_all_finite("report", &json);
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4);
    for row in rows {
        for key in [
            "method", "setting", "width", "height", "passes", "total_ms", "rmse", "mae", "psnr",
            "ssim", "flip",
        ] {
            assert!(row.get(key).is_some(), "row lacks {key}: {row}");
        }
        assert_eq!(row["width"], 96);
        assert_eq!(row["height"], 54);
        let passes = row["passes"].as_object().unwrap();
        assert!(
            passes.keys().any(|k| k.contains("restore")),
            "passes {passes:?}"
        );
        assert!(row["rmse"].as_f64().unwrap() > 0.0);
        let ssim = row["ssim"].as_f64().unwrap();
        assert!((-1.0..=1.0).contains(&ssim));
        let flip = row["flip"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&flip));
        // The fit is evaluated on other cameras than it was made on: it need not win, but it must be sane.
        assert!(row["fitted"]["rmse"].as_f64().unwrap() < 1.0);
    }
    // The error split: the depth buffer's share depends on camera and radius only, so every row
    // (all at R = 1 m) reports the same figures; the sampling share differs between methods.
    let split = |row: &serde_json::Value, key: &str| row[key]["rmse"].as_f64().unwrap();
    let depth_share = split(&rows[0], "depth_buffer_error");
    assert!(depth_share > 0.0 && depth_share < 1.0, "{depth_share}");
    for row in rows {
        assert_eq!(split(row, "depth_buffer_error"), depth_share);
        assert!(split(row, "sampling_error") > 0.0);
        // The split is computed on the test cameras only (their screen-space references).
        for cam in row["cameras"].as_array().unwrap() {
            let pixels = cam["depth_buffer_error"]["pixels"].as_u64().unwrap();
            assert_eq!(pixels > 0, cam["train"] == false, "{cam}");
        }
    }
    assert_ne!(
        split(&rows[0], "sampling_error"),
        split(&rows[2], "sampling_error")
    );
    assert!(report.reference.screen_rendered > 0);
    assert_eq!(rows[0]["method"], "sao-lesson");
    assert_eq!(rows[2]["method"], "gtao");
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("| sao-lesson | n4 r1 |") && md.contains("| gtao | n8 r1 |"),
        "{md}"
    );
    assert!(md.contains("## Error split") && md.contains("screen-space reference"));
    crate::bench_html::check(&out, 4);
    // The ceiling's error map beside each row's picture is the depth buffer's share at the
    // pictured camera (each test camera): the same truth, pixels and figure as the split's.
    for row in rows {
        for pictures in row["pictures"].as_array().unwrap() {
            let camera = pictures["camera"].as_str().unwrap();
            let cam = row["cameras"]
                .as_array()
                .unwrap()
                .iter()
                .find(|c| c["camera"] == camera)
                .unwrap();
            let want = cam["depth_buffer_error"]["psnr"].as_f64().unwrap();
            let got = pictures["ceiling_psnr"].as_f64().unwrap();
            assert!((got - want).abs() < 0.01, "{got} vs {want}: {row}");
        }
    }
    // A second run reads the references from the cache.
    let again = perf::run(
        &ResDirs::default(),
        &perf::PerfConfig {
            methods: vec![AoMethod::SaoLesson],
            samples: vec![4],
            charts: false,
            ..cfg
        },
    )
    .expect("second run");
    assert_eq!(again.reference.rendered, 0);
    assert!(again.reference.cached > 0);
    assert_eq!(again.reference.screen_rendered, 0);
    assert!(again.reference.screen_cached > 0);
}

#[test]
fn unknown_method_names_are_rejected_with_the_list() {
    let e = opengl3d::tools::bench::catalog::method_by_name("ssao-deluxe")
        .unwrap_err()
        .to_string();
    assert!(e.contains("sao-lesson") && e.contains("gtao"), "{e}");
    assert_eq!(
        opengl3d::tools::bench::catalog::method_by_name("hbao").unwrap(),
        AoMethod::Hbao
    );
}

#[test]
fn tiny_stress_run_has_no_nan_or_inf() {
    let out = temp_dir("stress-tiny");
    let cfg = stress::StressConfig {
        out: out.clone(),
        large: false,
        quick: true,
        progress: false,
    };
    let report = stress::run(&ResDirs::default(), &cfg).expect("stress run");
    assert!(report.cases.len() >= 8, "{} cases", report.cases.len());
    assert_eq!(report.total_non_finite, 0);
    for c in &report.cases {
        assert_eq!(c.non_finite, 0, "{}: NaN/Inf", c.name);
        assert!(c.ok, "{}: {:?}", c.name, c.failures);
    }
    // Depth reconstruction of a facing plane: within a millimetre up to 100 m at near 0.35, far 1000.
    let d = &report.depth_precision[0];
    assert_eq!((d.near, d.far), (0.35, 1000.0));
    for s in d.samples.iter().filter(|s| s.distance <= 100.0) {
        assert!(
            s.engine_d32.abs() < 1e-3 * s.distance.max(1.0),
            "z {}: error {}",
            s.distance,
            s.engine_d32
        );
    }
    // The stand-alone probe with the engine's format reproduces the engine's figures.
    for s in &d.samples {
        let probe = s
            .probe
            .iter()
            .find(|p| p.0 == "DEPTH_COMPONENT32")
            .and_then(|p| p.1)
            .unwrap();
        assert!(
            (probe - s.engine_d32).abs() <= 1e-6 * s.distance,
            "z {}: engine {} probe {probe}",
            s.distance,
            s.engine_d32
        );
    }
    // Reversed-Z with a float depth buffer (when glClipControl is there) is far more precise.
    let last = d.samples.last().unwrap();
    if let Some(rev) = last
        .probe
        .iter()
        .find(|p| p.0.contains("reversed"))
        .and_then(|p| p.1)
    {
        assert!(
            rev.abs() <= last.engine_d32.abs(),
            "reversed-Z {rev} vs engine {}",
            last.engine_d32
        );
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("stress.json")).unwrap()).unwrap();
    assert_eq!(json["total_non_finite"], 0);
    assert!(out.join("stress.md").is_file());
}

/// `opengl3d bench` with extra arguments; it must stop at the argument check, before any rendering.
fn bench_cli(args: &[&str]) -> std::process::Output {
    crate::common::bin()
        .arg("bench")
        .args(args)
        .output()
        .expect("run opengl3d")
}

#[test]
fn reference_rays_and_scale_out_of_range_are_refused() {
    for (flag, value, range) in [
        ("--ref-rays", "0", "1..=65536"),
        ("--ref-rays", "65537", "1..=65536"),
        ("--screen-rays", "0", "1..=65536"),
        ("--ref-scale", "0", "1..=16"),
        ("--ref-scale", "1000", "1..=16"),
    ] {
        let out = temp_dir("bench-cli-range");
        let o = bench_cli(&[flag, value, "--out", out.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        // clap's usage errors exit with 2, before anything runs or is written.
        assert_eq!(o.status.code(), Some(2), "{flag} {value}: {stderr}");
        assert!(
            stderr.contains(flag) && stderr.contains(value) && stderr.contains(range),
            "{flag} {value}: {stderr}"
        );
        assert!(!out.join("report.json").exists());
    }
}

#[test]
fn library_runs_refuse_the_same_ranges() {
    let out = temp_dir("bench-lib-range");
    let base = perf::PerfConfig {
        scenes: Vec::new(),
        models: Vec::new(),
        width: 32,
        height: 18,
        out: out.clone(),
        methods: vec![AoMethod::SaoLesson],
        samples: vec![4],
        radii: vec![1.0],
        qualities: Vec::new(),
        ref_rays: 8,
        screen_rays: 8,
        ref_scale: 1,
        cache: out.join("cache"),
        warmup: 0,
        frames: 1,
        flip: false,
        charts: false,
        progress: false,
        ceilings: true,
        grid: perf::Grid::Full,
        scaled: Vec::new(),
    };
    for (cfg, flag) in [
        (
            perf::PerfConfig {
                ref_rays: 0,
                ..base.clone()
            },
            "--ref-rays 0",
        ),
        (
            perf::PerfConfig {
                screen_rays: 0,
                ..base.clone()
            },
            "--screen-rays 0",
        ),
        (
            perf::PerfConfig {
                ref_scale: 0,
                ..base.clone()
            },
            "--ref-scale 0",
        ),
        (
            perf::PerfConfig {
                ref_scale: 17,
                ..base.clone()
            },
            "--ref-scale 17",
        ),
    ] {
        let e = perf::run(&ResDirs::default(), &cfg)
            .unwrap_err()
            .to_string();
        assert!(e.contains(flag), "{flag}: {e}");
    }
    assert!(!out.join("report.json").exists());
}
