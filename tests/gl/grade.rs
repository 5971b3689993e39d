//! The grader (`opengl3d grade`) run as a student would run it, against tests/mutants/: each folder
//! holds one lesson shader. `listing-*` are the lesson's listings typed as printed (errata fixed) and
//! `rewrite-*` correct shaders written differently: they must pass. The others are typical mistakes:
//! they must fail, with a message that names the problem.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn mutant(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/mutants")
        .join(name)
}

fn temp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    match std::fs::remove_dir_all(&d) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => panic!("{}: {e}", d.display()),
        _ => {}
    }
    std::fs::create_dir_all(&d).unwrap();
    d
}

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

impl Run {
    fn json(&self) -> Value {
        serde_json::from_str(self.stdout.trim()).unwrap_or_else(|e| {
            panic!(
                "grade --json printed no JSON ({e}):\n{}\n{}",
                self.stdout, self.stderr
            )
        })
    }
}

fn grade(res: Option<&Path>, args: &[&str]) -> Run {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_opengl3d"));
    if let Some(r) = res {
        cmd.arg("--res").arg(r);
    }
    let o = cmd.arg("grade").args(args).output().expect("run opengl3d");
    Run {
        code: o.status.code(),
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
    }
}

/// The report must have exactly {"passed", "steps": [{"step", "file", "passed", "message"}]}.
fn check_shape(v: &Value) {
    let top = v.as_object().expect("a JSON object");
    let mut keys: Vec<&str> = top.keys().map(String::as_str).collect();
    keys.sort();
    assert_eq!(keys, ["passed", "steps"], "{v}");
    assert!(top["passed"].is_boolean());
    for s in top["steps"].as_array().expect("steps is an array") {
        let o = s.as_object().expect("each step is an object");
        let mut keys: Vec<&str> = o.keys().map(String::as_str).collect();
        keys.sort();
        assert_eq!(keys, ["file", "message", "passed", "step"], "{s}");
        assert!(o["passed"].is_boolean() && o["message"].is_string());
    }
}

/// The step a mutant folder's only lesson shader belongs to (other files are its includes).
fn step_of(dir: &Path) -> &'static str {
    let file = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .find(|f| f.ends_with(".frag"))
        .expect("a mutant folder holds one shader");
    match file.as_str() {
        "sao_restore_depth.frag" => "restore",
        "sao_down_sampling.frag" => "down-sampling",
        "sao.frag" => "sao",
        "sao_blur.frag" => "blur",
        f => panic!("{f} is not a lesson shader"),
    }
}

/// Grades mutant `name` on its own step; checks the verdict and that the message holds `needles`.
fn expect(name: &str, pass: bool, needles: &[&str]) {
    let dir = mutant(name);
    let step = step_of(&dir);
    let run = grade(Some(&dir), &["--json", "--step", step]);
    let v = run.json();
    check_shape(&v);
    let s = &v["steps"][0];
    let message = s["message"].as_str().unwrap();
    eprintln!("{name}: {message}");
    assert_eq!(v["steps"].as_array().unwrap().len(), 1);
    assert_eq!(s["step"], step);
    assert_eq!(
        s["passed"].as_bool(),
        Some(pass),
        "{name} should {}: {message}",
        if pass { "pass" } else { "fail" }
    );
    assert_eq!(v["passed"].as_bool(), Some(pass));
    assert_eq!(run.code, Some(if pass { 0 } else { 1 }), "exit code");
    for n in needles {
        assert!(
            message.contains(n),
            "{name}: '{message}' should mention '{n}'"
        );
    }
}

macro_rules! passes {
    ($($test:ident: $dir:literal),* $(,)?) => {$(
        #[test]
        fn $test() {
            expect($dir, true, &[]);
        }
    )*};
}

macro_rules! fails {
    ($($test:ident: $dir:literal => [$($needle:literal),*]),* $(,)?) => {$(
        #[test]
        fn $test() {
            expect($dir, false, &[$($needle),*]);
        }
    )*};
}

passes! {
    listing_restore_passes: "listing-restore",
    listing_restore_saved_as_shift_jis_passes: "listing-restore-shift-jis",
    listing_down_sampling_passes: "listing-down-sampling",
    listing_sao_passes: "listing-sao",
    listing_sao_with_normal_guard_passes: "listing-sao-guarded",
    listing_blur_passes: "listing-blur",
    rewritten_restore_passes: "rewrite-restore",
    rewritten_down_sampling_passes: "rewrite-down-sampling",
    rewritten_sao_passes: "rewrite-sao",
    rewritten_sao_with_an_include_passes: "rewrite-sao-include",
    rewritten_blur_passes: "rewrite-blur",
}

fails! {
    restore_with_the_wrong_sign_fails: "restore-wrong-sign" => ["wrong sign at z=10 m: got -10.0"],
    restore_with_max_fails: "restore-max" => ["max instead of min"],
    restore_without_times_two_fails: "restore-no-x2" => ["gl_FragCoord.xy) * 2"],
    restore_with_the_debug_scale_left_fails: "restore-debug-scale" => ["0.01", "got 0.100"],
    restore_with_2d_plus_1_fails: "restore-2d-plus-1" => ["2D + 1", "2D − 1"],
    restore_not_text_is_rejected_by_name: "restore-not-text" => ["restore-not-text/sao_restore_depth.frag", "neither UTF-8, UTF-16 nor Shift-JIS"],
    down_sampling_with_max_fails: "down-sampling-max" => ["max instead of min"],
    down_sampling_without_times_two_fails: "down-sampling-no-x2" => ["gl_FragCoord.xy) * 2"],
    down_sampling_reading_level_0_fails: "down-sampling-level-0" => ["pass mipLevel"],
    down_sampling_with_a_float_mip_level_names_the_gl_error: "down-sampling-float-mip-level" => ["pass mipLevel", "OpenGL reported GL_INVALID_OPERATION"],
    sao_writing_inside_the_loop_fails: "sao-output-in-loop" => ["not normalised", "expected about 0."],
    sao_with_a_flipped_normal_fails: "sao-flipped-normal" => ["normal flipped"],
    sao_without_the_clamp_fails: "sao-no-clamp" => ["max(…, 0)"],
    sao_reading_only_level_0_fails: "sao-level-0" => ["never reads the mip levels 1–3", "textureLod(texDepth, uv, mipLevel)"],
    sao_with_a_squared_falloff_fails: "sao-falloff-squared" => ["f·f·f", "fades too slowly"],
    sao_with_a_compile_error_names_file_and_line: "sao-compile-error" => ["does not compile", "sao-compile-error/sao.frag:83:"],
    blur_without_normalisation_fails: "blur-no-normalise" => ["not normalised", "totalWeight"],
    blur_without_the_edge_weight_fails: "blur-no-edge-weight" => ["across a depth edge"],
}

#[test]
fn the_projects_own_shaders_pass() {
    let run = grade(None, &["--json"]);
    let v = run.json();
    check_shape(&v);
    let steps: Vec<&str> = v["steps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["step"].as_str().unwrap())
        .collect();
    assert_eq!(steps, ["restore", "down-sampling", "sao", "blur"]);
    assert_eq!(v["passed"], true, "{v}");
    assert_eq!(run.code, Some(0));
}

#[test]
fn a_student_with_every_listing_passes_and_gets_pictures() {
    let dir = temp_dir("grade-listings");
    for (m, f) in [
        ("listing-restore", "sao_restore_depth.frag"),
        ("listing-down-sampling", "sao_down_sampling.frag"),
        ("listing-sao", "sao.frag"),
        ("listing-blur", "sao_blur.frag"),
    ] {
        std::fs::copy(mutant(m).join(f), dir.join(f)).unwrap();
    }
    let out = dir.join("pictures");
    let run = grade(Some(&dir), &["--json", "--out", out.to_str().unwrap()]);
    let v = run.json();
    check_shape(&v);
    assert_eq!(v["passed"], true, "{v}");
    assert_eq!(v["steps"].as_array().unwrap().len(), 4);
    for s in v["steps"].as_array().unwrap() {
        assert!(
            !s["message"].as_str().unwrap().contains("project's file"),
            "{s}"
        );
    }
    for step in ["restore", "down-sampling", "sao", "blur"] {
        for kind in ["expected", "actual", "difference"] {
            let p = out.join(format!("{step}-{kind}.png"));
            let img = image::open(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert!(img.width() > 8 && img.height() > 4);
        }
    }
}

#[test]
fn missing_files_use_the_projects_and_lesson_selects_the_steps() {
    // Lesson step 4 needs the restore and down-sampling shaders; the student has only the first.
    let dir = temp_dir("grade-partial");
    std::fs::copy(
        mutant("listing-restore").join("sao_restore_depth.frag"),
        dir.join("sao_restore_depth.frag"),
    )
    .unwrap();
    let run = grade(Some(&dir), &["--lesson", "4"]);
    assert_eq!(run.code, Some(0), "{}{}", run.stdout, run.stderr);
    let verdicts: Vec<&str> = run
        .stdout
        .lines()
        .filter(|l| l.starts_with("PASS ") || l.starts_with("FAIL "))
        .collect();
    assert_eq!(verdicts.len(), 2, "{}", run.stdout);
    assert!(
        verdicts[0].starts_with("PASS sao_restore_depth.frag: "),
        "{}",
        run.stdout
    );
    assert!(
        verdicts[1].starts_with("PASS sao_down_sampling.frag: (using the project's file)"),
        "{}",
        run.stdout
    );
}

#[test]
fn an_endless_loop_times_out_and_grading_goes_on() {
    // Lesson step 6: restore and down-sampling (the project's files) and the student's SAO.
    let run = grade(
        Some(&mutant("sao-endless-loop")),
        &["--json", "--lesson", "6", "--timeout", "6"],
    );
    let v = run.json();
    check_shape(&v);
    assert_eq!(v["passed"], false);
    assert_eq!(run.code, Some(1));
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 3);
    assert_eq!(steps[0]["passed"], true, "{v}");
    assert_eq!(steps[1]["passed"], true, "{v}");
    assert_eq!(steps[2]["step"], "sao");
    let message = steps[2]["message"].as_str().unwrap();
    assert!(message.contains("timed out after 6 s"), "{message}");
}

#[test]
fn bad_arguments_are_errors() {
    let run = grade(None, &["--lesson", "13"]);
    assert_ne!(run.code, Some(0));
    assert!(run.stderr.contains("no lesson step 13"), "{}", run.stderr);
    let missing = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-such-student-folder");
    let run = grade(Some(&missing), &[]);
    assert_ne!(run.code, Some(0));
    assert!(run.stderr.contains("not a folder"), "{}", run.stderr);
}

#[test]
fn pictures_that_cannot_be_written_are_said_with_the_verdict() {
    // A folder where the restore step's first picture should go: the PNG cannot be written.
    let out = temp_dir("grade-blocked-pictures");
    std::fs::create_dir_all(out.join("restore-expected.png")).unwrap();
    let run = grade(
        Some(&mutant("listing-restore")),
        &[
            "--json",
            "--step",
            "restore",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    let v = run.json();
    check_shape(&v);
    let s = &v["steps"][0];
    assert_eq!(s["passed"], true, "{v}");
    let message = s["message"].as_str().unwrap();
    assert!(
        message.contains("pictures not written") && message.contains("restore-expected.png"),
        "{message}"
    );
}
