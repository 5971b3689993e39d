//! What the grader reports: one verdict per step, as the child prints it and as the grader shows
//! it (text or JSON).

use super::args::Step;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// One step's verdict (the child's output; `metrics` stay out of the grader's JSON).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StepReport {
    pub step: String,
    pub file: String,
    pub passed: bool,
    /// False when the student's folder has no usable file for the step (`message` says why).
    pub submitted: bool,
    pub message: String,
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub metrics: BTreeMap<String, f64>,
}

impl StepReport {
    /// A failing verdict for `step` with no measurements.
    pub fn failed(step: Step, message: String) -> StepReport {
        StepReport {
            step: step.name().into(),
            file: step.file().into(),
            passed: false,
            submitted: true,
            message,
            metrics: BTreeMap::new(),
        }
    }

    /// The failing verdict of a step whose file is not in the student's folder, and why.
    pub fn not_submitted(step: Step, reason: &str) -> StepReport {
        StepReport {
            submitted: false,
            ..StepReport::failed(step, format!("not submitted: {reason}"))
        }
    }
}

#[derive(Serialize)]
struct PublicStep<'a> {
    step: &'a str,
    file: &'a str,
    passed: bool,
    submitted: bool,
    message: &'a str,
}

#[derive(Serialize)]
struct PublicReport<'a> {
    passed: bool,
    steps: Vec<PublicStep<'a>>,
}

/// The JSON the grader prints with `--json`: {"passed", "steps": [{"step", "file", "passed",
/// "submitted", "message"}]}.
pub fn to_json(reports: &[StepReport]) -> serde_json::Result<String> {
    serde_json::to_string(&PublicReport {
        passed: reports.iter().all(|r| r.passed),
        steps: reports
            .iter()
            .map(|r| PublicStep {
                step: &r.step,
                file: &r.file,
                passed: r.passed,
                submitted: r.submitted,
                message: &r.message,
            })
            .collect(),
    })
}

/// Prints one PASS/FAIL line per step and a summary on stdout.
pub fn print_text(reports: &[StepReport], pictures: Option<&Path>) {
    for r in reports {
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
    if let Some(out) = pictures {
        println!("pictures in {}", out.display());
    }
}

/// Prints each step's measurements on stderr (`--verbose`).
pub fn print_metrics(reports: &[StepReport]) {
    for r in reports {
        for (k, v) in &r.metrics {
            eprintln!("{} {k}: {v}", r.step);
        }
    }
}
