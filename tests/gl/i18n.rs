//! Messages in Japanese: `--lang ja|en` on any command, else LC_ALL / LC_MESSAGES / LANG; `--json`
//! keeps its English keys and messages and adds `message_localised`.

use crate::common;
use serde_json::Value;
use std::process::Output;

/// The binary with the locale variables set to exactly `env` (the others removed).
fn run(env: &[(&str, &str)], args: &[&str]) -> Output {
    let mut cmd = crate::common::bin();
    for v in ["LC_ALL", "LC_MESSAGES", "LANG", "LANGUAGE"] {
        cmd.env_remove(v);
    }
    cmd.envs(env.iter().copied())
        .args(args)
        .output()
        .expect("run opengl3d")
}

fn out(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const JA: (&str, &str) = ("LANG", "ja_JP.UTF-8");
const C: (&str, &str) = ("LANG", "C.UTF-8");

fn is_japanese_overview(s: &str) -> bool {
    s.contains("ステップ:") && s.contains("表示:") && s.contains("lessons/ja/")
}

#[test]
fn lang_ja_writes_the_lesson_overview_in_japanese() {
    let o = run(&[C], &["--lang", "ja", "lesson"]);
    assert!(o.status.success(), "{}", err(&o));
    assert!(is_japanese_overview(&out(&o)), "{}", out(&o));
    assert!(!out(&o).contains("shows"), "{}", out(&o));
    // The flag after the command works too.
    let o = run(&[C], &["lesson", "--lang", "ja"]);
    assert!(is_japanese_overview(&out(&o)), "{}", out(&o));
}

#[test]
fn the_locale_chooses_japanese_without_the_flag() {
    let o = run(&[JA], &["lesson"]);
    assert!(is_japanese_overview(&out(&o)), "{}", out(&o));
    let o = run(&[("LC_MESSAGES", "ja_JP.UTF-8"), C], &["lesson"]);
    assert!(is_japanese_overview(&out(&o)), "{}", out(&o));
}

#[test]
fn lang_en_and_lc_all_c_win_over_a_japanese_lang() {
    for (env, args) in [
        (vec![JA], vec!["--lang", "en", "lesson"]),
        (vec![JA, ("LC_ALL", "C")], vec!["lesson"]),
        (vec![C], vec!["lesson"]),
    ] {
        let o = run(&env, &args);
        let s = out(&o);
        assert!(o.status.success(), "{}", err(&o));
        assert!(
            s.contains("steps:") && s.contains(" shows "),
            "{env:?} {args:?}: {s}"
        );
        assert!(!s.contains("ステップ"), "{env:?} {args:?}: {s}");
    }
}

#[test]
fn lesson_start_speaks_japanese() {
    let dir = common::temp_dir("i18n-lesson-start");
    let d = dir.join("work");
    let o = run(&[JA], &["lesson", "start", d.to_str().unwrap()]);
    assert!(o.status.success(), "{}", err(&o));
    let s = out(&o);
    assert!(s.contains("個のファイルを書き出しました"), "{s}");
    assert!(s.contains("5つの課題シェーダーはスタブです"), "{s}");
    // The stubs are commented in Japanese and point to the Japanese pages.
    let stub = std::fs::read_to_string(d.join("sao_restore_depth.frag")).unwrap();
    assert!(
        stub.contains("lessons/ja/02-restore-pass.md") && stub.contains("課題のステップ2"),
        "{stub}"
    );
    assert!(!stub.contains("Lesson step"), "{stub}");
    let o = run(&[JA], &["lesson", "start", d.to_str().unwrap()]);
    assert!(out(&o).contains("そのまま残しました"), "{}", out(&o));
    // The step list names each step's view in Japanese too.
    let o = run(&[JA], &["lesson"]);
    let s = format!("{}{}", out(&o), err(&o));
    assert!(s.contains("表示: 線形距離"), "{s}");
    assert!(s.contains("表示: ぼかした遮蔽率"), "{s}");
    assert!(!s.contains("linear depth"), "{s}");
}

#[test]
fn grading_an_empty_folder_says_not_submitted_in_japanese() {
    let dir = common::temp_dir("i18n-grade-empty");
    let res = dir.to_str().unwrap();
    let o = run(&[C], &["grade", "--lang", "ja", "--res", res]);
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    let s = out(&o);
    assert_eq!(s.matches("不合格 ").count(), 5, "{s}");
    assert!(
        s.contains(&format!("未提出: {res}にsao.fragがありません")),
        "{s}"
    );
    assert!(s.contains("5ステップ中5ステップが不合格です"), "{s}");
    assert!(!s.contains("FAIL") && !s.contains("not submitted"), "{s}");
}

#[test]
fn a_missing_student_folder_is_said_in_japanese_only() {
    let missing = common::temp_dir("i18n-grade-missing").join("nosuch");
    let res = missing.to_str().unwrap();
    let o = run(&[C], &["grade", "--lang", "ja", "--res", res]);
    assert_ne!(o.status.code(), Some(0));
    let e = err(&o);
    assert!(e.contains("フォルダーではありません(存在しません)"), "{e}");
    assert!(
        !e.contains("No such file") && !e.contains("os error"),
        "{e}"
    );
    let o = run(&[C], &["grade", "--lang", "en", "--res", res]);
    assert!(
        err(&o).contains("not a folder (it does not exist)"),
        "{}",
        err(&o)
    );
}

#[test]
fn json_keeps_english_and_adds_the_localised_message() {
    let dir = common::temp_dir("i18n-grade-json");
    let res = dir.to_str().unwrap();
    let keys = |v: &Value| -> Vec<String> { v.as_object().unwrap().keys().cloned().collect() };
    let o = run(&[JA], &["--res", res, "grade", "--json", "--step", "sao"]);
    let v: Value = serde_json::from_str(out(&o).trim()).expect("JSON");
    assert_eq!(keys(&v), ["level", "passed", "steps"]);
    let step = &v["steps"][0];
    assert_eq!(
        keys(step),
        [
            "file",
            "message",
            "message_localised",
            "passed",
            "step",
            "submitted"
        ]
    );
    assert_eq!(
        step["message"],
        format!("not submitted: no sao.frag in {res}")
    );
    assert_eq!(
        step["message_localised"],
        format!("未提出: {res}にsao.fragがありません")
    );
    // In English there is nothing to add.
    let o = run(&[C], &["--res", res, "grade", "--json", "--step", "sao"]);
    let v: Value = serde_json::from_str(out(&o).trim()).expect("JSON");
    assert_eq!(
        keys(&v["steps"][0]),
        ["file", "message", "passed", "step", "submitted"]
    );
}

#[test]
fn common_command_line_errors_in_japanese() {
    let dir = common::temp_dir("i18n-errors");
    let missing = dir.join("nowhere");
    let o = run(&[JA], &["--res", missing.to_str().unwrap(), "render"]);
    assert!(!o.status.success());
    assert!(
        err(&o).contains("そのようなフォルダーはありません"),
        "{}",
        err(&o)
    );
    let o = run(
        &[JA],
        &["render", "--out", dir.join("f.bmp").to_str().unwrap()],
    );
    assert!(!o.status.success());
    assert!(
        err(&o).contains("拡張子は.pngまたは.pfmにしてください"),
        "{}",
        err(&o)
    );
    let o = run(&[JA], &["lesson", "x"]);
    assert!(
        err(&o).contains("'x'はステップではありません"),
        "{}",
        err(&o)
    );
    // The same error in English with --lang en.
    let o = run(&[JA], &["--lang", "en", "lesson", "x"]);
    assert!(err(&o).contains("'x' is not a step"), "{}", err(&o));
}

/// A failing mutant with `--lang ja`: the verdict and its hint in Japanese in the text report; with
/// `--json`, `message` stays the English verdict and `message_localised` carries the Japanese one.
#[test]
fn verdicts_and_hints_in_japanese_and_json_keeps_english() {
    let mutant = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mutants/restore-max");
    let res = mutant.to_str().unwrap();
    let o = run(
        &[C],
        &["--lang", "ja", "--res", res, "grade", "--step", "restore"],
    );
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    let s = out(&o);
    assert!(
        s.contains("不合格 sao_restore_depth.frag: 各2×2ブロックで最も遠いテクセルを残しています"),
        "{s}"
    );
    assert!(s.contains("最も近い深度(min)を選んでください"), "{s}");
    assert!(!s.contains("keeps the farthest"), "{s}");
    let o = run(
        &[JA],
        &["--res", res, "grade", "--json", "--step", "restore"],
    );
    let v: Value = serde_json::from_str(out(&o).trim()).expect("JSON");
    let step = &v["steps"][0];
    assert_eq!(
        step["message"],
        "keeps the farthest texel of each 2×2 block (max instead of min?): the nearest depth \
         (min) must win"
    );
    let ja = step["message_localised"]
        .as_str()
        .expect("a localised message");
    assert!(ja.starts_with("各2×2ブロックで最も遠いテクセル"), "{ja}");
    // A passing step's summary is translated too.
    let listing =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mutants/listing-simple");
    let o = run(
        &[JA],
        &[
            "--res",
            listing.to_str().unwrap(),
            "grade",
            "--json",
            "--step",
            "simple",
        ],
    );
    let v: Value = serde_json::from_str(out(&o).trim()).expect("JSON");
    let step = &v["steps"][0];
    assert_eq!(step["passed"], true, "{v}");
    assert!(
        step["message"]
            .as_str()
            .unwrap()
            .starts_with("copies every channel"),
        "{v}"
    );
    assert!(
        step["message_localised"]
            .as_str()
            .unwrap()
            .contains("全チャンネル"),
        "{v}"
    );
}

/// Every `grade.verdict.*` key the grader's sources use is in both locale files, and every one the
/// files hold is used (a missing key would print the key itself instead of a message).
#[test]
fn every_verdict_key_is_in_both_languages_and_used() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut used = std::collections::BTreeSet::new();
    let mut dirs = vec![root.join("src/tools/grade")];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let text = std::fs::read_to_string(&p).unwrap();
                for (i, _) in text.match_indices("\"grade.verdict.") {
                    let key: String = text[i + 1..].chars().take_while(|c| *c != '"').collect();
                    used.insert(key);
                }
            }
        }
    }
    assert!(used.len() > 60, "{used:?}");
    for lang in ["en", "ja"] {
        let file = std::fs::read_to_string(root.join(format!("locales/{lang}.yml"))).unwrap();
        let keys: std::collections::BTreeSet<String> = file
            .lines()
            .filter(|l| l.starts_with("grade.verdict."))
            .map(|l| l.split(':').next().unwrap().to_string())
            .collect();
        let missing: Vec<_> = used.difference(&keys).collect();
        let unused: Vec<_> = keys.difference(&used).collect();
        assert!(missing.is_empty(), "{lang}.yml lacks {missing:?}");
        assert!(unused.is_empty(), "{lang}.yml has unused {unused:?}");
    }
}

#[test]
fn render_and_reference_speak_japanese() {
    let dir = common::temp_dir("i18n-render");
    let frame = dir.join("f.png");
    let size = ["--width", "64", "--height", "48"];
    let mut args = vec!["render", "--out", frame.to_str().unwrap()];
    args.extend(size);
    let o = run(&[JA], &args);
    assert!(o.status.success(), "{}", err(&o));
    assert!(out(&o).contains("を書き出しました(64×48、"), "{}", out(&o));
    let o = run(&[C], &args);
    assert!(out(&o).starts_with("wrote "), "{}", out(&o));

    let o = run(&[JA], &["render", "--samples", "0"]);
    assert!(
        err(&o).contains("--samples 0: 1から256までの値を指定してください"),
        "{}",
        err(&o)
    );
    let o = run(&[JA], &["render", "--obj", "nowhere.obj"]);
    assert!(
        err(&o).contains("nowhere.obj: モデルファイル(OBJ、glTF)が見つかりません"),
        "{}",
        err(&o)
    );

    let pfm = dir.join("r.pfm");
    let cache = dir.join("cache");
    let mut args = vec![
        "reference",
        "--rays",
        "2",
        "--out",
        pfm.to_str().unwrap(),
        "--cache",
        cache.to_str().unwrap(),
    ];
    args.extend(size);
    let o = run(&[JA], &args);
    assert!(o.status.success(), "{}", err(&o));
    assert!(
        out(&o).contains("を書き出しました(レイトレーシング、64×48、"),
        "{}",
        out(&o)
    );
    let o = run(&[JA], &["reference", "--rays", "0"]);
    assert!(
        err(&o).contains("--raysは1から1048576までの値を指定してください"),
        "{}",
        err(&o)
    );
}

#[test]
fn usage_errors_in_japanese_with_the_usage_line() {
    // clap prints a usage line for an unknown name, not for a missing or wrong value.
    for (args, says, usage) in [
        (vec!["rendr"], "'rendr'というサブコマンドはありません", true),
        (
            vec!["render", "--bogus"],
            "'--bogus'という引数はありません",
            true,
        ),
        (
            vec!["render", "--out"],
            "'--out <OUT>'には値を指定してください",
            false,
        ),
        (
            vec!["render", "--view", "x"],
            "'x'は'--view <VIEW>'に指定できる値ではありません",
            false,
        ),
    ] {
        let o = run(&[JA], &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", err(&o));
        let e = err(&o);
        assert!(
            e.starts_with("エラー: ") && e.contains(says),
            "{args:?}: {e}"
        );
        assert_eq!(e.contains("使い方: opengl3d"), usage, "{args:?}: {e}");
        assert!(
            e.contains("詳しくは'--help'を付けて実行してください"),
            "{e}"
        );
        // --lang on the command line wins over the locale, even when parsing failed.
        let mut en = vec!["--lang", "en"];
        en.extend(&args);
        let e = err(&run(&[JA], &en));
        assert!(
            e.starts_with("error: ") && !e.contains("エラー"),
            "{args:?}: {e}"
        );
        assert_eq!(e.contains("Usage:"), usage, "{args:?}: {e}");
    }
    let e = err(&run(&[C], &["--lang", "ja", "rendr"]));
    assert!(e.contains("'rendr'というサブコマンドはありません"), "{e}");
    assert!(e.contains("'render'のことですか？"), "{e}");
}

#[test]
fn the_class_summary_and_a_refused_zip_in_japanese() {
    let class = common::temp_dir("i18n-class");
    std::fs::create_dir_all(class.join("ada")).unwrap();
    std::fs::write(class.join("bob.zip"), "PK not really").unwrap();
    let report = class.join("report");
    let o = run(
        &[JA],
        &[
            "grade",
            "--class",
            class.to_str().unwrap(),
            "--out",
            report.to_str().unwrap(),
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    let s = out(&o);
    assert!(s.contains("の学生2人を採点します"), "{s}");
    assert!(s.contains("不合格 bob: 5ステップ中0ステップ合格"), "{s}");
    assert!(s.contains("2人中0人が全ステップに合格しました"), "{s}");
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    assert!(html.contains("<html lang=\"ja\">"), "{html}");
    assert!(
        html.contains("アーカイブを受け付けません: ")
            && html.contains("bob.zipは読み込める.zipファイルではありません"),
        "{html}"
    );
    // junit.xml is written in the chosen language too (its element names stay JUnit's).
    let junit = std::fs::read_to_string(report.join("junit.xml")).unwrap();
    assert!(
        junit.contains("<testsuites") && junit.contains("アーカイブを受け付けません"),
        "{junit}"
    );
}

#[test]
fn help_is_written_in_japanese() {
    let o = run(&[JA], &["--help"]);
    assert!(o.status.success(), "{}", err(&o));
    let s = out(&o);
    for says in [
        "使い方: opengl3d",
        "コマンド:",
        "オプション:",
        "ヘルプを表示します",
        "採点します",
    ] {
        assert!(s.contains(says), "{says}: {s}");
    }
    assert!(!s.contains("Usage:") && !s.contains("Print help"), "{s}");
    let s = out(&run(&[JA], &["lesson", "--help"]));
    assert!(
        s.contains("ステップの番号1～12") && s.contains("引数:"),
        "{s}"
    );
    // English stays clap's own.
    let s = out(&run(&[C], &["--help"]));
    assert!(
        s.contains("Usage: opengl3d") && s.contains("Print help"),
        "{s}"
    );
}

#[test]
fn errors_and_the_headless_fallback_are_said_in_japanese() {
    let o = run(&[JA], &["render", "--obj", "nowhere.obj"]);
    assert!(err(&o).starts_with("エラー: "), "{}", err(&o));
    assert!(
        err(&run(&[C], &["render", "--obj", "nowhere.obj"])).starts_with("error: "),
        "English keeps its prefix"
    );
    // Without a display, `lesson N` says why it writes a file instead of opening a window.
    let dir = common::temp_dir("i18n-no-display");
    let png = dir.join("step3.png");
    let mut cmd = common::bin();
    for v in [
        "LC_ALL",
        "LC_MESSAGES",
        "LANGUAGE",
        "DISPLAY",
        "WAYLAND_DISPLAY",
    ] {
        cmd.env_remove(v);
    }
    let args = ["lesson", "3", "--width", "32", "--height", "24", "--out"];
    let o = cmd
        .env("LANG", "ja_JP.UTF-8")
        .args(args)
        .arg(&png)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", err(&o));
    let e = err(&o);
    assert!(
        e.contains("ディスプレイが見つからない") && e.contains(png.to_str().unwrap()),
        "{e}"
    );
    assert!(out(&o).contains("線形距離を表示します"), "{}", out(&o));
    assert!(png.is_file());
}
