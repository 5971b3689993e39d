//! The grader: `opengl3d grade` renders fixed test inputs with a student's shaders and checks each of
//! the lesson's four passes, one verdict per step.
//!
//! | step | file | checked against |
//! |---|---|---|
//! | `restore` | `sao_restore_depth.frag` | the exact (f64) inverse of the projection of the nearest of each 2×2 block, within float precision |
//! | `down-sampling` | `sao_down_sampling.frag` | the exact min of each 2×2 block, level by level |
//! | `sao` | `sao.frag` | the project's `Res/sao.frag` on the same mip chain: mean, 8×8 block RMSE, open surfaces ≈ 0, creases occluded, far samples read from mip levels 1–3 |
//! | `blur` | `sao_blur.frag` | the project's `Res/sao_blur.frag` on the same input: RMSE, edges kept, flat surfaces smoothed, mean kept |
//!
//! Each step is graded on its own, from the project's inputs (a broken restore pass does not fail the
//! SAO step). A step whose file is missing from the student's folder is graded on the project's file
//! and says so. `--lesson N` grades the files lesson step N needs (the same as `opengl3d lesson N`:
//! steps 1–3 the restore pass, 4–5 also down-sampling, 6–10 also SAO, 11–12 all four); `--step`
//! picks steps by name.
//!
//! Every step runs in a child process (`opengl3d grade-step STEP`, hidden) with a time limit, so a
//! shader that never ends, or a driver crash, fails that step and grading goes on. The child prints
//! one JSON object on stdout.

pub mod picture;
pub mod scene;
pub mod step;

use crate::res::{project_res_dir, ResDirs};
use anyhow::{bail, Context as _, Result};
use clap::{Args, ValueEnum};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The lesson's four passes, in pipeline order.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, ValueEnum)]
pub enum Step {
    Restore,
    DownSampling,
    Sao,
    Blur,
}

impl Step {
    pub const ALL: [Step; 4] = [Step::Restore, Step::DownSampling, Step::Sao, Step::Blur];

    /// The shader file the step grades.
    pub fn file(self) -> &'static str {
        match self {
            Step::Restore => "sao_restore_depth.frag",
            Step::DownSampling => "sao_down_sampling.frag",
            Step::Sao => "sao.frag",
            Step::Blur => "sao_blur.frag",
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Step::Restore => "restore",
            Step::DownSampling => "down-sampling",
            Step::Sao => "sao",
            Step::Blur => "blur",
        }
    }
    fn from_file(file: &str) -> Option<Step> {
        Step::ALL.into_iter().find(|s| s.file() == file)
    }
}

#[derive(Args, Debug, Clone)]
pub struct GradeArgs {
    /// Grade the shaders lesson step N needs (1-3: restore; 4-5: + down-sampling; 6-10: + SAO;
    /// 11-12: all four).
    #[arg(long, value_name = "N")]
    pub lesson: Option<u32>,
    /// Grade only these steps (comma-separated or repeated); overrides --lesson.
    #[arg(long, value_enum, value_delimiter = ',')]
    pub step: Vec<Step>,
    /// Print the verdicts as JSON: {"passed": bool, "steps": [{"step", "file", "passed", "message"}]}.
    #[arg(long)]
    pub json: bool,
    /// Folder for expected/actual/difference PNGs of each step.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Seconds each step may take before it counts as hung (an endless loop in a shader).
    #[arg(long, default_value_t = 20.0, value_name = "SECONDS")]
    pub timeout: f64,
    /// Also print each step's measurements on stderr.
    #[arg(long)]
    pub verbose: bool,
}

/// The hidden child command: grades one step and prints its report as JSON.
#[derive(Args, Debug, Clone)]
pub struct GradeStepArgs {
    #[arg(value_enum)]
    pub step: Step,
    /// Private working folder (the graded file is copied there).
    #[arg(long)]
    pub work: PathBuf,
    /// Folder for the step's PNGs.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// One step's verdict (the child's output; `metrics` stay out of the grader's JSON).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StepReport {
    pub step: String,
    pub file: String,
    pub passed: bool,
    pub message: String,
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub metrics: BTreeMap<String, f64>,
}

#[derive(Serialize)]
struct PublicStep<'a> {
    step: &'a str,
    file: &'a str,
    passed: bool,
    message: &'a str,
}

#[derive(Serialize)]
struct PublicReport<'a> {
    passed: bool,
    steps: Vec<PublicStep<'a>>,
}

/// The steps `args` select, in pipeline order.
pub fn selected_steps(args: &GradeArgs) -> Result<Vec<Step>> {
    let mut steps: Vec<Step> = if !args.step.is_empty() {
        args.step.clone()
    } else if let Some(n) = args.lesson {
        if !(1..=crate::tools::lesson::STEPS).contains(&n) {
            bail!(
                "there is no lesson step {n}: steps are 1 to {}",
                crate::tools::lesson::STEPS
            );
        }
        crate::tools::lesson::shaders_for_step(n)
            .iter()
            .filter_map(|f| Step::from_file(f))
            .collect()
    } else {
        Step::ALL.to_vec()
    };
    steps.sort();
    steps.dedup();
    Ok(steps)
}

/// A running child: one step.
struct Child {
    step: Step,
    child: std::process::Child,
    started: Instant,
    stdout: Option<std::thread::JoinHandle<String>>,
    stderr: Option<std::thread::JoinHandle<String>>,
}

fn drain<R: Read + Send + 'static>(r: Option<R>) -> Option<std::thread::JoinHandle<String>> {
    r.map(|mut r| {
        std::thread::spawn(move || {
            let mut buf = Vec::new();
            let _ = r.read_to_end(&mut buf);
            String::from_utf8_lossy(&buf).into_owned()
        })
    })
}

fn last_line(s: &str) -> String {
    s.lines()
        .rev()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or("")
        .to_string()
}

/// Waits for `c` until its deadline, killing it then; turns what it printed into a report.
fn finish(mut c: Child, timeout: Duration) -> StepReport {
    let report = |passed: bool, message: String| StepReport {
        step: c.step.name().to_string(),
        file: c.step.file().to_string(),
        passed,
        message,
        metrics: BTreeMap::new(),
    };
    let status = loop {
        match c.child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if c.started.elapsed() >= timeout => {
                let _ = c.child.kill();
                let _ = c.child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(10)),
            Err(e) => {
                return report(
                    false,
                    format!("grader error: cannot wait for the step: {e}"),
                )
            }
        }
    };
    let out = c
        .stdout
        .take()
        .and_then(|h| h.join().ok())
        .unwrap_or_default();
    let err = c
        .stderr
        .take()
        .and_then(|h| h.join().ok())
        .unwrap_or_default();
    let Some(status) = status else {
        return report(
            false,
            format!(
                "timed out after {} s: the shader never finishes (an endless loop?); grading went on",
                timeout.as_secs_f64()
            ),
        );
    };
    if let Some(r) = out
        .lines()
        .rev()
        .find(|l| l.trim_start().starts_with('{'))
        .and_then(|l| serde_json::from_str::<StepReport>(l).ok())
    {
        return r;
    }
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(sig) = status.signal() {
            return report(
                false,
                format!(
                    "the renderer crashed (signal {sig}) while running this shader{}",
                    match last_line(&err) {
                        l if l.is_empty() => String::new(),
                        l => format!(": {l}"),
                    }
                ),
            );
        }
    }
    report(
        false,
        format!(
            "grader error: the step's process ended ({status}) without a verdict{}",
            match last_line(&err) {
                l if l.is_empty() => String::new(),
                l => format!(": {l}"),
            }
        ),
    )
}

/// Grades the shaders found through `res`; returns the process exit code (0: every step passed).
pub fn run(_res: &ResDirs, student: Option<&Path>, args: &GradeArgs) -> Result<i32> {
    let steps = selected_steps(args)?;
    if let Some(dir) = student {
        if !dir.is_dir() {
            bail!("--res {}: not a folder", dir.display());
        }
    }
    if !(args.timeout > 0.0 && args.timeout.is_finite()) {
        bail!("--timeout {}: give a number of seconds > 0", args.timeout);
    }
    if let Some(out) = &args.out {
        std::fs::create_dir_all(out)
            .with_context(|| format!("cannot create folder {}", out.display()))?;
    }
    let exe = std::env::current_exe().context("cannot find the opengl3d executable")?;
    let work = std::env::temp_dir().join(format!(
        "opengl3d-grade-{}-{}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos())
            .unwrap_or(0)
    ));
    std::fs::create_dir_all(&work)
        .with_context(|| format!("cannot create folder {}", work.display()))?;
    if !args.json {
        match student {
            Some(d) => println!("grading {} ({} step(s))", d.display(), steps.len()),
            None => println!(
                "grading the project's own {} (no --res DIR given)",
                project_res_dir().display()
            ),
        }
    }
    // All steps at once: each is a separate process with its own deadline.
    let mut children = Vec::new();
    let mut reports = Vec::new();
    for &s in &steps {
        let mut cmd = Command::new(&exe);
        if let Some(d) = student {
            cmd.arg("--res").arg(d);
        }
        cmd.arg("grade-step")
            .arg(s.name())
            .arg("--work")
            .arg(work.join(s.name()));
        if let Some(out) = &args.out {
            cmd.arg("--out").arg(out);
        }
        cmd.stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        match cmd.spawn() {
            Ok(mut child) => {
                let stdout = drain(child.stdout.take());
                let stderr = drain(child.stderr.take());
                children.push((
                    reports.len(),
                    Child {
                        step: s,
                        child,
                        started: Instant::now(),
                        stdout,
                        stderr,
                    },
                ));
                reports.push(None);
            }
            Err(e) => reports.push(Some(StepReport {
                step: s.name().into(),
                file: s.file().into(),
                passed: false,
                message: format!("grader error: cannot start {}: {e}", exe.display()),
                metrics: BTreeMap::new(),
            })),
        }
    }
    let timeout = Duration::from_secs_f64(args.timeout);
    for (i, c) in children {
        reports[i] = Some(finish(c, timeout));
    }
    let _ = std::fs::remove_dir_all(&work);
    let reports: Vec<StepReport> = reports.into_iter().flatten().collect();
    let passed = reports.iter().all(|r| r.passed);
    if args.verbose {
        for r in &reports {
            for (k, v) in &r.metrics {
                eprintln!("{} {k}: {v}", r.step);
            }
        }
    }
    if args.json {
        let public = PublicReport {
            passed,
            steps: reports
                .iter()
                .map(|r| PublicStep {
                    step: &r.step,
                    file: &r.file,
                    passed: r.passed,
                    message: &r.message,
                })
                .collect(),
        };
        println!("{}", serde_json::to_string(&public)?);
    } else {
        for r in &reports {
            println!(
                "{} {}: {}",
                if r.passed { "PASS" } else { "FAIL" },
                r.file,
                r.message
            );
        }
        let failed = reports.iter().filter(|r| !r.passed).count();
        if failed == 0 {
            println!("all {} step(s) passed", reports.len());
        } else {
            println!("{failed} of {} step(s) failed", reports.len());
        }
        if let Some(out) = &args.out {
            println!("pictures in {}", out.display());
        }
    }
    Ok(if passed { 0 } else { 1 })
}

/// The child: grades one step and prints its report as one JSON line on stdout.
pub fn run_step(student: Option<&Path>, args: &GradeStepArgs) -> Result<()> {
    let project = project_res_dir();
    let step = args.step;
    let from_student = student.map(|d| d.join(step.file())).filter(|p| p.is_file());
    let using_project = student.is_some() && from_student.is_none();
    let file = from_student
        .clone()
        .unwrap_or_else(|| project.join(step.file()));
    let mut report = StepReport {
        step: step.name().into(),
        file: step.file().into(),
        passed: false,
        message: String::new(),
        metrics: BTreeMap::new(),
    };
    match step::stage(&file, &args.work) {
        Err(e) => report.message = format!("cannot read {}: {e}", file.display()),
        Ok(_) => {
            let shown = file.parent().unwrap_or(Path::new("")).to_path_buf();
            let subject = step::Subject {
                work_dir: &args.work,
                shown_dir: &shown,
            };
            let v = step::grade(step, &subject, &project);
            report.passed = v.passed;
            report.message = v.message;
            report.metrics = v.metrics;
            if let Some(out) = &args.out {
                if !v.panels.is_empty() {
                    if let Err(e) = picture::write(out, step.name(), &v.panels) {
                        eprintln!("warning: {e:#}");
                    }
                }
            }
        }
    }
    if using_project {
        report.message = format!("(using the project's file) {}", report.message);
    }
    let _ = std::fs::remove_dir_all(&args.work);
    println!("{}", serde_json::to_string(&report)?);
    Ok(())
}
