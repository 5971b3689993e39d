//! `opengl3d tune` on a tiny run of the demo scene: the chosen table is never worse on the training
//! cameras than the scene's own (which the search starts from), its TOML reads back, and pasted
//! over the scene's `[ao]` the bench measures the same training and test figures; bad inputs are
//! refused with messages that name them.

use opengl3d::ao::{AoMethod, AoSettings};
use opengl3d::res::ResDirs;
use opengl3d::tools::bench::perf;
use opengl3d::tools::tune::{self, Protocol, TuneArgs, TuneConfig};
use std::path::{Path, PathBuf};

fn temp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    if d.exists() {
        std::fs::remove_dir_all(&d).unwrap();
    }
    std::fs::create_dir_all(&d).unwrap();
    d
}

pub(crate) const TINY: Protocol = Protocol {
    width: 96,
    height: 54,
    ref_scale: 1,
    ref_rays: 16,
    warmup: 0,
    frames: 1,
};

fn tiny_config(out: &Path, methods: Vec<AoMethod>) -> TuneConfig {
    TuneConfig {
        scenes: Vec::new(),
        methods,
        method_files: Vec::new(),
        protocol: TINY,
        budget: None,
        passes: 1,
        cache: out.join("cache"),
        out: out.to_path_buf(),
        progress: false,
    }
}

/// The bench at the tiny protocol on `scene`, one method at one sample count and radius, writing
/// under `out` (no charts, no pictures beyond the report's, no progress).
pub(crate) fn tiny_bench(
    scene: &Path,
    (method, samples, radius): (AoMethod, u32, f32),
    out: &Path,
) -> perf::PerfConfig {
    perf::PerfConfig {
        scenes: vec![scene.to_path_buf()],
        models: Vec::new(),
        width: TINY.width,
        height: TINY.height,
        out: out.join("bench"),
        methods: vec![method],
        samples: vec![samples],
        radii: vec![radius],
        qualities: Vec::new(),
        ref_rays: TINY.ref_rays,
        screen_rays: 1,
        ref_scale: TINY.ref_scale,
        cache: out.join("cache"),
        warmup: 0,
        frames: 1,
        flip: false,
        charts: false,
        progress: false,
        ceilings: false,
        grid: perf::Grid::Full,
        scaled: Vec::new(),
    }
}

/// The bench's mean raw PSNR of the training and of the test cameras for `method` on `scene` at
/// the tiny protocol, at the settings' sample count and radius (the rest from the scene's `[ao]`).
fn bench_figures(scene: &Path, ao: &AoSettings, out: &Path) -> (f64, f64) {
    let cfg = tiny_bench(scene, (ao.method, ao.samples, ao.radius), out);
    let report = perf::run(&ResDirs::default(), &cfg).expect("bench run");
    assert_eq!(report.rows.len(), 1);
    let mean = |train: bool| {
        let v: Vec<f64> = report.rows[0]
            .cameras
            .iter()
            .filter(|c| c.train == train)
            .map(|c| c.raw.psnr)
            .collect();
        assert_eq!(v.len(), 2, "two cameras of each kind");
        v.iter().sum::<f64>() / v.len() as f64
    };
    (mean(true), mean(false))
}

#[derive(serde::Deserialize)]
struct AoTable {
    ao: AoSettings,
}

#[test]
fn tuned_table_is_no_worse_on_training_and_reproduces_in_the_bench() {
    let out = temp_dir("tune-tiny");
    let results = tune::run(
        &ResDirs::default(),
        &tiny_config(&out, vec![AoMethod::Vbao]),
    )
    .expect("tune run");
    assert_eq!(results.len(), 1);
    let r = &results[0];
    for v in [r.train_default, r.train_tuned, r.test_default, r.test_tuned] {
        assert!(v.is_finite() && v > 0.0, "{r:?}");
    }
    assert!(r.train_tuned >= r.train_default, "{r:?}");
    // On this scene the slabs thicker than R/2 gain on every camera: a table that differs, so
    // the bench checks below tell the two apart.
    assert_ne!(r.tuned, r.default, "{r:?}");
    assert_eq!(r.keys, ["bias", "thickness"]);
    assert!(r.evaluated > 10, "{r:?}");
    // Without --budget only free keys move: the taps stay the scene's.
    assert_eq!(
        (r.tuned.samples, r.tuned.quality),
        (r.default.samples, r.default.quality)
    );

    // The written table reads back as the chosen settings.
    let text = std::fs::read_to_string(out.join("demo-vbao.toml")).unwrap();
    assert!(text.starts_with("# opengl3d tune"), "{text}");
    let table: AoTable = toml::from_str(&text).expect("tuned TOML parses");
    assert_eq!(table.ao, r.tuned);
    let md = std::fs::read_to_string(out.join("tune.md")).unwrap();
    assert!(md.contains("| demo | vbao |"), "{md}");

    // Pasted over the demo scene's [ao], the bench measures the reported figures; the scene's own
    // table gives the reported defaults.
    let demo = ResDirs::default().find("scenes/demo.toml").unwrap();
    let mut scene: toml::Value = toml::from_str(&std::fs::read_to_string(&demo).unwrap()).unwrap();
    let tuned_ao = toml::from_str::<toml::Value>(&text).unwrap()["ao"].clone();
    scene.as_table_mut().unwrap().insert("ao".into(), tuned_ao);
    let tuned_scene = out.join("demo.toml");
    std::fs::write(&tuned_scene, toml::to_string(&scene).unwrap()).unwrap();
    let (train, test) = bench_figures(&tuned_scene, &r.tuned, &out);
    assert!(
        (train - r.train_tuned).abs() < 1e-3,
        "bench {train} vs tune {}",
        r.train_tuned
    );
    assert!(
        (test - r.test_tuned).abs() < 1e-3,
        "bench {test} vs tune {}",
        r.test_tuned
    );
    // The scene's own table written out in full, as the tuned one is: the bench then runs it as
    // tune did, not the method's recommendation for the keys the scene file leaves unwritten.
    // An unset thickness is written as the one it stands for (R/2), which renders the same.
    let mut written = r.default;
    if written.thickness.is_none() {
        written.thickness = Some(opengl3d::ao::Thickness::Metres(written.thickness_metres()));
    }
    let default_ao = toml::Value::try_from(written).expect("the scene's table as TOML");
    scene
        .as_table_mut()
        .unwrap()
        .insert("ao".into(), default_ao);
    let default_scene = out.join("default").join("demo.toml");
    std::fs::create_dir_all(default_scene.parent().unwrap()).unwrap();
    std::fs::write(&default_scene, toml::to_string(&scene).unwrap()).unwrap();
    let (train, test) = bench_figures(&default_scene, &r.default, &out);
    assert!(
        (train - r.train_default).abs() < 1e-3,
        "bench {train} vs tune {}",
        r.train_default
    );
    assert!(
        (test - r.test_default).abs() < 1e-3,
        "bench {test} vs tune {}",
        r.test_default
    );
}

#[test]
fn bad_inputs_are_refused_with_messages_that_name_them() {
    let out = temp_dir("tune-bad");
    let args = |methods: &[&str]| TuneArgs {
        scenes: Vec::new(),
        methods: methods.iter().map(|m| m.to_string()).collect(),
        method_files: Vec::new(),
        budget: None,
        full: false,
        passes: 2,
        ref_rays: None,
        cache: Some(out.join("cache")),
        out: out.clone(),
    };
    let e = args(&["vbao", "ssao"]).config().unwrap_err().to_string();
    assert!(
        e.contains("unknown AO method 'ssao'") && e.contains("vbao"),
        "{e}"
    );
    let res = ResDirs::default();
    let e = tune::run(&res, &tiny_config(&out, vec![AoMethod::Rtao])).unwrap_err();
    assert!(e.to_string().contains("rtao"), "{e}");
    let missing = out.join("no-such-scene.toml");
    let cfg = TuneConfig {
        scenes: vec![missing.clone()],
        ..tiny_config(&out, vec![AoMethod::Gtao])
    };
    let e = tune::run(&res, &cfg).unwrap_err().to_string();
    assert!(e.contains(&missing.display().to_string()), "{e}");
    for budget in [0.0, -1.0, f64::NAN] {
        let cfg = TuneConfig {
            budget: Some(budget),
            ..tiny_config(&out, vec![AoMethod::Gtao])
        };
        let e = tune::run(&res, &cfg).unwrap_err().to_string();
        assert!(e.contains("--budget"), "{e}");
    }
    assert!(!out.join("tune.md").exists(), "nothing written on refusal");
    // The command line: a clean message and a failing exit, nothing rendered.
    let o = crate::common::bin()
        .args(["tune", "--methods", "ssao", "--out"])
        .arg(&out)
        .output()
        .expect("run opengl3d");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && stderr.contains("ssao"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn a_budget_opens_the_costly_keys_and_one_nothing_fits_is_refused() {
    let out = temp_dir("tune-budget");
    let cfg = TuneConfig {
        budget: Some(1e6),
        ..tiny_config(&out, vec![AoMethod::Hbao])
    };
    let results = tune::run(&ResDirs::default(), &cfg).expect("tune run");
    let r = &results[0];
    // hbao reads no free key: only the budget gives it anything to search.
    assert_eq!(r.keys, ["samples", "resolution", "guard_band", "normals"]);
    assert!(r.train_tuned >= r.train_default, "{r:?}");
    let cost = r.cost.expect("timed under a budget");
    for ratio in [cost.default_ratio, cost.tuned_ratio] {
        assert!(ratio.is_finite() && ratio > 0.0, "{cost:?}");
    }
    assert_eq!(r.over_budget, 0);
    let cfg = TuneConfig {
        budget: Some(1e-9),
        ..tiny_config(&out, vec![AoMethod::Hbao])
    };
    let e = tune::run(&ResDirs::default(), &cfg).unwrap_err();
    assert!(format!("{e:#}").contains("--budget"), "{e:#}");
}
