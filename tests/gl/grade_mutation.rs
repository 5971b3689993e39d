//! The grader's sensitivity (`opengl3d grade --mutation-score`): a fixed sample of the generated
//! mutants of the project's five shaders, each graded as a student's file is; the grader must fail
//! every sampled mutant beyond the step's tolerance. The probe itself, checked against the
//! hand-written folders of tests/mutants/: the shaders the grader must accept (listings, correct
//! rewrites) are within the tolerance, the typical mistakes beyond it. And the equivalence test:
//! known faults of the project's shaders (a 2×2 smoothing statement dropped, its weight doubled, a
//! sign flipped, a clamp dropped) are never equivalent, true equivalents (operands of `*` swapped,
//! a variable renamed) are.

use serde_json::Value;
use std::path::Path;

/// The probe's difference (in units of the step's tolerance) for the shader in tests/mutants/NAME.
fn probe(name: &str, step: &str) -> f64 {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/mutants")
        .join(name);
    probe_metrics(&dir, name, step)["mutation_probe"]
        .as_f64()
        .unwrap_or_else(|| panic!("{name}: no probe"))
}

/// The probe's metrics for the shader in `dir`.
fn probe_metrics(dir: &Path, name: &str, step: &str) -> Value {
    let work =
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("probe-{name}-{}", std::process::id()));
    let o = crate::common::bin()
        .arg("--res")
        .arg(dir)
        .args(["grade-step", step, "--probe", "--work"])
        .arg(&work)
        .output()
        .expect("run opengl3d");
    let out = String::from_utf8_lossy(&o.stdout);
    let line = out
        .lines()
        .rev()
        .find(|l| l.starts_with('{'))
        .unwrap_or_else(|| panic!("{name}: no verdict:\n{out}\n{}", crate::common::stderr(&o)));
    let v: Value = serde_json::from_str(line).expect("a JSON verdict");
    v["metrics"].clone()
}

/// The largest difference (in units of float noise) between the project's `file` and the same
/// file with `from` replaced by `to` (each must occur).
fn listing_difference(step: &str, file: &str, edits: &[(&str, &str)], name: &str) -> f64 {
    let mut src =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("Res").join(file))
            .unwrap();
    for (from, to) in edits {
        assert!(src.contains(from), "{name}: no `{from}` in {file}");
        src = src.replace(from, to);
    }
    let dir = crate::grade_class::temp_dir(&format!("equivalence-{name}"));
    std::fs::write(dir.join(file), src).unwrap();
    let m = probe_metrics(&dir, name, step);
    m["mutation_probe_listing"]
        .as_f64()
        .unwrap_or_else(|| panic!("{name}: no listing difference in {m}"))
}

/// (step, file, name, text replacements) of a hand-made mutant of the project's shader.
type Case = (
    &'static str,
    &'static str,
    &'static str,
    &'static [(&'static str, &'static str)],
);

#[test]
fn known_faults_are_never_equivalent_and_true_equivalents_are() {
    const SMOOTHING_X: &str = "occlusion -= dOccX * (float(iuv.x & 1) - 0.5);";
    const SMOOTHING_Y: &str = "occlusion -= dOccY * (float(iuv.y & 1) - 0.5);";
    let faults: [Case; 6] = [
        ("sao", "sao.frag", "no-smoothing-x", &[(SMOOTHING_X, "")]),
        ("sao", "sao.frag", "no-smoothing-y", &[(SMOOTHING_Y, "")]),
        (
            "sao",
            "sao.frag",
            "smoothing-weight-1",
            &[("(float(iuv.x & 1) - 0.5)", "(float(iuv.x & 1) - 1.0)")],
        ),
        (
            "sao",
            "sao.frag",
            "offset-sign",
            &[(
                "inTexcoord + ratio * radiusTS",
                "inTexcoord - ratio * radiusTS",
            )],
        ),
        (
            "sao",
            "sao.frag",
            "max-mip-level-2",
            &[("const int maxMipLevel = 3;", "const int maxMipLevel = 2;")],
        ),
        (
            "blur",
            "sao_blur.frag",
            "no-clamp",
            &[(
                "clamp(uv + ivec2(x, y) * blurScale, ivec2(0), maxUV)",
                "uv + ivec2(x, y) * blurScale",
            )],
        ),
    ];
    for (step, file, name, edits) in faults {
        let e = listing_difference(step, file, edits, name);
        assert!(e > 1.0, "{name}: a fault is called equivalent ({e:.2})");
    }
    let equivalents: [Case; 3] = [
        (
            "sao",
            "sao.frag",
            "swapped-product",
            &[("radiusTS * size.y", "size.y * radiusTS")],
        ),
        ("sao", "sao.frag", "renamed", &[("occlusion", "obscurance")]),
        (
            "blur",
            "sao_blur.frag",
            "swapped-weights",
            &[(
                "gaussian[abs(x)] * gaussian[abs(y)]",
                "gaussian[abs(y)] * gaussian[abs(x)]",
            )],
        ),
    ];
    for (step, file, name, edits) in equivalents {
        let e = listing_difference(step, file, edits, name);
        assert!(e <= 1.0, "{name}: a true equivalent differs ({e:.2})");
    }
}

#[test]
fn the_probe_accepts_what_the_grader_must_accept_and_sees_the_mistakes() {
    for (name, step) in [
        ("listing-restore", "restore"),
        ("rewrite-restore", "restore"),
        ("listing-down-sampling", "down-sampling"),
        ("rewrite-down-sampling", "down-sampling"),
        ("listing-simple", "simple"),
        ("rewrite-simple", "simple"),
        ("listing-sao", "sao"),
        ("listing-sao-guarded", "sao"),
        ("rewrite-sao", "sao"),
        ("listing-blur", "blur"),
        ("rewrite-blur", "blur"),
    ] {
        let d = probe(name, step);
        assert!(
            d <= 1.0,
            "{name}: a shader the grader must accept is observable ({d:.2})"
        );
    }
    for (name, step) in [
        ("restore-max", "restore"),
        ("restore-2d-plus-1", "restore"),
        ("down-sampling-no-x2", "down-sampling"),
        ("simple-swapped", "simple"),
        ("simple-wrong-channel", "simple"),
        ("sao-falloff-squared", "sao"),
        ("sao-flipped-normal", "sao"),
        ("sao-no-clamp", "sao"),
        ("blur-no-edge-weight", "blur"),
        ("blur-no-normalise", "blur"),
    ] {
        let d = probe(name, step);
        assert!(
            d > 1.0,
            "{name}: a typical mistake is not observable ({d:.2})"
        );
    }
}

#[test]
fn the_grader_fails_every_sampled_mutant_beyond_the_tolerance() {
    let o = crate::common::run(&[
        "grade",
        "--mutation-score",
        "--mutation-sample",
        "6",
        "--jobs",
        "2",
        "--json",
    ]);
    let out = String::from_utf8_lossy(&o.stdout);
    let v: Value = serde_json::from_str(&out)
        .unwrap_or_else(|e| panic!("no JSON ({e}):\n{out}\n{}", crate::common::stderr(&o)));
    let steps = v["steps"].as_array().expect("steps");
    let names: Vec<&str> = steps.iter().map(|s| s["step"].as_str().unwrap()).collect();
    assert_eq!(names, ["restore", "down-sampling", "simple", "sao", "blur"]);
    for s in steps {
        let step = s["step"].as_str().unwrap();
        let results = s["results"].as_array().expect("results");
        // simple.frag is one statement: the operators make a single mutant of it.
        let generated = s["mutants"].as_u64().unwrap() as usize;
        assert_eq!(
            results.len(),
            6.min(generated),
            "{step}: six mutants sampled"
        );
        let count = |o: &str| results.iter().filter(|r| r["outcome"] == o).count() as u64;
        for r in results {
            let (id, outcome) = (r["id"].as_str().unwrap(), r["outcome"].as_str().unwrap());
            assert!(
                id.starts_with(step) && r["description"].as_str().is_some_and(|d| !d.is_empty()),
                "{r}"
            );
            assert_ne!(outcome, "grader-error", "{r}");
            assert_ne!(
                outcome, "survived",
                "{step}: the grader passes a mutant beyond the tolerance: {r}"
            );
            // Equivalence is decided on float noise, never on the tolerance.
            let listing = r["probe_listing"].as_f64();
            if outcome == "equivalent" {
                assert!(listing.is_some_and(|e| e <= 1.0), "{r}");
            } else if matches!(outcome, "killed" | "between") {
                assert!(listing.is_some_and(|e| e > 1.0), "{r}");
            }
        }
        let killed = count("killed") + count("timed-out") + count("killed-unseen");
        assert!(killed >= 1, "{step}: no sampled mutant failed: {results:?}");
        let faults = results.len() as u64 - count("equivalent") - count("does-not-build");
        assert_eq!(s["faults"].as_u64(), Some(faults));
        assert_eq!(s["killed"].as_u64(), Some(killed));
        assert_eq!(s["between"].as_u64(), Some(count("between")));
        let score = s["score"].as_f64().unwrap();
        assert!((score - killed as f64 / faults as f64).abs() < 1e-12, "{s}");
    }
    assert_eq!(v["passed"].as_bool(), Some(true));
    assert_eq!(o.status.code(), Some(0));
}

#[test]
fn mutation_score_arguments_are_checked() {
    crate::common::fails_with(&["grade", "--mutation-score", "--class", "x"], &["--class"]);
    crate::common::fails_with(&["grade", "--jobs", "2"], &["--jobs"]);
    crate::common::fails_with(
        &["--res", ".", "grade", "--mutation-score"],
        &["--res", "--mutation-score"],
    );
    crate::common::fails_with(&["grade", "--mutation-sample", "2"], &["--mutation-score"]);
    crate::common::fails_with(
        &["grade", "--mutation-score", "--mutation-sample", "0"],
        &["--mutation-sample 0"],
    );
}
