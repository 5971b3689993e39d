//! What the grader reports: one verdict per step, as the child prints it and as the grader shows
//! it (text or JSON).

use super::args::Step;
use super::points::Points;
use crate::i18n::Text;
use rust_i18n::t;
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
    /// `message` in the chosen language when that is not English (`--lang`, or the locale).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub message_localised: Option<String>,
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
            message_localised: None,
            metrics: BTreeMap::new(),
        }
    }

    /// A failing verdict for `step` with a message in English and the chosen language.
    pub fn failed_with(step: Step, message: Text) -> StepReport {
        StepReport {
            message_localised: message.localised,
            ..StepReport::failed(step, message.en)
        }
    }

    /// The failing verdict of a step whose file is not in the student's folder, and why.
    pub fn not_submitted(step: Step, reason: &Text) -> StepReport {
        let said = |locale: &str, reason: &str| {
            t!("grade.not_submitted", locale = locale, reason = reason).into_owned()
        };
        StepReport {
            submitted: false,
            message_localised: reason
                .localised
                .as_deref()
                .map(|r| said(crate::i18n::current().code(), r)),
            ..StepReport::failed(step, said("en", &reason.en))
        }
    }

    /// What a person reads: the localised message, else the English one.
    pub fn shown_message(&self) -> &str {
        self.message_localised.as_deref().unwrap_or(&self.message)
    }
}

#[derive(Serialize)]
struct PublicStep<'a> {
    step: &'a str,
    file: &'a str,
    passed: bool,
    submitted: bool,
    message: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    message_localised: Option<&'a str>,
    /// With `--points`: what the step earned and what it is worth.
    #[serde(skip_serializing_if = "Option::is_none")]
    points: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_points: Option<u32>,
}

#[derive(Serialize)]
struct PublicReport<'a> {
    passed: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    points: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_points: Option<u32>,
    steps: Vec<PublicStep<'a>>,
}

/// The JSON the grader prints with `--json`: {"passed", "steps": [{"step", "file", "passed",
/// "submitted", "message"}]}, plus "message_localised" on a step whose message was also written in
/// a language other than English, and with `points` "points" and "max_points" in the whole and in
/// each step.
pub fn to_json(reports: &[StepReport], points: Option<&Points>) -> serde_json::Result<String> {
    let sum = |f: &dyn Fn(&Points, &StepReport) -> u32| {
        points.map(|p| reports.iter().map(|r| f(p, r)).sum::<u32>())
    };
    serde_json::to_string(&PublicReport {
        passed: reports.iter().all(|r| r.passed),
        points: sum(&|p, r| p.earned(&r.step, r.passed)),
        max_points: sum(&|p, r| p.of_name(&r.step)),
        steps: reports
            .iter()
            .map(|r| PublicStep {
                step: &r.step,
                file: &r.file,
                passed: r.passed,
                submitted: r.submitted,
                message: &r.message,
                message_localised: r.message_localised.as_deref(),
                points: points.map(|p| p.earned(&r.step, r.passed)),
                max_points: points.map(|p| p.of_name(&r.step)),
            })
            .collect(),
    })
}

/// Prints one PASS/FAIL line per step and a summary on stdout.
pub fn print_text(reports: &[StepReport], pictures: Option<&Path>) {
    for r in reports {
        let verdict = if r.passed {
            t!("grade.pass")
        } else {
            t!("grade.fail")
        };
        crate::outln!("{verdict} {}: {}", r.file, r.shown_message());
    }
    let failed = reports.iter().filter(|r| !r.passed).count();
    let count = reports.len();
    if failed == 0 {
        crate::outln!("{}", t!("grade.all_passed", count = count));
    } else {
        crate::outln!(
            "{}",
            t!("grade.some_failed", failed = failed, count = count)
        );
    }
    if let Some(out) = pictures {
        crate::outln!("{}", t!("grade.pictures", dir = out.display()));
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
