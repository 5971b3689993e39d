//! `opengl3d grade --mutation-score`: how sensitive the grader is. Every mutant of the project's
//! lesson shaders (`mutate`) is graded exactly as a student's file is (`grade-step` in a child with
//! its limits), and the same child renders the probe (`mutation_probe`): a mutant whose probe
//! output differs from the project's beyond the step's tolerance is observable, and the grader
//! ought to fail it. The score of a step is the fraction of its observable mutants the grader
//! fails; mutants with no observable difference, and those that do not compile, are counted apart.

use super::args::{GradeArgs, Step};
use super::child::Child;
use super::mutate::{mutants, Mutant};
use super::report::StepReport;
use crate::res::project_res_dir;
use anyhow::{anyhow, bail, Context as _, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// The score each step must reach.
pub const TARGET: f64 = 0.95;

/// Metric names the child adds with `--probe`.
pub const PROBE_METRIC: &str = "mutation_probe";
pub const PROBE_BUILDS_METRIC: &str = "mutation_probe_builds";

/// What became of one mutant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    /// Observable, and the grader fails it.
    Killed,
    /// Observable, and the grader passes it.
    Survived,
    /// Ran past the time limit (a loop a mutation made endless): failed by the grader's timeout.
    TimedOut,
    /// No observable difference on the probe render.
    Equivalent,
    /// Does not compile or link.
    DoesNotBuild,
    /// The grader itself failed (no verdict, no probe): neither observable nor equivalent.
    GraderError,
}

#[derive(Clone, Debug, Serialize)]
pub struct MutantResult {
    pub id: String,
    pub description: String,
    pub outcome: Outcome,
    /// Probe difference in units of the step's tolerance (observable above 1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probe: Option<f64>,
    /// The grader's message.
    pub message: String,
}

#[derive(Clone, Debug, Serialize)]
pub struct StepScore {
    pub step: String,
    pub file: String,
    pub mutants: usize,
    pub observable: usize,
    pub killed: usize,
    pub equivalent: usize,
    pub does_not_build: usize,
    pub timed_out: usize,
    pub grader_errors: usize,
    /// killed (timeouts included) / observable; 1 when nothing is observable.
    pub score: f64,
    pub results: Vec<MutantResult>,
}

/// Classifies what the child reported for one mutant.
fn outcome(r: &StepReport) -> (Outcome, Option<f64>) {
    if r.metrics.get(PROBE_BUILDS_METRIC) == Some(&0.0) {
        return (Outcome::DoesNotBuild, None);
    }
    match r.metrics.get(PROBE_METRIC) {
        Some(&d) if d > 1.0 && r.passed => (Outcome::Survived, Some(d)),
        Some(&d) if d > 1.0 => (Outcome::Killed, Some(d)),
        Some(&d) => (Outcome::Equivalent, Some(d)),
        None if r.message.starts_with("timed out") => (Outcome::TimedOut, None),
        None => (Outcome::GraderError, None),
    }
}

fn score(step: Step, results: Vec<MutantResult>) -> StepScore {
    let count = |o: Outcome| results.iter().filter(|r| r.outcome == o).count();
    let (killed, survived, timed_out) = (
        count(Outcome::Killed),
        count(Outcome::Survived),
        count(Outcome::TimedOut),
    );
    let observable = killed + survived + timed_out;
    StepScore {
        step: step.name().into(),
        file: step.file().into(),
        mutants: results.len(),
        observable,
        killed: killed + timed_out,
        equivalent: count(Outcome::Equivalent),
        does_not_build: count(Outcome::DoesNotBuild),
        timed_out,
        grader_errors: count(Outcome::GraderError),
        score: if observable == 0 {
            1.0
        } else {
            (killed + timed_out) as f64 / observable as f64
        },
        results,
    }
}

/// The folder the mutants are written to, removed whatever happens.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        if let Err(e) = std::fs::remove_dir_all(&self.0) {
            if e.kind() != std::io::ErrorKind::NotFound {
                eprintln!("warning: cannot remove {}: {e}", self.0.display());
            }
        }
    }
}

fn scratch() -> Result<Scratch> {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    let dir = std::env::temp_dir().join(format!("opengl3d-mutants-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("cannot create folder {}", dir.display()))?;
    Ok(Scratch(dir))
}

/// `n` mutants spread evenly over `all` (every one when `n` is at least their number).
pub fn sample(all: Vec<Mutant>, n: Option<usize>) -> Vec<Mutant> {
    match n {
        Some(n) if n < all.len() => {
            let len = all.len();
            // The middle of each of n equal stretches: fixed, and not biased to the file's start.
            let picks: Vec<usize> = (0..n).map(|k| (2 * k + 1) * len / (2 * n)).collect();
            all.into_iter()
                .enumerate()
                .filter(|(i, _)| picks.contains(i))
                .map(|(_, m)| m)
                .collect()
        }
        _ => all,
    }
}

/// Grades one mutant in a child and classifies it.
fn run_one(
    exe: &Path,
    root: &Path,
    step: Step,
    m: &Mutant,
    timeout: Duration,
) -> Result<MutantResult> {
    let id = format!("{}-{:03}", step.name(), m.index);
    let dir = root.join(&id);
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("cannot create folder {}", dir.display()))?;
    let file = dir.join(step.file());
    std::fs::write(&file, &m.source).with_context(|| format!("cannot write {}", file.display()))?;
    let mut cmd = Command::new(exe);
    cmd.arg("--res")
        .arg(&dir)
        .arg("--lang")
        .arg("en")
        .arg("grade-step")
        .arg(step.name())
        .arg("--work")
        .arg(root.join(format!("{id}-work")))
        .arg("--probe");
    let child =
        Child::spawn(cmd, step).with_context(|| format!("cannot start {}", exe.display()))?;
    let report = child.finish(timeout);
    let (outcome, probe) = outcome(&report);
    // The mutant's folder is not needed any more; the scratch folder goes at the end anyway.
    let _ = std::fs::remove_dir_all(&dir);
    Ok(MutantResult {
        id,
        description: m.description.clone(),
        outcome,
        probe,
        message: report.message,
    })
}

fn progress_bar(total: usize) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
    // The template is a constant: were it ever rejected, the default style still shows progress.
    if let Ok(style) =
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} mutants {msg}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// Scores `steps`; returns the exit code (0: every step reaches `TARGET`).
pub fn run(exe: &Path, steps: &[Step], args: &GradeArgs, timeout: Duration) -> Result<i32> {
    let jobs = match args.jobs {
        Some(0) => bail!("--jobs 0: give at least 1"),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    if args.mutation_sample == Some(0) {
        bail!("--mutation-sample 0: give at least 1 (a score of no mutants says nothing)");
    }
    let project = project_res_dir();
    let mut work: Vec<(Step, Mutant)> = Vec::new();
    for &step in steps {
        let path = project.join(step.file());
        let src = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        work.extend(
            sample(mutants(&src), args.mutation_sample)
                .into_iter()
                .map(|m| (step, m)),
        );
    }
    let root = scratch()?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| anyhow!("cannot start {jobs} threads: {e}"))?;
    if !args.json {
        let files: Vec<&str> = steps.iter().map(|s| s.file()).collect();
        crate::outln!(
            "{}",
            rust_i18n::t!(
                "mutation.grading",
                count = work.len(),
                files = files.join(", "),
                jobs = jobs
            )
        );
    }
    let bar = progress_bar(work.len());
    let start = Instant::now();
    let results: Vec<Result<(Step, MutantResult)>> = pool.install(|| {
        work.par_iter()
            .map(|(step, m)| {
                let r = run_one(exe, &root.0, *step, m, timeout).map(|r| (*step, r));
                bar.inc(1);
                r
            })
            .collect()
    });
    bar.finish_and_clear();
    let mut per_step: Vec<(Step, Vec<MutantResult>)> = steps.iter().map(|s| (*s, vec![])).collect();
    for r in results {
        let (step, r) = r?;
        if let Some((_, v)) = per_step.iter_mut().find(|(s, _)| *s == step) {
            v.push(r);
        }
    }
    let scores: Vec<StepScore> = per_step.into_iter().map(|(s, r)| score(s, r)).collect();
    let passed = scores
        .iter()
        .all(|s| s.score >= TARGET && s.grader_errors == 0);
    if args.json {
        let v = serde_json::json!({
            "passed": passed,
            "target": TARGET,
            "seconds": start.elapsed().as_secs_f64(),
            "steps": scores,
        });
        crate::outln!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        print_text(&scores, start.elapsed().as_secs_f64());
    }
    Ok(if passed { 0 } else { 1 })
}

fn print_text(scores: &[StepScore], seconds: f64) {
    crate::outln!(
        "{:<14} {:>7} {:>10} {:>6} {:>10} {:>11} {:>8}",
        "step",
        "mutants",
        "observable",
        "killed",
        "equivalent",
        "not-compile",
        "score"
    );
    for s in scores {
        crate::outln!(
            "{:<14} {:>7} {:>10} {:>6} {:>10} {:>11} {:>7.1}%{}",
            s.step,
            s.mutants,
            s.observable,
            s.killed,
            s.equivalent,
            s.does_not_build,
            100.0 * s.score,
            if s.score >= TARGET {
                ""
            } else {
                "  (below 95%)"
            }
        );
    }
    for s in scores {
        for r in s.results.iter().filter(|r| {
            matches!(
                r.outcome,
                Outcome::Survived | Outcome::GraderError | Outcome::TimedOut
            )
        }) {
            let what = match r.outcome {
                Outcome::Survived => "survived",
                Outcome::TimedOut => "timed out",
                _ => "grader error",
            };
            let probe = r
                .probe
                .map_or(String::new(), |d| format!(" (probe {d:.2}× tolerance)"));
            crate::outln!("  {what}: {} {}{probe}: {}", r.id, r.description, r.message);
        }
    }
    crate::outln!("{seconds:.1} s");
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(passed: bool, message: &str, metrics: &[(&str, f64)]) -> StepReport {
        let mut r = StepReport::failed(Step::Sao, message.into());
        r.passed = passed;
        r.metrics = metrics.iter().map(|(k, v)| (k.to_string(), *v)).collect();
        r
    }

    #[test]
    fn outcomes_follow_the_probe_and_the_verdict() {
        let o = |r: &StepReport| outcome(r).0;
        assert_eq!(
            o(&report(false, "x", &[(PROBE_METRIC, 3.0)])),
            Outcome::Killed
        );
        assert_eq!(
            o(&report(true, "x", &[(PROBE_METRIC, 3.0)])),
            Outcome::Survived
        );
        assert_eq!(
            o(&report(true, "x", &[(PROBE_METRIC, 0.5)])),
            Outcome::Equivalent
        );
        assert_eq!(
            o(&report(false, "x", &[(PROBE_METRIC, 1.0)])),
            Outcome::Equivalent
        );
        assert_eq!(
            o(&report(
                false,
                "does not compile",
                &[(PROBE_BUILDS_METRIC, 0.0)]
            )),
            Outcome::DoesNotBuild
        );
        assert_eq!(
            o(&report(false, "timed out after 20 s", &[])),
            Outcome::TimedOut
        );
        assert_eq!(
            o(&report(false, "grader error: x", &[])),
            Outcome::GraderError
        );
    }

    #[test]
    fn the_score_counts_only_observable_mutants() {
        let r = |o| MutantResult {
            id: String::new(),
            description: String::new(),
            outcome: o,
            probe: None,
            message: String::new(),
        };
        let s = score(
            Step::Blur,
            vec![
                r(Outcome::Killed),
                r(Outcome::Killed),
                r(Outcome::TimedOut),
                r(Outcome::Survived),
                r(Outcome::Equivalent),
                r(Outcome::DoesNotBuild),
            ],
        );
        assert_eq!((s.mutants, s.observable, s.killed), (6, 4, 3));
        assert_eq!((s.equivalent, s.does_not_build), (1, 1));
        assert!((s.score - 0.75).abs() < 1e-12);
    }

    #[test]
    fn a_sample_is_spread_and_fixed() {
        let all: Vec<Mutant> = (1..=10)
            .map(|i| Mutant {
                index: i,
                description: String::new(),
                source: String::new(),
            })
            .collect();
        let idx = |n| {
            sample(all.clone(), n)
                .iter()
                .map(|m| m.index)
                .collect::<Vec<_>>()
        };
        assert_eq!(idx(Some(2)), vec![3, 8]);
        assert_eq!(idx(Some(20)).len(), 10);
        assert_eq!(idx(None).len(), 10);
    }
}
