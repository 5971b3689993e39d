//! `opengl3d grade --mutation-score`: how sensitive the grader is. Every mutant of the project's
//! lesson shaders (`mutate`) is graded exactly as a student's file is (`grade-step` in a child with
//! its limits), and the same child renders the probes (`mutation_probe`). A mutant is equivalent
//! only when every value of every probe render matches the shader it was made from to float noise;
//! the others are faults. A step's score is the fraction of its faults the grader fails:
//! killed / (mutants − equivalent − not compiling). Of the faults that pass, those beyond the
//! step's tolerance on the probe are the grader's defects (exit 1); the rest, the "between" count,
//! are faults the step's tolerance accepts.

use super::args::{GradeArgs, Step};
use super::child::Child;
use super::mutate::{mutants, Mutant};
use super::report::StepReport;
use crate::res::project_res_dir;
use anyhow::{anyhow, bail, Context as _, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// Metric names the child adds with `--probe`: the difference in units of the step's tolerance,
/// the difference in units of float noise, and 0 when the shader does not build.
pub const PROBE_METRIC: &str = "mutation_probe";
pub const PROBE_LISTING_METRIC: &str = "mutation_probe_listing";
pub const PROBE_BUILDS_METRIC: &str = "mutation_probe_builds";

/// What became of one mutant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    /// Differs from the listing, and the grader fails it.
    Killed,
    /// Differs beyond the step's tolerance on the probe, and the grader passes it: a defect.
    Survived,
    /// Differs from the listing but within the step's tolerance on the probe, and the grader
    /// passes it: a fault the tolerance accepts.
    Between,
    /// Ran past the time limit (a loop a mutation made endless): failed by the grader's timeout.
    TimedOut,
    /// Matches the listing to float noise on every probe, and the grader passes it.
    Equivalent,
    /// Matches the listing to float noise on every probe, and the grader fails it: either the
    /// grader's own inputs see what no probe does, or it is a false FAIL. Scored as killed.
    KilledUnseen,
    /// Does not compile or link.
    DoesNotBuild,
    /// The grader itself failed (no verdict, no probe).
    GraderError,
}

#[derive(Clone, Debug, Serialize)]
pub struct MutantResult {
    pub id: String,
    pub description: String,
    pub outcome: Outcome,
    /// Probe difference in units of the step's tolerance (beyond it above 1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probe: Option<f64>,
    /// Largest difference from the listing over every probe render, in units of float noise
    /// (equivalent at most 1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probe_listing: Option<f64>,
    /// The grader's message.
    pub message: String,
    /// What the step measured (its report's metrics).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub metrics: BTreeMap<String, f64>,
}

#[derive(Clone, Debug, Serialize)]
pub struct StepScore {
    pub step: String,
    pub file: String,
    pub mutants: usize,
    /// Mutants that compile and differ from the listing: the score's denominator.
    pub faults: usize,
    /// Faults the grader fails (timeouts and `killed-unseen` included).
    pub killed: usize,
    /// Faults beyond the tolerance that the grader passes.
    pub survived: usize,
    /// Faults within the tolerance that the grader passes.
    pub between: usize,
    pub equivalent: usize,
    pub does_not_build: usize,
    pub timed_out: usize,
    pub killed_unseen: usize,
    pub grader_errors: usize,
    /// killed / faults; 1 when there is no fault.
    pub score: f64,
    pub results: Vec<MutantResult>,
}

/// Classifies what the child reported for one mutant.
fn outcome(r: &StepReport) -> (Outcome, Option<f64>, Option<f64>) {
    if r.metrics.get(PROBE_BUILDS_METRIC) == Some(&0.0) {
        return (Outcome::DoesNotBuild, None, None);
    }
    let (d, e) = (
        r.metrics.get(PROBE_METRIC).copied(),
        r.metrics.get(PROBE_LISTING_METRIC).copied(),
    );
    let o = match (d, e) {
        (Some(_), Some(e)) if e <= 1.0 && r.passed => Outcome::Equivalent,
        (Some(_), Some(e)) if e <= 1.0 => Outcome::KilledUnseen,
        (Some(_), Some(_)) if !r.passed => Outcome::Killed,
        (Some(d), Some(_)) if d > 1.0 => Outcome::Survived,
        (Some(_), Some(_)) => Outcome::Between,
        _ if r.message.starts_with("timed out") => Outcome::TimedOut,
        _ => Outcome::GraderError,
    };
    (o, d, e)
}

fn score(step: Step, results: Vec<MutantResult>) -> StepScore {
    let count = |o: Outcome| results.iter().filter(|r| r.outcome == o).count();
    let killed = count(Outcome::Killed) + count(Outcome::TimedOut) + count(Outcome::KilledUnseen);
    let (equivalent, does_not_build) = (count(Outcome::Equivalent), count(Outcome::DoesNotBuild));
    let faults = results.len() - equivalent - does_not_build;
    StepScore {
        step: step.name().into(),
        file: step.file().into(),
        mutants: results.len(),
        faults,
        killed,
        survived: count(Outcome::Survived),
        between: count(Outcome::Between),
        equivalent,
        does_not_build,
        timed_out: count(Outcome::TimedOut),
        killed_unseen: count(Outcome::KilledUnseen),
        grader_errors: count(Outcome::GraderError),
        score: if faults == 0 {
            1.0
        } else {
            killed as f64 / faults as f64
        },
        results,
    }
}

/// The folder the mutants are written to, removed whatever happens.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        super::interrupt::unregister(&self.0);
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
    super::interrupt::create_registered(&dir)
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
    level: super::args::Level,
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
        .arg("--probe")
        .arg("--level")
        .arg(level.name());
    let child =
        Child::spawn(cmd, step).with_context(|| format!("cannot start {}", exe.display()))?;
    let report = child.finish(timeout);
    let (outcome, probe, probe_listing) = outcome(&report);
    // The mutant's folder is not needed any more; the scratch folder goes at the end anyway.
    let _ = std::fs::remove_dir_all(&dir);
    Ok(MutantResult {
        id,
        description: m.description.clone(),
        outcome,
        probe,
        probe_listing,
        message: report.message,
        metrics: report.metrics,
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

/// Scores `steps`; returns the exit code (0: the grader fails every fault beyond the tolerance and
/// never errs).
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
                let r = run_one(exe, &root.0, *step, m, timeout, args.level).map(|r| (*step, r));
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
        .all(|s| s.survived == 0 && s.grader_errors == 0);
    if args.json {
        let v = serde_json::json!({
            "passed": passed,
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
        "{:<14} {:>7} {:>10} {:>11} {:>6} {:>6} {:>8} {:>8} {:>7}",
        "step",
        "mutants",
        "equivalent",
        "not-compile",
        "faults",
        "killed",
        "between",
        "survived",
        "score"
    );
    for s in scores {
        crate::outln!(
            "{:<14} {:>7} {:>10} {:>11} {:>6} {:>6} {:>8} {:>8} {:>6.1}%",
            s.step,
            s.mutants,
            s.equivalent,
            s.does_not_build,
            s.faults,
            s.killed,
            s.between,
            s.survived,
            100.0 * s.score,
        );
    }
    for s in scores {
        for r in s.results.iter().filter(|r| {
            matches!(
                r.outcome,
                Outcome::Survived
                    | Outcome::Between
                    | Outcome::GraderError
                    | Outcome::TimedOut
                    | Outcome::KilledUnseen
            )
        }) {
            let what = match r.outcome {
                Outcome::Survived => "survived",
                Outcome::Between => "between",
                Outcome::TimedOut => "timed out",
                Outcome::KilledUnseen => "killed, no probe sees it",
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
    fn outcomes_follow_the_probes_and_the_verdict() {
        let o = |passed, d: f64, e: f64| {
            outcome(&report(
                passed,
                "x",
                &[(PROBE_METRIC, d), (PROBE_LISTING_METRIC, e)],
            ))
            .0
        };
        // Equivalent only when the output matches the listing to float noise.
        assert_eq!(o(true, 0.0, 0.0), Outcome::Equivalent);
        assert_eq!(o(true, 0.0, 1.0), Outcome::Equivalent);
        assert_eq!(o(false, 0.0, 1.0), Outcome::KilledUnseen);
        // Within the tolerance but not equal: a fault, never an equivalent.
        assert_eq!(o(true, 0.99, 1.5), Outcome::Between);
        assert_eq!(o(false, 0.99, 1.5), Outcome::Killed);
        assert_eq!(o(true, 3.0, 1e9), Outcome::Survived);
        assert_eq!(o(false, 3.0, 1e9), Outcome::Killed);
        let o = |r: &StepReport| outcome(r).0;
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
    fn the_score_is_killed_over_the_faults() {
        let r = |o| MutantResult {
            id: String::new(),
            description: String::new(),
            outcome: o,
            probe: None,
            probe_listing: None,
            message: String::new(),
            metrics: BTreeMap::new(),
        };
        let s = score(
            Step::Blur,
            vec![
                r(Outcome::Killed),
                r(Outcome::KilledUnseen),
                r(Outcome::TimedOut),
                r(Outcome::Survived),
                r(Outcome::Between),
                r(Outcome::Equivalent),
                r(Outcome::DoesNotBuild),
            ],
        );
        assert_eq!((s.mutants, s.faults, s.killed), (7, 5, 3));
        assert_eq!((s.survived, s.between), (1, 1));
        assert_eq!((s.equivalent, s.does_not_build), (1, 1));
        assert!((s.score - 0.6).abs() < 1e-12);
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
