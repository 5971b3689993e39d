//! Commands whose stdout is a pipe nobody reads (`| head -c1`, `| true`): no panic, no backtrace,
//! the command's own exit status (0 on success, the grader's 1 on a failed step), files still written.

use crate::common::{bin, temp_dir};
use std::path::{Path, PathBuf};
use std::process::Stdio;

/// Runs the binary with its stdout a pipe whose read end is already closed; returns the exit code
/// and stderr.
fn run_into_closed_pipe(args: &[&str]) -> (Option<i32>, String) {
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    let o = bin()
        .args(args)
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .expect("run opengl3d");
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Asserts exit code `want` without a panic, a backtrace or a message about stdout.
fn expect(args: &[&str], want: i32) {
    let (code, stderr) = run_into_closed_pipe(args);
    assert!(
        !stderr.contains("panicked") && !stderr.contains("Broken pipe"),
        "{args:?} into a closed pipe:\n{stderr}"
    );
    assert!(
        !stderr.contains("standard output"),
        "a closed pipe is not an error worth a message: {args:?}\n{stderr}"
    );
    assert_eq!(code, Some(want), "{args:?} exit status; stderr:\n{stderr}");
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn mutant(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/mutants")
        .join(name)
}

#[test]
fn render_and_its_stats_into_a_closed_pipe_exit_0_and_write_the_file() {
    let dir = temp_dir("pipe-render");
    let out = dir.join("frame.png");
    let size = ["--width", "48", "--height", "32"];
    expect(&[&["render", "--out", s(&out)][..], &size].concat(), 0);
    assert!(
        out.is_file(),
        "the frame is written even though stdout is closed"
    );
    let stats = dir.join("stats.png");
    expect(
        &[&["render", "--stats", "--out", s(&stats)][..], &size].concat(),
        0,
    );
    assert!(stats.is_file());
}

#[test]
fn reference_into_a_closed_pipe_exits_0() {
    let dir = temp_dir("pipe-reference");
    let out = dir.join("ref.pfm");
    let cache = dir.join("cache");
    expect(
        &[
            "reference",
            "--width",
            "16",
            "--height",
            "9",
            "--rays",
            "4",
            "--out",
            s(&out),
            "--cache",
            s(&cache),
        ],
        0,
    );
    assert!(out.is_file());
}

#[test]
fn lesson_start_and_the_overview_into_a_closed_pipe_exit_0() {
    let dir = temp_dir("pipe-lesson").join("student");
    expect(&["lesson", "start", s(&dir)], 0);
    assert!(dir.join("sao.frag").is_file());
    expect(&["lesson"], 0);
}

#[test]
fn grade_into_a_closed_pipe_keeps_its_verdict_in_the_exit_status() {
    let passing = mutant("listing-simple");
    let failing = mutant("simple-flipped");
    for json in [&[][..], &["--json"][..]] {
        for (dir, code) in [(&passing, 0), (&failing, 1)] {
            let args = [&["grade", "--step", "simple", "--res", s(dir)][..], json].concat();
            expect(&args, code);
        }
    }
}

#[test]
fn output_lost_to_a_full_disk_is_reported_and_fails() {
    // /dev/full: every write fails with ENOSPC, which is not a reader going away.
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    let o = bin()
        .arg("lesson")
        .stdout(full)
        .stderr(Stdio::piped())
        .output()
        .expect("run opengl3d");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(
        stderr.matches("cannot write to standard output").count(),
        1,
        "one message:\n{stderr}"
    );
    assert_eq!(o.status.code(), Some(1), "{stderr}");
}
