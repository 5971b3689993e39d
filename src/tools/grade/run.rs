//! `opengl3d grade`: grades the selected steps, each in its own child process with a time limit,
//! all at once, and prints their verdicts.

use super::args::{selected_steps, GradeArgs};
use super::child::Child;
use super::report::{self, StepReport};
use super::submission;
use crate::res::{project_res_dir, ResDirs};
use anyhow::{bail, Context as _, Result};
use rust_i18n::t;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// The children's private folder, removed when the grader leaves `run`, whatever happens (a step
/// killed at its time limit leaves its copy behind; a panic unwinds through here too).
struct WorkDir(PathBuf);

impl Drop for WorkDir {
    fn drop(&mut self) {
        // The verdicts stand whatever happens to the copies: a folder left behind is only reported.
        match std::fs::remove_dir_all(&self.0) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                eprintln!("warning: cannot remove {}: {e}", self.0.display())
            }
            _ => {}
        }
    }
}

/// A fresh private folder for the children's copies of the graded files.
fn work_dir() -> Result<WorkDir> {
    // The pid alone keeps concurrent graders apart; the clock only guards against a reused pid, so a
    // clock set before 1970 just leaves it out.
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    let work = std::env::temp_dir().join(format!("opengl3d-grade-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&work)
        .with_context(|| format!("cannot create folder {}", work.display()))?;
    Ok(WorkDir(work))
}

/// Grades the shaders found through `res`; returns the process exit code (0: every step passed).
pub fn run(_res: &ResDirs, student: Option<&Path>, args: &GradeArgs) -> Result<i32> {
    let steps = selected_steps(args)?;
    if let Some(dir) = student {
        match std::fs::metadata(dir) {
            Ok(m) if m.is_dir() => {}
            Ok(_) => bail!("{}", t!("grade.res_not_folder", dir = dir.display())),
            Err(e) => bail!("{} ({e})", t!("grade.res_not_folder", dir = dir.display())),
        }
    }
    if !(args.timeout > 0.0 && args.timeout.is_finite()) {
        bail!("{}", t!("grade.bad_timeout", value = args.timeout));
    }
    if let Some(out) = &args.out {
        std::fs::create_dir_all(out)
            .with_context(|| format!("cannot create folder {}", out.display()))?;
    }
    let exe = std::env::current_exe().context("cannot find the opengl3d executable")?;
    let work = work_dir()?;
    if !args.json {
        match student {
            Some(d) => println!(
                "{}",
                t!("grade.grading_dir", dir = d.display(), count = steps.len())
            ),
            None => println!(
                "{}",
                t!("grade.grading_project", dir = project_res_dir().display())
            ),
        }
    }
    // All steps at once: each is a separate process with its own deadline.
    let mut children = Vec::new();
    let mut reports = Vec::new();
    for &s in &steps {
        // A step with nothing to grade needs no child.
        if let Some(Err(reason)) = student.map(|d| submission::find(d, s)) {
            reports.push(Some(StepReport::not_submitted(s, &reason)));
            continue;
        }
        let mut cmd = Command::new(&exe);
        if let Some(d) = student {
            cmd.arg("--res").arg(d);
        }
        // The child writes its messages in the grader's language, whether flag or locale chose it.
        cmd.arg("--lang").arg(crate::i18n::current().code());
        cmd.arg("grade-step")
            .arg(s.name())
            .arg("--work")
            .arg(work.0.join(s.name()));
        if let Some(out) = &args.out {
            cmd.arg("--out").arg(out);
        }
        match Child::spawn(cmd, s) {
            Ok(child) => {
                children.push((reports.len(), child));
                reports.push(None);
            }
            Err(e) => reports.push(Some(StepReport::failed(
                s,
                format!("grader error: cannot start {}: {e}", exe.display()),
            ))),
        }
    }
    let timeout = Duration::from_secs_f64(args.timeout);
    for (i, c) in children {
        reports[i] = Some(c.finish(timeout));
    }
    drop(work);
    let reports: Vec<StepReport> = reports.into_iter().flatten().collect();
    let passed = reports.iter().all(|r| r.passed);
    if args.verbose {
        report::print_metrics(&reports);
    }
    if args.json {
        println!("{}", report::to_json(&reports)?);
    } else {
        report::print_text(&reports, args.out.as_deref());
    }
    Ok(if passed { 0 } else { 1 })
}
