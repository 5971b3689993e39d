//! Each method's recommended configuration (`scene::ao_defaults`): what `--method NAME` alone runs,
//! checked against the same keys written out as flags; a flag or a scene file's key still wins; the
//! lesson's SAO renders as the course's values written out do.

use crate::common;
use crate::common::{run, stderr};
use opengl3d::ao::{AoMethod, AoResolution, GuardBand, NormalSource, SlicePreset, Thickness};
use opengl3d::scene::ao_defaults::recommended;
use std::path::{Path, PathBuf};

/// The AO view (PFM bytes) `render` writes at 80×60 with `flags`.
fn ao_view(dir: &Path, name: &str, flags: &[&str]) -> Vec<u8> {
    let out = dir.join(format!("{name}.pfm"));
    let mut args: Vec<String> = ["render", "--view", "ao", "--width", "80", "--height", "60"]
        .map(String::from)
        .to_vec();
    args.extend(flags.iter().map(|s| s.to_string()));
    args.extend(["--out".into(), out.to_str().unwrap().into()]);
    let o = run(&args);
    assert!(o.status.success(), "{flags:?}: {}", stderr(&o));
    std::fs::read(&out).unwrap()
}

/// The flags that write vbao's recommended configuration out, spelled here, not read from the table.
const VBAO_WRITTEN_OUT: [&str; 12] = [
    "--quality",
    "ultra",
    "--ao-resolution",
    "quarter",
    "--normals",
    "geometric",
    "--guard-band",
    "auto",
    "--layers",
    "2",
    "--thickness",
    "backface",
];

#[test]
fn vbao_alone_runs_the_configuration_the_table_gives() {
    let r = recommended(AoMethod::Vbao);
    assert_eq!(r.quality, Some(SlicePreset::Ultra));
    assert_eq!(r.resolution, AoResolution::Quarter);
    assert_eq!(r.normals, NormalSource::Geometric);
    assert_eq!(r.guard_band, GuardBand::Auto);
    assert_eq!((r.layers, r.thickness), (2, Some(Thickness::Backface)));

    let dir = common::temp_dir("ao-defaults-vbao");
    let alone = ao_view(&dir, "alone", &["--method", "vbao"]);
    let mut written = vec!["--method", "vbao"];
    written.extend(VBAO_WRITTEN_OUT);
    assert!(alone == ao_view(&dir, "written", &written));
    // The configuration is not the struct's plain one: one layer, depth normals, half size differ.
    let plain = [
        "--method",
        "vbao",
        "--ao-resolution",
        "half",
        "--normals",
        "depth",
        "--guard-band",
        "0",
        "--layers",
        "1",
        "--thickness",
        "0.5",
    ];
    assert!(alone != ao_view(&dir, "plain", &plain));
}

#[test]
fn a_flag_or_a_scene_key_overrides_the_recommendation() {
    let dir = common::temp_dir("ao-defaults-override");
    let mut one_layer = vec!["--method", "vbao"];
    one_layer.extend(VBAO_WRITTEN_OUT);
    let at = one_layer.iter().position(|a| *a == "--layers").unwrap();
    one_layer[at + 1] = "1";
    let written = ao_view(&dir, "written", &one_layer);
    let flag = ao_view(&dir, "flag", &["--method", "vbao", "--layers", "1"]);
    assert!(flag == written);
    assert!(flag != ao_view(&dir, "alone", &["--method", "vbao"]));

    // The same key in the scene file's [ao] table.
    let demo = opengl3d::res::project_res_dir().join("scenes/demo.toml");
    let text = std::fs::read_to_string(&demo).unwrap();
    let text = text.replace("[ao]\n", "[ao]\nmethod = \"vbao\"\nlayers = 1\n");
    let scene: PathBuf = dir.join("one-layer.toml");
    std::fs::write(&scene, text).unwrap();
    let keyed = ao_view(&dir, "keyed", &["--scene", scene.to_str().unwrap()]);
    assert!(keyed == written);
}

#[test]
fn the_lessons_sao_renders_as_the_course_values_written_out() {
    let dir = common::temp_dir("ao-defaults-lesson");
    let alone = ao_view(&dir, "alone", &[]);
    let written = ao_view(
        &dir,
        "written",
        &[
            "--method",
            "sao-lesson",
            "--samples",
            "11",
            "--ao-resolution",
            "half",
            "--normals",
            "depth",
            "--guard-band",
            "0",
            "--layers",
            "1",
        ],
    );
    assert!(alone == written);
    // After another method's recommendation, switching back leaves nothing of it behind.
    let r = recommended(AoMethod::SaoLesson);
    assert_eq!(
        (r.quality, r.resolution, r.normals, r.guard_band, r.layers),
        (
            None,
            AoResolution::Half,
            NormalSource::Depth,
            GuardBand::Off,
            1
        )
    );
    let mut s = opengl3d::ao::settings::AoSettings {
        method: AoMethod::Vbao,
        ..Default::default()
    };
    opengl3d::scene::ao_defaults::apply(&mut s);
    s.method = AoMethod::SaoLesson;
    opengl3d::scene::ao_defaults::apply(&mut s);
    assert_eq!(s, opengl3d::ao::settings::AoSettings::default());
}

#[test]
fn render_stats_names_the_configuration() {
    let dir = common::temp_dir("ao-defaults-stats");
    let out = dir.join("f.png");
    let o = run(&[
        "--lang",
        "en",
        "render",
        "--method",
        "vbao",
        "--layers",
        "1",
        "--width",
        "80",
        "--height",
        "60",
        "--stats",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("quality = ultra, resolution = quarter") && e.contains("layers = 1*"),
        "{e}"
    );
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let keys = json["ao_configuration"].as_array().unwrap();
    let layers = keys.iter().find(|k| k["key"] == "layers").unwrap();
    assert_eq!(layers["value"], "1");
    assert_eq!(layers["recommended"], false);
}

#[test]
fn rtao_alone_traces_its_recommended_rays() {
    assert_eq!(recommended(AoMethod::Rtao).rays, Some(4));
    let dir = common::temp_dir("ao-defaults-rtao");
    let alone = ao_view(&dir, "alone", &["--method", "rtao"]);
    let four = ao_view(&dir, "four", &["--method", "rtao", "--rays-per-pixel", "4"]);
    assert!(alone == four);
    let two = ao_view(&dir, "two", &["--method", "rtao", "--rays-per-pixel", "2"]);
    assert!(alone != two);
    // The same key in the scene file's [ao] table wins as the flag does.
    let demo = opengl3d::res::project_res_dir().join("scenes/demo.toml");
    let text = std::fs::read_to_string(&demo).unwrap();
    let text = text.replace("[ao]\n", "[ao]\nmethod = \"rtao\"\nrays = 2\n");
    let scene: PathBuf = dir.join("two-rays.toml");
    std::fs::write(&scene, text).unwrap();
    assert!(two == ao_view(&dir, "keyed", &["--scene", scene.to_str().unwrap()]));
}
