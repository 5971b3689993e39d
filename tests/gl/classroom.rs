//! A class as a teacher runs it. Classroom 50: `lesson start --classroom classroom50` writes the
//! bundle, and its `autograder.py` is run as the runner runs it (in each student's checkout, with
//! the runner's environment) with this build's binary beside it, copied away from the source tree
//! (so it grades with the shaders built into it), on a class of six; every `result.json` is checked
//! against the Classroom 50 contract. Plain Actions: the workflow parses, names only actions of
//! docs/grade/known-actions.md, and its reading tests give each step its verdict from result.json.
//! And `grade --points` in --json, results.csv and junit.xml.

use crate::grade_class::{mutant, temp_dir};
use quick_xml::events::Event;
use serde_json::Value as Json;
use serde_yaml::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

const LISTINGS: [&str; 5] = [
    "lesson-restore",
    "listing-down-sampling",
    "listing-simple",
    "lesson-sao",
    "listing-blur",
];

/// Copies the shader(s) of tests/mutants/NAME into `dir`.
fn put(dir: &Path, name: &str) {
    for f in std::fs::read_dir(mutant(name)).unwrap() {
        let f = f.unwrap();
        std::fs::copy(f.path(), dir.join(f.file_name())).unwrap();
    }
}

/// A student checkout: the template's files with the course's listings, then `mistakes` over them.
fn student(class: &Path, name: &str, template: &Path, mistakes: &[&str]) -> PathBuf {
    let dir = class.join(name);
    copy_tree(template, &dir);
    for l in LISTINGS {
        put(&dir, l);
    }
    for m in mistakes {
        put(&dir, m);
    }
    dir
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let (src, dst) = (e.path(), to.join(e.file_name()));
        if src.is_dir() {
            copy_tree(&src, &dst);
        } else {
            std::fs::copy(&src, &dst).unwrap();
        }
    }
}

/// A fresh folder outside the source tree (its binary must not find the tree's Res/), removed
/// with everything in it when the test is done with it.
struct OutsideDir(tempfile::TempDir);

impl std::ops::Deref for OutsideDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<Path> for OutsideDir {
    fn as_ref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<std::ffi::OsStr> for OutsideDir {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.path().as_os_str()
    }
}

fn outside_dir(name: &str) -> OutsideDir {
    OutsideDir(
        tempfile::Builder::new()
            .prefix(&format!("opengl3d-{name}-"))
            .tempdir()
            .unwrap(),
    )
}

fn have(program: &str) -> bool {
    Command::new(program)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The committer date of the correct student's commit.
const SUBMITTED_AT: &str = "2026-06-01T14:32:05Z";

/// Makes `dir` a git checkout with everything in one commit at `date`.
fn commit_all(dir: &Path, date: &str) {
    let git = |args: &[&str]| {
        let o = Command::new("git")
            .args([
                "-c",
                "user.name=student",
                "-c",
                "user.email=student@example.com",
            ])
            .args(args)
            .current_dir(dir)
            .env("GIT_AUTHOR_DATE", date)
            .env("GIT_COMMITTER_DATE", date)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "git {args:?}: {}",
            crate::common::stderr(&o)
        );
    };
    git(&["init", "-q"]);
    git(&["add", "-A"]);
    git(&["commit", "-q", "-m", "submission"]);
}

/// Checks `r` against the result.json contract (Classroom 50, Advanced Autograding: "The
/// result.json contract"): the schema, the identity strings, integer scores that are the sums of
/// the tests', and each test's four fields. Returns (score, max-score).
fn check_contract(r: &Json, env: &[(&str, &str)]) -> (u64, u64) {
    assert_eq!(r["schema"], "classroom50/result/v1", "{r}");
    let var = |k: &str| env.iter().find(|e| e.0 == k).unwrap().1;
    assert_eq!(r["classroom"], var("CLASSROOM"));
    assert_eq!(r["assignment"], var("ASSIGNMENT"));
    assert_eq!(r["submission"], var("SUBMISSION_TAG"));
    assert_eq!(r["commit"], var("COMMIT_URL"));
    assert_eq!(r["release"], var("RELEASE_URL"));
    assert_eq!(r["review"], var("REVIEW_URL"));
    for k in ["datetime", "graded_at"] {
        let t = r[k]
            .as_str()
            .unwrap_or_else(|| panic!("{k} is a string: {r}"));
        let b = t.as_bytes();
        assert!(
            t.len() == 20 && b[4] == b'-' && b[10] == b'T' && b[19] == b'Z',
            "{k}: {t}"
        );
    }
    let tests = r["tests"].as_array().expect("tests is an array");
    let (mut score, mut max) = (0, 0);
    for t in tests {
        assert!(
            t["test-name"].as_str().is_some_and(|n| !n.is_empty()),
            "{t}"
        );
        let passed = t["passed"].as_bool().expect("passed is a bool");
        let (s, m) = (
            t["score"].as_u64().expect("score is an integer"),
            t["max-score"].as_u64().expect("max-score is an integer"),
        );
        assert!(s <= m, "{t}");
        if passed {
            assert_eq!(s, m, "a passed test earns its points: {t}");
        }
        score += s;
        max += m;
    }
    assert_eq!(r["score"].as_u64(), Some(score), "score is the tests' sum");
    assert_eq!(
        r["max-score"].as_u64(),
        Some(max),
        "max-score is the tests' sum"
    );
    (score, max)
}

/// The scores of `r`'s tests by unit id.
fn scores(r: &Json) -> Vec<(String, u64)> {
    r["tests"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| {
            (
                t["id"].as_str().unwrap().to_string(),
                t["score"].as_u64().unwrap(),
            )
        })
        .collect()
}

#[test]
fn classroom50_grades_a_class_of_six_into_valid_results() {
    if !have("python3") {
        panic!("python3 is needed to run the Classroom 50 autograder (the runner has it)");
    }
    let teacher = temp_dir("c50-teacher");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args([
            "--lang",
            "ja",
            "lesson",
            "start",
            "--classroom",
            "classroom50",
        ])
        .args(["--grader-repo", "school/opengl3d"])
        .arg(&teacher)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    for f in [
        "template/README.md",
        "template/sao.frag",
        "template/scenes/demo.toml",
        "autograder/autograder.py",
        "runtime.json",
        "assignment.json",
        "TEACHER.md",
    ] {
        assert!(teacher.join(f).is_file(), "{f} written");
    }
    let readme = std::fs::read_to_string(teacher.join("template/README.md")).unwrap();
    assert!(
        readme.contains("gh student submit") && readme.contains("提出"),
        "{readme}"
    );
    let fields: Json =
        serde_json::from_str(&std::fs::read_to_string(teacher.join("assignment.json")).unwrap())
            .unwrap();
    assert_eq!(fields["submission_mode"], "tag");
    let apt = fields["runtime"]["apt"].as_array().unwrap();
    assert!(apt.iter().any(|p| p == "libgl1-mesa-dri"), "{fields}");
    let assets: Vec<String> = fields["release_assets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap().to_string())
        .collect();

    // The bundle as the runner unpacks it, with the grader beside autograder.py: a copy of this
    // build's binary in a folder of its own, outside the source tree.
    let bundle = outside_dir("c50-bundle");
    std::fs::copy(
        teacher.join("autograder/autograder.py"),
        bundle.join("autograder.py"),
    )
    .unwrap();
    std::fs::copy(env!("CARGO_BIN_EXE_opengl3d"), bundle.join("opengl3d")).unwrap();
    let cache = outside_dir("c50-cache");

    let class = outside_dir("c50-class");
    let template = teacher.join("template");
    let students = [
        ("correct", vec![]),
        ("restore-2d-plus-1", vec!["restore-2d-plus-1"]),
        ("down-sampling-max", vec!["down-sampling-max"]),
        ("smoothing-sign", vec!["sao-smoothing-sign-flipped"]),
        ("blur-no-clamp", vec!["blur-no-clamp"]),
        ("course-text", vec!["course-sao"]),
    ];
    let mut results = Vec::new();
    for (name, mistakes) in &students {
        let dir = student(&class, name, &template, mistakes);
        if *name == "correct" {
            commit_all(&dir, SUBMITTED_AT);
        }
        let submission = format!("submit/2026-12-01T10-00-00Z-{name}");
        let env = [
            ("CLASSROOM", "cg-2026"),
            ("ASSIGNMENT", "ao-lesson"),
            ("SUBMISSION_TAG", submission.as_str()),
            ("COMMIT_URL", "https://github.com/org/repo/commit/abc"),
            ("RELEASE_URL", "https://github.com/org/repo/releases/tag/x"),
            ("REVIEW_URL", "https://github.com/org/repo/compare/a...b"),
            ("USERNAME", "student"),
        ];
        let o = Command::new("python3")
            .arg(bundle.join("autograder.py"))
            .current_dir(&dir)
            .envs(env)
            .env("XDG_CACHE_HOME", &cache)
            .env_remove("OPENGL3D_LANG")
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{name}: the autograder ran end to end:\n{}",
            crate::common::stderr(&o)
        );
        let text = std::fs::read_to_string(dir.join("result.json")).expect("result.json");
        let r: Json = serde_json::from_str(&text).expect("result.json is JSON");
        let (score, max) = check_contract(&r, &env);
        if *name == "correct" {
            assert_eq!(
                r["datetime"], SUBMITTED_AT,
                "the graded commit's committer date"
            );
        }
        assert_eq!(max, 100, "{name}: every step's points");
        let first = &r["tests"][0];
        assert!(
            first["test-name"].as_str().unwrap().contains("線形距離"),
            "test names in the class's language: {first}"
        );
        // Every release asset path the grader wrote is one the assignment lists.
        if score < 100 {
            assert!(dir.join("grade-report/feedback.html").is_file(), "{name}");
            let heat_maps = std::fs::read_dir(dir.join("grade-report")).unwrap().count();
            assert!(heat_maps > 1, "{name}: the failing step's pictures");
        }
        for e in std::fs::read_dir(dir.join("grade-report")).unwrap() {
            let rel = format!("grade-report/{}", e.unwrap().file_name().to_string_lossy());
            assert!(
                assets.contains(&rel),
                "{rel} is not among the release assets"
            );
        }
        results.push((name.to_string(), score, r));
    }
    // The grader ran from the copy: the shaders it grades against came from the binary itself.
    let extracted = std::fs::read_dir(cache.join("opengl3d"))
        .expect("the built-in Res/ was written to the cache")
        .filter_map(Result::ok)
        .any(|e| e.file_name().to_string_lossy().starts_with("res-"));
    assert!(extracted, "the grader used its built-in Res/");

    let score = |n: &str| results.iter().find(|r| r.0 == n).unwrap().1;
    let unit = |n: &str, id: &str| {
        let r = &results.iter().find(|r| r.0 == n).unwrap().2;
        scores(r).into_iter().find(|s| s.0 == id).unwrap().1
    };
    assert_eq!(score("correct"), 100);
    assert_eq!(score("restore-2d-plus-1"), 80, "restore is 20 points");
    assert_eq!(unit("restore-2d-plus-1", "restore"), 0);
    assert_eq!(score("down-sampling-max"), 90);
    assert_eq!(score("blur-no-clamp"), 90);
    // SAO is graded in sub-steps: a wrong sign in the smoothing costs only the smoothing's points.
    assert_eq!(score("smoothing-sign"), 90);
    assert_eq!(unit("smoothing-sign", "sao.smoothing"), 0);
    for id in ["sao.normal", "sao.sampling", "sao.occlusion", "sao.view"] {
        assert_eq!(unit("smoothing-sign", id), 10, "smoothing-sign keeps {id}");
    }
    // The course's own text keeps its stretched sampling disc (appendix A #20): the points of what
    // that erratum does not touch, and the erratum named.
    let course = &results.iter().find(|r| r.0 == "course-text").unwrap().2;
    assert_eq!(unit("course-text", "sao.sampling"), 0);
    // At the default level (lesson) it also loses what the pages add to the listing (the edge
    // guard) and the smoothing's derivatives inside a branch (appendix A #22): 20 of SAO's 50.
    assert_eq!(score("course-text"), 70, "{course}");
    let sampling = course["tests"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["id"] == "sao.sampling")
        .unwrap();
    assert!(
        sampling["message"].as_str().unwrap().contains("#20"),
        "the erratum is named: {sampling}"
    );
}

fn str_at<'a>(v: &'a Value, key: &str) -> &'a str {
    v.get(key)
        .and_then(Value::as_str)
        .unwrap_or_else(|| panic!("no string {key} in {v:?}"))
}

/// The actions and versions of docs/grade/known-actions.md.
fn known_actions() -> Vec<String> {
    let doc = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/grade/known-actions.md");
    let text = std::fs::read_to_string(doc).unwrap();
    text.lines()
        .filter(|l| l.starts_with("| `"))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(|c| c.trim().trim_matches('`')).collect();
            format!("{}@{}", cells[1], cells[2])
        })
        .collect()
}

/// Every `uses:` of a workflow, wherever it stands.
fn uses(v: &Value, out: &mut Vec<String>) {
    match v {
        Value::Mapping(m) => {
            for (k, v) in m {
                if k.as_str() == Some("uses") {
                    out.push(v.as_str().unwrap().to_string());
                }
                uses(v, out);
            }
        }
        Value::Sequence(s) => s.iter().for_each(|v| uses(v, out)),
        _ => {}
    }
}

#[test]
fn every_action_a_template_uses_is_a_known_one() {
    let known = known_actions();
    assert!(known.len() >= 5, "{known:?}");
    let dir = temp_dir("actions-known");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(["lesson", "start", "--classroom", "actions"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    let release =
        Path::new(env!("CARGO_MANIFEST_DIR")).join(".github/workflows/grader-release.yml");
    for file in [dir.join(".github/workflows/classroom.yml"), release] {
        let text = std::fs::read_to_string(&file).unwrap();
        let workflow: Value = serde_yaml::from_str(&text).expect("a workflow is YAML");
        let mut used = Vec::new();
        uses(&workflow, &mut used);
        assert!(!used.is_empty(), "{}", file.display());
        for u in used {
            assert!(
                known.contains(&u),
                "{}: `{u}` is not in known-actions.md",
                file.display()
            );
        }
    }
    // The check itself can fail: the name the old template used is not known.
    assert!(!known.contains(&"education/autograding-grader-reporter@v1".to_string()));
}

#[test]
fn the_actions_workflow_gives_each_step_its_verdict_from_result_json() {
    let dir = temp_dir("actions-workflow");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(["--lang", "ja", "lesson", "start", "--classroom", "actions"])
        .args(["--points", "sao=40,blur=20"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    let text = std::fs::read_to_string(dir.join(".github/workflows/classroom.yml")).unwrap();
    let workflow: Value = serde_yaml::from_str(&text).expect("the workflow is YAML");
    assert!(workflow["on"].get("push").is_some(), "runs on push");
    assert_eq!(str_at(&workflow["permissions"], "checks"), "write");
    let env = &workflow["env"];
    let version = env!("CARGO_PKG_VERSION");
    assert_eq!(str_at(env, "OPENGL3D_VERSION"), version);
    assert_eq!(str_at(env, "OPENGL3D_TAG"), format!("v{version}"));
    assert!(str_at(env, "OPENGL3D_RELEASE").ends_with(&format!("/releases/download/v{version}")));
    let job = &workflow["jobs"]["run-autograding-tests"];
    let steps = job["steps"].as_sequence().unwrap();
    let cache = steps
        .iter()
        .find(|s| s.get("uses").and_then(Value::as_str) == Some("actions/cache@v4"))
        .expect("a cache step");
    assert!(
        str_at(&cache["with"], "key").contains("env.OPENGL3D_TAG"),
        "the key names the pin"
    );
    let install = steps
        .iter()
        .filter_map(|s| s.get("run").and_then(Value::as_str))
        .find(|r| r.contains("cargo install"))
        .expect("a build step");
    assert!(
        install.contains("--profile grader --no-default-features")
            && install.contains("--tag \"$OPENGL3D_TAG\""),
        "{install}"
    );
    let grade = steps
        .iter()
        .filter_map(|s| s.get("run").and_then(Value::as_str))
        .find(|r| r.contains("grade --format classroom50"))
        .expect("one grading step");
    assert!(
        grade.contains("--lang ja") && grade.contains("sao.smoothing=8"),
        "{grade}"
    );
    let mut tests = Vec::new();
    for s in steps {
        if s.get("uses").and_then(Value::as_str)
            == Some("classroom-resources/autograding-command-grader@v1")
        {
            let with = &s["with"];
            tests.push((
                str_at(s, "id").to_string(),
                str_at(with, "command").to_string(),
                with["max-score"].as_u64().unwrap(),
            ));
        }
    }
    let ids: Vec<&str> = tests.iter().map(|t| t.0.as_str()).collect();
    let sao = ["normal", "sampling", "occlusion", "smoothing", "view"].map(|p| format!("sao_{p}"));
    let mut want = vec!["restore", "down_sampling", "simple"];
    want.extend(sao.iter().map(String::as_str));
    want.push("blur");
    assert_eq!(ids, want);
    // sao=40 spreads over its five sub-steps.
    assert_eq!(
        tests.iter().map(|t| t.2).collect::<Vec<_>>(),
        [20, 10, 10, 8, 8, 8, 8, 8, 20]
    );
    let reporter = steps.last().unwrap();
    assert_eq!(
        str_at(reporter, "uses"),
        "classroom-resources/autograding-grading-reporter@v1"
    );
    assert_eq!(str_at(&reporter["with"], "runners"), ids.join(","));
    for t in &tests {
        let var = format!("{}_RESULTS", t.0.to_uppercase());
        assert_eq!(
            str_at(&reporter["env"], &var),
            format!("${{{{steps.{}.outputs.result}}}}", t.0)
        );
    }
    // The reading commands, run with jq (as on GitHub's runners) on the grader's own result.json of
    // a student whose down-sampling keeps the max: only that test fails.
    if !have("jq") {
        panic!("jq is needed to run the workflow's reading commands (GitHub's runners have it)");
    }
    put(&dir, "lesson-restore");
    put(&dir, "down-sampling-max");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args([
            "--lang",
            "ja",
            "--res",
            ".",
            "grade",
            "--step",
            "restore,down-sampling",
        ])
        .args(["--format", "classroom50"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    for (id, command, _) in &tests[..2] {
        let o = Command::new("bash")
            .args(["-c", command])
            .current_dir(&dir)
            .output()
            .unwrap();
        let failed = id == "down_sampling";
        assert_eq!(!o.status.success(), failed, "{id}: {command}");
        assert!(!o.stdout.is_empty(), "{id} prints the grader's message");
    }
    let o = Command::new("bash")
        .args(["-c", &tests[3].1])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(!o.status.success(), "a step not graded does not pass");
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
    for (name, from) in [("ada", "lesson-restore"), ("bob", "restore-max")] {
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
        "student,restore,restore points,passed,points,max points,level"
    );
    assert!(rows.contains(&"ada,PASS,20,1,20,20,lesson"), "{csv}");
    assert!(rows.contains(&"bob,FAIL,0,0,0,20,lesson"), "{csv}");
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

#[test]
fn an_installed_grader_needs_no_source_tree() {
    // As `cargo install` leaves it: the binary alone in a folder of its own, away from the tree.
    let bin = outside_dir("installed");
    let exe = bin.join("opengl3d");
    std::fs::copy(env!("CARGO_BIN_EXE_opengl3d"), &exe).unwrap();
    let cache = outside_dir("installed-cache");
    let run = |args: &[&str]| {
        Command::new(&exe)
            .args(args)
            .current_dir(&bin)
            .env("XDG_CACHE_HOME", &cache)
            .output()
            .unwrap()
    };
    // The project's own shaders pass their own grading, read from the copy built into the binary.
    let o = run(&["grade"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}\n{}", crate::common::stderr(&o));
    let source = env!("CARGO_MANIFEST_DIR");
    assert!(!out.contains(source), "reads the source tree: {out}");
    assert!(out.contains(&cache.display().to_string()), "{out}");
    // A student's folder is written from it too, and graded.
    let o = run(&["lesson", "start", "work"]);
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    assert!(bin.join("work/sao.frag").is_file() && bin.join("work/scenes/demo.toml").is_file());
    let o = run(&["--res", "work", "grade", "--step", "restore"]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "the stub fails: {}",
        crate::common::stderr(&o)
    );
    // A pruned cache is noticed and written again.
    let extracted = std::fs::read_dir(cache.join("opengl3d"))
        .unwrap()
        .filter_map(Result::ok)
        .find(|e| e.file_name().to_string_lossy().starts_with("res-"))
        .unwrap()
        .path();
    std::fs::remove_file(extracted.join("sao_blur.frag")).unwrap();
    let o = run(&["grade", "--step", "blur"]);
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    assert!(extracted.join("sao_blur.frag").is_file());
}

#[test]
fn the_class_edition_leaves_out_every_answer_listing() {
    let dir = temp_dir("edition");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(["--lang", "ja", "lesson", "edition"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    let lessons = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    // The lines of the project's five lesson shaders that a stub does not have: the answers.
    let mut answer_lines = Vec::new();
    for f in [
        "sao_restore_depth.frag",
        "sao_down_sampling.frag",
        "simple.frag",
        "sao.frag",
        "sao_blur.frag",
    ] {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("Res");
        let solution = std::fs::read_to_string(root.join(f)).unwrap();
        let stub = std::fs::read_to_string(root.join("lesson-stubs").join(f)).unwrap();
        for line in solution.lines().map(str::trim) {
            // Constants and declarations are the task's facts (the pages state them); statements
            // with an operator or a call are what a student writes.
            let given = ["//", "const ", "#", "layout", "uniform ", "in ", "out "]
                .iter()
                .any(|p| line.starts_with(p));
            let code = line.len() > 24 && !given && line.contains(['=', '(']);
            if code && !stub.contains(line) {
                answer_lines.push(line.to_string());
            }
        }
    }
    assert!(answer_lines.len() > 30, "{answer_lines:?}");
    let (mut pages, mut leaks) = (0, 0);
    for (source, edition) in [
        (lessons.clone(), dir.join("lessons")),
        (lessons.join("ja"), dir.join("lessons/ja")),
    ] {
        for e in std::fs::read_dir(&source).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_none_or(|x| x != "md") {
                continue;
            }
            let original = std::fs::read_to_string(&p).unwrap();
            let text = std::fs::read_to_string(edition.join(p.file_name().unwrap())).unwrap();
            pages += 1;
            // The page's text outside its folded blocks: what the task itself says stays.
            let (mut outside, mut inside) = (String::new(), String::new());
            for (i, part) in original.split("<details>").enumerate() {
                match part.split_once("</details>") {
                    Some((folded, rest)) if i > 0 => {
                        inside.push_str(folded);
                        outside.push_str(rest);
                    }
                    _ => outside.push_str(part),
                }
            }
            let found: Vec<&String> = answer_lines
                .iter()
                .filter(|l| inside.contains(l.as_str()) && !outside.contains(l.as_str()))
                .filter(|l| text.contains(l.as_str()))
                .collect();
            if !found.is_empty() {
                eprintln!("{}: {found:?}", p.display());
                leaks += found.len();
            }
            if !inside.is_empty() {
                assert!(text.len() < original.len(), "{}", p.display());
            }
        }
    }
    assert_eq!(leaks, 0, "answer lines left in the edition (listed above)");
    assert!(pages >= 26, "{pages} pages");
    for img in std::fs::read_dir(lessons.join("img")).unwrap() {
        let name = img.unwrap().file_name();
        assert!(dir.join("lessons/img").join(&name).exists(), "{name:?}");
    }
    for stub in ["sao.frag", "sao_blur.frag", "scenes/demo.toml"] {
        assert!(dir.join("start").join(stub).is_file(), "{stub}");
    }
    let sao = std::fs::read_to_string(dir.join("start/sao.frag")).unwrap();
    assert!(
        sao.contains("レッスン") || sao.contains("ステップ"),
        "Japanese stub comments"
    );
}

/// A local HTTP server on loopback serving `dir` (python3's), stopped on drop.
struct Server(std::process::Child, u16);

impl Server {
    fn start(dir: &Path) -> Server {
        let port = {
            let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
            l.local_addr().unwrap().port()
        };
        let child = Command::new("python3")
            .args([
                "-m",
                "http.server",
                "--bind",
                "127.0.0.1",
                &port.to_string(),
            ])
            .current_dir(dir)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        for _ in 0..100 {
            if std::net::TcpStream::connect(("127.0.0.1", port)).is_ok() {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        Server(child, port)
    }
    fn url(&self) -> String {
        format!("http://127.0.0.1:{}", self.1)
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn the_prebuilt_grader_is_downloaded_checked_and_refused_when_its_checksum_differs() {
    // The Release as grader-release.yml publishes it: the binary in a .tar.gz and its .sha256.
    let release = outside_dir("release");
    let staged = outside_dir("release-staged");
    std::fs::copy(env!("CARGO_BIN_EXE_opengl3d"), staged.join("opengl3d")).unwrap();
    let asset = "opengl3d-grader-x86_64-linux.tar.gz";
    let tar = Command::new("tar")
        .args(["-czf"])
        .arg(release.join(asset))
        .arg("-C")
        .arg(&staged)
        .arg("opengl3d")
        .status()
        .unwrap();
    assert!(tar.success());
    let sum = Command::new("sha256sum")
        .arg(asset)
        .current_dir(&release)
        .output()
        .unwrap();
    std::fs::write(release.join(format!("{asset}.sha256")), &sum.stdout).unwrap();
    let server = Server::start(&release);

    let teacher = temp_dir("c50-download");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args([
            "lesson",
            "start",
            "--classroom",
            "classroom50",
            "--grader-repo",
            "school/opengl3d",
        ])
        .arg(&teacher)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    let written = std::fs::read_to_string(teacher.join("autograder/autograder.py")).unwrap();
    let github = format!(
        "https://github.com/school/opengl3d/releases/download/v{}",
        env!("CARGO_PKG_VERSION")
    );
    assert!(written.contains(&github), "the Release of the pinned tag");
    // The same autograder pointed at the local copy of that Release, with no source fallback.
    let bundle = outside_dir("c50-download-bundle");
    let local = written.replace(&github, &server.url()).replace(
        "GRADER_GIT = \"https://github.com/school/opengl3d\"",
        "GRADER_GIT = \"\"",
    );
    std::fs::write(bundle.join("autograder.py"), &local).unwrap();
    let class = outside_dir("c50-download-class");
    let dir = student(&class, "ada", &teacher.join("template"), &[]);
    let env = [
        ("CLASSROOM", "cg"),
        ("ASSIGNMENT", "ao"),
        ("SUBMISSION_TAG", "submit/x"),
        ("COMMIT_URL", "c"),
        ("RELEASE_URL", "r"),
        ("REVIEW_URL", "v"),
    ];
    let runner_tmp = outside_dir("c50-download-tmp");
    let download_cache = outside_dir("c50-download-cache");
    let run = || {
        Command::new("python3")
            .arg(bundle.join("autograder.py"))
            .current_dir(&dir)
            .envs(env)
            .env("XDG_CACHE_HOME", &download_cache)
            .env("TMPDIR", &runner_tmp)
            .output()
            .unwrap()
    };
    let o = run();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    // The downloaded grader lives only as long as the run.
    let left: Vec<_> = std::fs::read_dir(&runner_tmp)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "autograder.py left {left:?} in TMPDIR");
    let r: Json =
        serde_json::from_str(&std::fs::read_to_string(dir.join("result.json")).unwrap()).unwrap();
    check_contract(&r, &env);
    // A corrupted or truncated download is refused, and nothing pretends to have graded.
    std::fs::write(
        release.join(format!("{asset}.sha256")),
        format!("{} {asset}\n", "0".repeat(64)),
    )
    .unwrap();
    let o = run();
    let err = crate::common::stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("does not match its .sha256"), "{err}");
    assert!(
        !dir.join("result.json").exists(),
        "no result without a grader"
    );

    // The plain Actions workflow's download step, run by bash as the runner runs a `run:` step
    // (`bash --noprofile --norc -eo pipefail`), against the same Release: refused while the checksum
    // is wrong, installed once it is right.
    let actions = temp_dir("actions-download");
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(["lesson", "start", "--classroom", "actions"])
        .arg(&actions)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    let text = std::fs::read_to_string(actions.join(".github/workflows/classroom.yml")).unwrap();
    let workflow: Value = serde_yaml::from_str(&text).unwrap();
    let step = workflow["jobs"]["run-autograding-tests"]["steps"]
        .as_sequence()
        .unwrap()
        .iter()
        .find(|s| s.get("name").and_then(Value::as_str) == Some("Prebuilt grader"))
        .expect("a download step");
    let script = str_at(step, "run").to_string();
    let home = outside_dir("actions-home");
    let runner_temp = outside_dir("actions-temp");
    let github_path = runner_temp.join("github_path");
    let download = || {
        Command::new("bash")
            .args(["--noprofile", "--norc", "-eo", "pipefail", "-c", &script])
            .env("OPENGL3D_RELEASE", server.url())
            .env("HOME", &home)
            .env("RUNNER_TEMP", &runner_temp)
            .env("GITHUB_PATH", &github_path)
            .output()
            .unwrap()
    };
    let o = download();
    assert!(!o.status.success(), "a wrong checksum passes");
    assert!(!home.join(".local/bin/opengl3d").exists());
    std::fs::write(release.join(format!("{asset}.sha256")), &sum.stdout).unwrap();
    let o = download();
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    let installed = Command::new(home.join(".local/bin/opengl3d"))
        .arg("--version")
        .output()
        .unwrap();
    let version = format!("opengl3d {}", env!("CARGO_PKG_VERSION"));
    assert_eq!(String::from_utf8_lossy(&installed.stdout).trim(), version);
    let path = std::fs::read_to_string(&github_path).unwrap();
    assert!(path.contains(".local/bin"), "{path}");
}
