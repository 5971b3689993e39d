//! The grader's sensitivity (`opengl3d grade --mutation-score`): a fixed sample of the generated
//! mutants of the project's four shaders, each graded as a student's file is; the grader must fail
//! every sampled mutant the probe render calls observable. And the probe itself, checked against
//! the hand-written folders of tests/mutants/: the shaders the grader must accept (listings, correct
//! rewrites) are never observable, the typical mistakes are.

use serde_json::Value;
use std::path::Path;

/// The probe's difference (in units of the step's tolerance) for the shader in tests/mutants/NAME.
fn probe(name: &str, step: &str) -> f64 {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/mutants")
        .join(name);
    let work =
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("probe-{name}-{}", std::process::id()));
    let o = crate::common::bin()
        .arg("--res")
        .arg(&dir)
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
    v["metrics"]["mutation_probe"]
        .as_f64()
        .unwrap_or_else(|| panic!("{name}: no probe in {line}"))
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
fn the_grader_fails_every_observable_mutant_of_a_fixed_sample() {
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
        let mut observable = 0;
        for r in results {
            let (id, outcome) = (r["id"].as_str().unwrap(), r["outcome"].as_str().unwrap());
            assert!(
                id.starts_with(step) && r["description"].as_str().is_some_and(|d| !d.is_empty()),
                "{r}"
            );
            assert_ne!(outcome, "grader-error", "{r}");
            assert_ne!(
                outcome, "survived",
                "{step}: the grader passes an observable mutant: {r}"
            );
            if matches!(outcome, "killed" | "timed-out") {
                observable += 1;
            }
        }
        assert!(
            observable >= 1,
            "{step}: no observable mutant in the sample: {results:?}"
        );
        assert_eq!(s["observable"].as_u64(), Some(observable as u64));
        assert_eq!(s["score"].as_f64(), Some(1.0));
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
