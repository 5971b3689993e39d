//! Grading one student's folder: each selected step in its own child process, all steps at once,
//! one verdict per step. Both `grade --res DIR` and `grade --class DIR` (one call per student) use it.

use super::args::Step;
use super::child::Child;
use super::report::StepReport;
use super::say::say;
use super::submission;
use anyhow::{Context as _, Result};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// The children's private folder, removed when grading the student ends, whatever happens (a step
/// killed at its time limit leaves its copy behind; a panic unwinds through here too).
struct WorkDir(PathBuf);

impl Drop for WorkDir {
    fn drop(&mut self) {
        super::interrupt::unregister(&self.0);
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
    // The pid keeps concurrent graders apart and the counter the students one grader grades at
    // once; the clock only guards against a reused pid, so a clock set before 1970 just leaves it out.
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    let work =
        std::env::temp_dir().join(format!("opengl3d-grade-{}-{n}-{nanos}", std::process::id()));
    super::interrupt::create_registered(&work)
        .with_context(|| format!("cannot create folder {}", work.display()))?;
    Ok(WorkDir(work))
}

/// How to grade: the executable the children run, where pictures go, the time limit of a step, and
/// the lesson step the student is at (`--lesson N`: a file it has only begun is checked as far as it
/// is written).
pub struct Grading<'a> {
    pub exe: &'a Path,
    pub pictures: Option<&'a Path>,
    pub timeout: Duration,
    pub lesson: Option<u32>,
    /// How strict (`--level`).
    pub level: super::args::Level,
}

/// Grades `steps` of the shaders in `student` (the project's own files when `None`): one verdict
/// per step, in the order of `steps`. A step that crashes, hangs or cannot start fails with its
/// reason; only a missing private folder is an error.
pub fn grade(g: &Grading, student: Option<&Path>, steps: &[Step]) -> Result<Vec<StepReport>> {
    let work = work_dir()?;
    // All steps at once: each is a separate process with its own deadline.
    let mut children = Vec::new();
    let mut reports = Vec::new();
    for &s in steps {
        // A step with nothing to grade needs no child.
        if let Some(Err(reason)) = student.map(|d| submission::find(d, s)) {
            reports.push(Some(StepReport::not_submitted(s, &reason)));
            continue;
        }
        let mut cmd = Command::new(g.exe);
        if let Some(d) = student {
            cmd.arg("--res").arg(d);
        }
        // The child writes its messages in the grader's language, whether flag or locale chose it.
        cmd.arg("--lang").arg(crate::i18n::current().code());
        cmd.arg("grade-step")
            .arg(s.name())
            .arg("--work")
            .arg(work.0.join(s.name()));
        if let Some(out) = g.pictures {
            cmd.arg("--out").arg(out);
        }
        if let Some(n) = g.lesson {
            cmd.arg("--lesson").arg(n.to_string());
        }
        cmd.arg("--level").arg(g.level.name());
        match Child::spawn(cmd, s) {
            Ok(child) => {
                children.push((reports.len(), child));
                reports.push(None);
            }
            Err(e) => {
                let (exe, error) = (g.exe.display(), e);
                let message = say!("grade.verdict.cannot_start", exe = exe, error = error);
                reports.push(Some(StepReport::failed_with(s, message)))
            }
        }
    }
    for (i, c) in children {
        reports[i] = Some(c.finish(g.timeout));
    }
    drop(work);
    // Every report says how strictly it was graded, those that needed no child too.
    Ok(reports
        .into_iter()
        .flatten()
        .map(|r| StepReport {
            level: g.level,
            ..r
        })
        .collect())
}
