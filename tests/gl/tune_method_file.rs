//! `opengl3d tune --method-file`: on a method whose only parameter is a constant occlusion, the
//! value chosen is the one the truth's statistics predict (worked out from two bench runs, not by
//! the search); the tuned copy of the file reads back with the chosen default; the example method
//! file is searched and never scores below its default; a file without parameters and a broken
//! file are refused with messages that name them.

use crate::common::{fails_with, temp_dir};
use opengl3d::ao::AoMethod;
use opengl3d::res::ResDirs;
use opengl3d::scene::method_file::MethodFile;
use opengl3d::tools::bench::perf;
use opengl3d::tools::tune::{self, file_space, TuneConfig};
use std::path::{Path, PathBuf};

use crate::tune::{tiny_bench, TINY};

/// Occlusion `OCCLUSION` on every surface pixel: the AO view is the constant `1 - OCCLUSION`.
const CONSTANT_FRAG: &str = "#version 450
#include \"common.glsl\"
void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  float z = -TexelPos(pix).z;
  WriteOcclusion(IsSky(z) ? 0.0 : OCCLUSION, z);
}
";

/// Its default is far from any scene's mean occlusion, so a search that stays put fails.
const CONSTANT_TOML: &str = "name = \"constant\"
shader = \"constant.frag\"
counts = [1, 1]

[[parameter]]
name = \"OCCLUSION\"
default = 0.9
min = 0.0
max = 1.0
";

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn demo() -> PathBuf {
    ResDirs::default().find("scenes/demo.toml").unwrap()
}

/// The bench's per-training-camera MSE of `file` at the tiny protocol on the demo scene.
fn training_mse(file: &MethodFile, radius: f32, out: &Path) -> Vec<f64> {
    // The bench runs an engine method beside the file (one it can run at 11 samples).
    let cfg = tiny_bench(&demo(), (AoMethod::Hbao, 11, radius), out);
    let report = perf::run_with_method_files(&ResDirs::default(), &cfg, std::slice::from_ref(file))
        .expect("bench run");
    assert_eq!(report.rows.len(), 2, "hbao's row, then the file's");
    let mse: Vec<f64> = report.rows[1]
        .cameras
        .iter()
        .filter(|c| c.train)
        .map(|c| c.raw.rmse * c.raw.rmse)
        .collect();
    assert_eq!(mse.len(), 2, "two training cameras");
    mse
}

#[test]
fn a_constant_occlusion_is_tuned_to_the_value_the_truth_predicts() {
    let out = temp_dir("tune-method-file");
    let methods = out.join("methods");
    std::fs::create_dir_all(&methods).unwrap();
    write(&methods, "constant.frag", CONSTANT_FRAG);
    let constant = write(&methods, "constant.toml", CONSTANT_TOML);
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/method-file/my_hbao.toml");
    let cfg = TuneConfig {
        scenes: Vec::new(),
        methods: Vec::new(),
        method_files: vec![constant.clone(), example.clone()],
        protocol: TINY,
        budget: None,
        passes: 2,
        cache: out.join("cache"),
        out: out.clone(),
        progress: false,
    };
    let results = tune::run(&ResDirs::default(), &cfg).expect("tune run");
    assert_eq!(results.len(), 2);
    let (r, hbao) = (&results[0], &results[1]);
    assert_eq!((r.name(), hbao.name()), ("constant", "my-hbao"));
    for r in &results {
        for v in [r.train_default, r.train_tuned, r.test_default, r.test_tuned] {
            assert!(v.is_finite() && v > 0.0, "{r:?}");
        }
        assert!(r.train_tuned >= r.train_default, "{r:?}");
    }
    let chosen = r.file.as_ref().unwrap().parameters[0].tuned;

    // Against a truth t, a constant view v has MSE var(t) + (mean(t) - v)²: the bench's MSE at
    // v = 1 and v = 0 gives each training camera's mean and variance, and with them the mean PSNR
    // of every occlusion the search could try.
    let mut file = MethodFile::read(&constant).unwrap();
    file.set("OCCLUSION", 0.0).unwrap();
    let open = training_mse(&file, r.default.radius, &out);
    file.set("OCCLUSION", 1.0).unwrap();
    let closed = training_mse(&file, r.default.radius, &out);
    let cameras: Vec<(f64, f64)> = open
        .iter()
        .zip(&closed)
        .map(|(m1, m0)| {
            let mean = (m0 - m1 + 1.0) / 2.0;
            (mean, m0 - mean * mean)
        })
        .collect();
    let predicted_psnr = |k: f64| {
        let v = 1.0 - k;
        cameras
            .iter()
            .map(|(mean, var)| -10.0 * (var + (mean - v).powi(2)).log10())
            .sum::<f64>()
            / cameras.len() as f64
    };
    let grid = file_space::grid(0.0, 1.0, file_space::PARAMETER_STEPS);
    let best = grid
        .iter()
        .copied()
        .max_by(|a, b| predicted_psnr(*a as f64).total_cmp(&predicted_psnr(*b as f64)))
        .unwrap();
    let step = 1.0 / file_space::PARAMETER_STEPS as f32;
    assert!(
        (chosen - best).abs() <= step + 1e-6,
        "chose {chosen}, the truth predicts {best} ({cameras:?})"
    );
    assert!(
        (r.train_tuned - predicted_psnr(chosen as f64)).abs() < 0.1,
        "tune {} dB, predicted {} dB",
        r.train_tuned,
        predicted_psnr(chosen as f64)
    );
    assert_ne!(chosen, 0.9, "the default is far from the truth's mean");

    // The tuned copy, saved beside the shader, reads back with the chosen default; the user's
    // file is untouched.
    let tuned = std::fs::read_to_string(out.join("demo-constant.toml")).unwrap();
    assert!(tuned.starts_with("# "), "{tuned}");
    let copy = write(&methods, "tuned.toml", &tuned);
    let back = MethodFile::read(&copy).expect("the tuned copy reads");
    assert_eq!(back.parameters[0].default, chosen);
    assert_eq!(std::fs::read_to_string(&constant).unwrap(), CONSTANT_TOML);
    let ao = std::fs::read_to_string(out.join("demo-constant.ao.toml")).unwrap();
    assert!(ao.contains("--method-file") && ao.contains("[ao]"), "{ao}");
    let md = std::fs::read_to_string(out.join("tune.md")).unwrap();
    assert!(md.contains("| demo | constant |"), "{md}");
    assert!(md.contains("| demo | my-hbao |"), "{md}");

    // The example: its one parameter searched, over its range, on the engine's hbao chain.
    assert_eq!(hbao.keys, ["SIN_BIAS"]);
    assert_eq!(
        hbao.method,
        AoMethod::Vbao,
        "a method file runs in vbao's place"
    );
    let sin_bias = hbao.file.as_ref().unwrap().parameters[0].tuned;
    assert!((0.0..=0.5).contains(&sin_bias), "{sin_bias}");
}

#[test]
fn a_file_with_nothing_to_search_or_a_broken_file_is_refused() {
    let out = temp_dir("tune-method-file-bad");
    write(&out, "constant.frag", CONSTANT_FRAG);
    let none = write(
        &out,
        "none.toml",
        "name = \"none\"\nshader = \"constant.frag\"\n",
    );
    let broken = write(
        &out,
        "broken.toml",
        &CONSTANT_TOML.replace("max = 1.0", "max = -1.0"),
    );
    let out_s = out.to_str().unwrap();
    fails_with(
        &[
            "tune",
            "--method-file",
            none.to_str().unwrap(),
            "--out",
            out_s,
        ],
        &["none.toml", "[[parameter]]", "nothing to search"],
    );
    // The same place `render --method-file` names: the max below its min, line 9 column 7.
    let e = fails_with(
        &[
            "tune",
            "--method-file",
            broken.to_str().unwrap(),
            "--out",
            out_s,
        ],
        &["broken.toml:9:7:"],
    );
    let png = out.join("x.png");
    fails_with(
        &[
            "render",
            "--method-file",
            broken.to_str().unwrap(),
            "--out",
            png.to_str().unwrap(),
        ],
        &["broken.toml:9:7:"],
    );
    assert!(e.contains("max -1 is below min 0"), "{e}");
    assert!(!out.join("tune.md").exists(), "nothing written on refusal");
}
