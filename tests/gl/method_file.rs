//! Method files: the engine's `hbao` written as one (docs/method-file/) renders exactly what the
//! built-in method renders, in `render` and in `bench`; its parameter and its recommended
//! configuration reach the engine; a broken shader or file is an error
//! naming the file and line.

use crate::common::{fails_with, run, stderr, temp_dir};
use std::path::{Path, PathBuf};

const EXAMPLE: &str = "docs/method-file/my_hbao.toml";

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(EXAMPLE)
}

/// Raw occlusion of a small frame (floats, so that any change shows), with extra flags.
fn raw_ao(dir: &Path, name: &str, method: &[&str], extra: &[&str]) -> Vec<u8> {
    let out = dir.join(format!("{name}.pfm"));
    // Every key a method's recommended configuration could set is given, so that both runs
    // start from the same settings.
    let mut args = vec![
        "render",
        "--width",
        "320",
        "--height",
        "180",
        "--view",
        "ao-raw",
        "--guard-band",
        "0",
        "--ao-resolution",
        "half",
    ];
    args.extend_from_slice(method);
    args.extend_from_slice(extra);
    let out_s = out.to_str().unwrap();
    args.extend_from_slice(&["--out", out_s]);
    let o = run(&args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    std::fs::read(&out).unwrap()
}

/// The example with its files copied to `dir`, `edit` applied to the shader and `toml_edit` to
/// the TOML file.
fn edited_copy(
    dir: &Path,
    edit: impl Fn(String) -> String,
    toml_edit: impl Fn(String) -> String,
) -> PathBuf {
    let from = example();
    let folder = from.parent().unwrap();
    let frag = std::fs::read_to_string(folder.join("my_hbao.frag")).unwrap();
    std::fs::write(dir.join("my_hbao.frag"), edit(frag)).unwrap();
    let toml = std::fs::read_to_string(&from).unwrap();
    let path = dir.join("my_hbao.toml");
    std::fs::write(&path, toml_edit(toml)).unwrap();
    path
}

#[test]
fn hbao_as_a_method_file_renders_what_the_engine_s_hbao_renders() {
    let dir = temp_dir("method-file-hbao");
    let file = example();
    let file = file.to_str().unwrap();
    for (i, extra) in [
        &["--normals", "depth"][..],
        &["--normals", "geometric", "--samples", "20"][..],
    ]
    .iter()
    .enumerate()
    {
        let builtin = raw_ao(&dir, &format!("builtin-{i}"), &["--method", "hbao"], extra);
        let own = raw_ao(&dir, &format!("file-{i}"), &["--method-file", file], extra);
        assert!(
            builtin == own,
            "flags {extra:?}: the method file's occlusion differs from hbao's"
        );
    }
    // With no flag beyond the method, each runs its own recommendation: the file recommends what
    // the engine's hbao does, so the two still agree (a scene key left unwritten either way).
    let bare = |name: &str, method: &[&str]| {
        let out = dir.join(format!("{name}.pfm"));
        let mut args = vec!["render", "--width", "320", "--height", "180", "--view"];
        args.extend_from_slice(&["ao-raw", "--out", out.to_str().unwrap()]);
        args.extend_from_slice(method);
        let o = run(&args);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        std::fs::read(&out).unwrap()
    };
    let builtin = bare("builtin-bare", &["--method", "hbao"]);
    assert!(
        builtin == bare("file-bare", &["--method-file", file]),
        "without flags the method file's occlusion differs from hbao's"
    );
    // Without its `[recommended]` table the file runs without hbao's guard band: another picture
    // (the recommendation is what made the two agree above).
    let plain = edited_copy(&dir, |f| f, |t| t.replace("guard_band = \"auto\"", ""));
    let plain = bare("file-plain", &["--method-file", plain.to_str().unwrap()]);
    assert!(
        builtin != plain,
        "the recommended guard band changed nothing"
    );
    // The parameter reaches the shader: another bias, another picture.
    let raised = edited_copy(
        &dir,
        |f| f,
        |t| t.replace("default = 0.1736", "default = 0.45"),
    );
    let builtin = raw_ao(&dir, "builtin-0b", &["--method", "hbao"], &[]);
    let other = raw_ao(
        &dir,
        "raised",
        &["--method-file", raised.to_str().unwrap()],
        &[],
    );
    assert!(builtin != other, "SIN_BIAS = 0.45 changed nothing");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_broken_method_shader_or_file_names_the_file_and_line() {
    let dir = temp_dir("method-file-broken");
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    // A GLSL error (`vec3 P` becomes an undeclared type) on the line it is written.
    let broken = edited_copy(
        &dir,
        |f| f.replacen("vec3 P = TexelPos(pix);", "vec9 P = TexelPos(pix);", 1),
        |t| t,
    );
    let line = std::fs::read_to_string(dir.join("my_hbao.frag"))
        .unwrap()
        .lines()
        .position(|l| l.contains("vec9 P"))
        .unwrap()
        + 1;
    let at = format!("my_hbao.frag:{line}");
    fails_with(
        &[
            "render",
            "--method-file",
            broken.to_str().unwrap(),
            "--out",
            out,
        ],
        &[&at],
    );
    // A bad value in the TOML file: its line and column.
    let bad = edited_copy(&dir, |f| f, |t| t.replace("\"normals\"", "\"colour\""));
    fails_with(
        &[
            "render",
            "--method-file",
            bad.to_str().unwrap(),
            "--out",
            out,
        ],
        &["my_hbao.toml:6:10", "colour"],
    );
    // A recommendation asking for an input the method does not read: the key's line and column.
    let unread = edited_copy(
        &dir,
        |f| f,
        |t| t.replace("guard_band = \"auto\"", "layers = 2"),
    );
    let line = std::fs::read_to_string(&unread)
        .unwrap()
        .lines()
        .position(|l| l.starts_with("layers = 2"))
        .unwrap()
        + 1;
    fails_with(
        &[
            "render",
            "--method-file",
            unread.to_str().unwrap(),
            "--out",
            out,
        ],
        &[&format!("my_hbao.toml:{line}:10"), "second-layer"],
    );
    // An include that climbs out of the folder is refused.
    let climbing = edited_copy(
        &dir,
        |f| f.replace("#include \"common.glsl\"", "#include \"../common.glsl\""),
        |t| t,
    );
    fails_with(
        &[
            "render",
            "--method-file",
            climbing.to_str().unwrap(),
            "--out",
            out,
        ],
        &["'..'"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_bench_measures_a_method_file_beside_the_engine_s_methods() {
    let dir = temp_dir("method-file-bench");
    let file = example();
    let o = run(&[
        "bench",
        "--methods",
        "hbao",
        "--method-file",
        file.to_str().unwrap(),
        "--samples",
        "11",
        "--radii",
        "1",
        "--width",
        "320",
        "--height",
        "180",
        "--ref-scale",
        "2",
        "--frames",
        "1",
        "--warmup",
        "0",
        "--no-flip",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let rows = report["rows"].as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["method"].as_str().unwrap()).collect();
    assert_eq!(names, ["hbao", "my-hbao"]);
    let psnr = rows[1]["psnr"].as_f64().unwrap();
    assert!(psnr.is_finite() && psnr > 10.0, "{psnr}");
    // The same occlusion as the engine's hbao: every camera's error, and every AO picture.
    let cameras = |r: &serde_json::Value| r["cameras"].clone();
    assert_eq!(cameras(&rows[0]), cameras(&rows[1]));
    let pictures = |r: &serde_json::Value| -> Vec<Vec<u8>> {
        let list = r["pictures"].as_array().unwrap();
        assert!(!list.is_empty());
        list.iter()
            .map(|p| std::fs::read(dir.join(p["ao"].as_str().unwrap())).unwrap())
            .collect()
    };
    assert!(
        pictures(&rows[0]) == pictures(&rows[1]),
        "the bench's AO pictures of hbao and my-hbao differ"
    );
    let page = std::fs::read_to_string(dir.join("report.html")).unwrap();
    assert!(page.contains("my-hbao"));
    assert!(dir
        .join("pictures/demo-orbit-left-my-hbao-n11_r1-error.png")
        .is_file());
    let _ = std::fs::remove_dir_all(&dir);
}
