//! GitHub Classroom as a teacher sets it up: `lesson start --classroom DIR` writes a workflow that
//! parses as YAML and follows the autograding conventions, and each of its tests' commands, run
//! here with this build's binary in place of the installed `opengl3d`, passes on the course's
//! listings and fails on a broken shader. And `grade --points` in --json, results.csv and junit.xml.

use crate::grade_class::{mutant, temp_dir};
use quick_xml::events::Event;
use serde_yaml::Value;
use std::path::Path;
use std::process::Command;

const LISTINGS: [(&str, &str); 5] = [
    ("restore", "lesson-restore"),
    ("down-sampling", "listing-down-sampling"),
    ("simple", "listing-simple"),
    ("sao", "lesson-sao"),
    ("blur", "listing-blur"),
];
const BROKEN: [(&str, &str); 5] = [
    ("restore", "restore-2d-plus-1"),
    ("down-sampling", "down-sampling-max"),
    ("simple", "simple-swapped"),
    ("sao", "sao-no-smoothing"),
    ("blur", "blur-no-clamp"),
];

/// Copies the shader(s) of tests/mutants/NAME into `dir`.
fn put(dir: &Path, name: &str) {
    for f in std::fs::read_dir(mutant(name)).unwrap() {
        let f = f.unwrap();
        std::fs::copy(f.path(), dir.join(f.file_name())).unwrap();
    }
}

fn str_at<'a>(v: &'a Value, key: &str) -> &'a str {
    v.get(key)
        .and_then(Value::as_str)
        .unwrap_or_else(|| panic!("no string {key} in {v:?}"))
}

/// One command-grader step: (step id, test name, command, timeout, max-score).
type GraderStep = (String, String, String, u64, u64);

/// The command-grader steps of the workflow, and the reporter's step.
fn autograding_steps(workflow: &Value) -> (Vec<GraderStep>, Value) {
    let job = &workflow["jobs"]["run-autograding-tests"];
    assert_eq!(str_at(job, "runs-on"), "ubuntu-latest");
    let steps = job["steps"].as_sequence().expect("steps");
    let mut tests = Vec::new();
    let mut reporter = None;
    for s in steps {
        match s.get("uses").and_then(Value::as_str) {
            Some("education/autograding-command-grader@v1") => {
                let with = &s["with"];
                tests.push((
                    str_at(s, "id").to_string(),
                    str_at(with, "test-name").to_string(),
                    str_at(with, "command").to_string(),
                    with["timeout"].as_u64().expect("timeout in minutes"),
                    with["max-score"].as_u64().expect("max-score"),
                ));
            }
            Some("education/autograding-grader-reporter@v1") => {
                assert!(reporter.is_none(), "one reporter");
                reporter = Some(s.clone());
            }
            _ => assert!(reporter.is_none(), "the reporter comes last: {s:?}"),
        }
    }
    (tests, reporter.expect("a reporter step"))
}

/// Runs a test's command as the workflow would, in `dir`, with this build's binary.
fn run_command(command: &str, dir: &Path) -> std::process::Output {
    let mut words = command.split_whitespace();
    assert_eq!(words.next(), Some("opengl3d"), "{command}");
    Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(words)
        .current_dir(dir)
        .output()
        .expect("run opengl3d")
}

#[test]
fn the_classroom_workflow_parses_and_its_tests_grade_each_shader() {
    let dir = temp_dir("classroom");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(["--lang", "ja", "lesson", "start", "--classroom"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("OPENGL3D_GIT"));
    let text = std::fs::read_to_string(dir.join(".github/workflows/classroom.yml")).unwrap();
    let workflow: Value = serde_yaml::from_str(&text).expect("the workflow is YAML");
    assert!(workflow["on"].get("push").is_some(), "runs on push");
    assert_eq!(str_at(&workflow["permissions"], "checks"), "write");
    let install = text.contains("cargo install --locked --git \"$OPENGL3D_GIT\" opengl3d");
    assert!(install && text.contains("libgl1-mesa-dri"), "{text}");
    let (tests, reporter) = autograding_steps(&workflow);
    let ids: Vec<&str> = tests.iter().map(|t| t.0.as_str()).collect();
    assert_eq!(ids, ["restore", "down_sampling", "simple", "sao", "blur"]);
    assert_eq!(tests.iter().map(|t| t.4).sum::<u64>(), 100);
    assert_eq!(str_at(&reporter["with"], "runners"), ids.join(","));
    for t in &tests {
        let env = format!("{}_RESULTS", t.0.to_uppercase());
        let expected = format!("${{{{steps.{}.outputs.result}}}}", t.0);
        assert_eq!(str_at(&reporter["env"], &env), expected);
        assert!(t.1.contains(".frag") && (1..=60).contains(&t.3), "{t:?}");
    }
    // The stubs the student starts from fail every test; the listings pass each; one broken shader
    // fails its own test only.
    for (i, t) in tests.iter().enumerate() {
        let o = run_command(&t.2, &dir);
        assert!(!o.status.success(), "the stub passes {}", t.1);
        let (step, listing) = LISTINGS[i];
        assert_eq!(step.replace('-', "_"), t.0);
        put(&dir, listing);
        let o = run_command(&t.2, &dir);
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{listing} fails {}:\n{out}", t.1);
        let japanese = out.lines().any(|l| l.starts_with("合格 "));
        assert!(japanese, "Japanese verdicts: {out}");
    }
    for (t, (step, broken)) in tests.iter().zip(BROKEN) {
        assert_eq!(step.replace('-', "_"), t.0);
        put(&dir, broken);
        let o = run_command(&t.2, &dir);
        assert!(!o.status.success(), "{broken} passes {}", t.1);
        let (_, listing) = LISTINGS.iter().find(|l| l.0 == step).unwrap();
        put(&dir, listing);
    }
}

#[test]
fn points_appear_in_json_csv_and_junit() {
    let student = temp_dir("points-student");
    put(&student, "lesson-restore");
    put(&student, "blur-no-clamp");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .arg("--res")
        .arg(&student)
        .args([
            "grade",
            "--step",
            "restore,blur",
            "--points",
            "blur=7",
            "--json",
        ])
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(
        (v["points"].as_u64(), v["max_points"].as_u64()),
        (Some(20), Some(27))
    );
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps[0]["points"].as_u64(), Some(20));
    assert_eq!(steps[1]["points"].as_u64(), Some(0));
    assert_eq!(steps[1]["max_points"].as_u64(), Some(7));

    let class = temp_dir("points-class");
    for (name, from) in [("ada", "listing-restore"), ("bob", "restore-max")] {
        std::fs::create_dir_all(class.join(name)).unwrap();
        put(&class.join(name), from);
    }
    let out = temp_dir("points-report");
    let o = crate::grade_class::grade_class(
        &class,
        &[
            "--step",
            "restore",
            "--points",
            "--jobs",
            "1",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", crate::common::stderr(&o));
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(
        rows[0],
        "student,restore,restore points,passed,points,max points"
    );
    assert!(rows.contains(&"ada,PASS,20,1,20,20"), "{csv}");
    assert!(rows.contains(&"bob,FAIL,0,0,0,20"), "{csv}");
    let xml = std::fs::read_to_string(out.join("junit.xml")).unwrap();
    // Each test case's points, read with an XML parser: (suite, points, max_points).
    let mut reader = quick_xml::Reader::from_str(&xml);
    let (mut suite, mut in_case, mut seen) = (String::new(), false, Vec::new());
    let mut property: (Option<String>, Option<String>) = (None, None);
    loop {
        match reader.read_event().expect("well-formed junit.xml") {
            Event::Start(e) | Event::Empty(e) => {
                let attr = |k: &[u8]| {
                    e.attributes()
                        .flatten()
                        .find(|a| a.key.as_ref() == k)
                        .map(|a| {
                            a.normalized_value(quick_xml::XmlVersion::Explicit1_0)
                                .unwrap()
                                .into_owned()
                        })
                };
                match e.name().as_ref() {
                    b"testsuite" => suite = attr(b"name").unwrap(),
                    b"testcase" => in_case = true,
                    b"property" if in_case => match attr(b"name").as_deref() {
                        Some("points") => property.0 = attr(b"value"),
                        Some("max_points") => property.1 = attr(b"value"),
                        _ => {}
                    },
                    _ => {}
                }
            }
            Event::End(e) if e.name().as_ref() == b"testcase" => {
                in_case = false;
                let p = std::mem::take(&mut property);
                seen.push((suite.clone(), p.0.unwrap(), p.1.unwrap()));
            }
            Event::Eof => break,
            _ => {}
        }
    }
    seen.sort();
    let want = |s: &str, p: &str| (s.to_string(), p.to_string(), "20".to_string());
    assert_eq!(seen, [want("ada", "20"), want("bob", "0")]);
}
