//! `grade --challenge`: a class of five method files (two honest variants of `hbao`, an unchanged
//! copy of the engine's `hbao`, one whose shader does not compile, one far over the cost budget)
//! ranked with the right reasons, pictures per entry, containment as the grader's.

use crate::common::{run, stderr, temp_dir};
use std::path::Path;

fn example(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs/method-file")
        .join(name);
    std::fs::read_to_string(path).unwrap()
}

/// Writes one student's folder: the example's files with `frag` and `toml` edited.
fn student(
    class: &Path,
    who: &str,
    frag: impl Fn(String) -> String,
    toml: impl Fn(String) -> String,
) {
    let dir = class.join(who);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("my_hbao.frag"), frag(example("my_hbao.frag"))).unwrap();
    let named = example("my_hbao.toml").replace("my-hbao", &format!("{who}-ao"));
    std::fs::write(dir.join("ao.toml"), toml(named)).unwrap();
}

#[test]
fn a_class_challenge_ranks_honest_entries_and_says_why_the_others_are_not() {
    let dir = temp_dir("challenge");
    let class = dir.join("class");
    let same = |s: String| s;
    student(&class, "alice", same, same);
    student(
        &class,
        "bob",
        |f| f.replacen("vec3 P = TexelPos(pix);", "vec9 P = TexelPos(pix);", 1),
        same,
    );
    student(&class, "carol", same, |t| {
        t.replace("counts = [4, \"samples/4\"]", "counts = [32, 48]")
    });
    student(&class, "dave", same, |t| {
        t.replace("default = 0.1736", "default = 0.05")
    });
    student(&class, "erin", same, |t| {
        t.replace("default = 0.1736", "default = 0.35")
    });
    let out = dir.join("report");
    // A budget of 3× keeps the honest entries (about the lesson chain's cost) clear of a loaded
    // machine's noise; carol's 32 × 48 taps cost many times more.
    let o = run(&[
        "grade",
        "--challenge",
        class.to_str().unwrap(),
        "--budget",
        "3",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let entries = results["entries"].as_array().unwrap();
    let by_name = |name: &str| {
        entries
            .iter()
            .find(|e| e["name"] == name)
            .unwrap_or_else(|| panic!("{name} missing: {entries:?}"))
    };
    // The two honest variants are ranked 1 and 2, by PSNR.
    let (dave, erin) = (by_name("dave-ao"), by_name("erin-ao"));
    let ranked: Vec<&serde_json::Value> = entries.iter().filter(|e| !e["rank"].is_null()).collect();
    assert_eq!(ranked.len(), 2, "{entries:?}");
    assert!(ranked[0]["psnr"].as_f64() >= ranked[1]["psnr"].as_f64());
    assert!(dave["reason"].is_null() && erin["reason"].is_null());
    // The others, each with its reason.
    let reason = |name: &str| by_name(name)["reason"].as_str().unwrap_or("").to_string();
    assert!(
        reason("alice-ao").contains("hbao"),
        "{}",
        reason("alice-ao")
    );
    assert!(
        reason("bob-ao").contains("my_hbao.frag:"),
        "{}",
        reason("bob-ao")
    );
    assert!(
        reason("carol-ao").contains("over the budget"),
        "{}",
        reason("carol-ao")
    );
    for who in ["alice-ao", "bob-ao", "carol-ao"] {
        assert!(by_name(who)["rank"].is_null(), "{who} must not be ranked");
    }
    // Pictures per measured entry, linked from the page.
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    for e in [dave, erin] {
        let folder = e["pictures"].as_str().unwrap();
        for picture in ["demo-ao.png", "demo-error.png"] {
            assert!(
                out.join(folder).join(picture).is_file(),
                "{folder}/{picture}"
            );
            assert!(page.contains(&format!("{folder}/{picture}")));
        }
    }
    assert!(out.join("truth-demo.png").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_challenge_without_entries_says_so() {
    let dir = temp_dir("challenge-empty");
    let o = run(&[
        "grade",
        "--challenge",
        dir.to_str().unwrap(),
        "--out",
        dir.join("r").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("no method files"), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}
