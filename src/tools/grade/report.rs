//! What the grader reports: one verdict per step (and per sub-step, for a step graded in parts), as
//! the child prints it and as the grader shows it (text or JSON).

use super::args::{Level, Step};
use super::points::Points;
use crate::i18n::Text;
use rust_i18n::t;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// One sub-step's verdict (`points::SAO_PARTS`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PartReport {
    /// Stable id, `step.part` (`sao.smoothing`).
    pub part: String,
    pub passed: bool,
    pub message: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub message_localised: Option<String>,
    /// The erratum of the original course the shader keeps, when that is why the sub-step fails:
    /// its number in appendix A and its title (English).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub erratum: Option<String>,
}

impl PartReport {
    /// What a person reads: the localised message, else the English one.
    pub fn shown_message(&self) -> &str {
        self.message_localised.as_deref().unwrap_or(&self.message)
    }

    /// The sub-step's title in the current language (`grade.part.<id>`).
    pub fn title(&self) -> String {
        part_title(&self.part, &rust_i18n::locale())
    }
}

/// The title of sub-step `id` in `locale` (the id itself when no title is written).
pub fn part_title(id: &str, locale: &str) -> String {
    let key = format!("grade.part.{id}");
    let title = t!(key.as_str(), locale = locale).into_owned();
    if title == key {
        id.to_string()
    } else {
        title
    }
}

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
    /// The sub-steps' verdicts (SAO); the step passes when all of them pass.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub parts: Vec<PartReport>,
    /// How strictly it was graded (`--level`).
    #[serde(default)]
    pub level: Level,
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
            parts: Vec::new(),
            level: Level::default(),
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

    /// What the step is worth: the sum of its sub-steps' points when it has them.
    pub fn max_points(&self, points: &Points) -> u32 {
        if self.parts.is_empty() {
            points.of_name(&self.step)
        } else {
            self.parts.iter().map(|p| points.of_part(&p.part)).sum()
        }
    }

    /// What the step earned: its points when it passed, or those of each sub-step that passed.
    pub fn earned_points(&self, points: &Points) -> u32 {
        if self.parts.is_empty() {
            points.earned(&self.step, self.passed)
        } else {
            self.parts
                .iter()
                .filter(|p| p.passed)
                .map(|p| points.of_part(&p.part))
                .sum()
        }
    }
}

#[derive(Serialize)]
struct PublicPart<'a> {
    part: &'a str,
    passed: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    points: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_points: Option<u32>,
    message: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    message_localised: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    erratum: Option<&'a str>,
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
    #[serde(skip_serializing_if = "Vec::is_empty")]
    parts: Vec<PublicPart<'a>>,
}

#[derive(Serialize)]
struct PublicReport<'a> {
    passed: bool,
    level: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    points: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_points: Option<u32>,
    steps: Vec<PublicStep<'a>>,
}

/// The JSON the grader prints with `--json`: {"passed", "level", "steps": [{"step", "file",
/// "passed", "submitted", "message"}]}, plus "message_localised" on a step whose message was also
/// written in a language other than English, "parts" [{"part", "passed", "message",
/// "message_localised"?, "erratum"?}] on a step graded in sub-steps, and with `points` "points" and
/// "max_points" in the whole, in each step and in each sub-step (a step's are its sub-steps' sum).
/// The level is the reports' (`--level`).
pub fn to_json(reports: &[StepReport], points: Option<&Points>) -> serde_json::Result<String> {
    let level = reports.first().map(|r| r.level).unwrap_or_default();
    to_json_at(reports, points, level)
}

/// `to_json` with the level given (for an empty list of reports).
pub fn to_json_at(
    reports: &[StepReport],
    points: Option<&Points>,
    level: Level,
) -> serde_json::Result<String> {
    let sum = |f: &dyn Fn(&Points, &StepReport) -> u32| {
        points.map(|p| reports.iter().map(|r| f(p, r)).sum::<u32>())
    };
    serde_json::to_string(&PublicReport {
        passed: reports.iter().all(|r| r.passed),
        level: level.name(),
        points: sum(&|p, r| r.earned_points(p)),
        max_points: sum(&|p, r| r.max_points(p)),
        steps: reports
            .iter()
            .map(|r| PublicStep {
                step: &r.step,
                file: &r.file,
                passed: r.passed,
                submitted: r.submitted,
                message: &r.message,
                message_localised: r.message_localised.as_deref(),
                points: points.map(|p| r.earned_points(p)),
                max_points: points.map(|p| r.max_points(p)),
                parts: r
                    .parts
                    .iter()
                    .map(|part| PublicPart {
                        part: &part.part,
                        passed: part.passed,
                        points: points.map(|p| {
                            if part.passed {
                                p.of_part(&part.part)
                            } else {
                                0
                            }
                        }),
                        max_points: points.map(|p| p.of_part(&part.part)),
                        message: &part.message,
                        message_localised: part.message_localised.as_deref(),
                        erratum: part.erratum.as_deref(),
                    })
                    .collect(),
            })
            .collect(),
    })
}

/// Prints the level, one PASS/FAIL line per step (and one per sub-step under it) and a summary
/// on stdout.
pub fn print_text(reports: &[StepReport], pictures: Option<&Path>) {
    if let Some(r) = reports.first() {
        crate::outln!("{}", t!("grade.level", level = r.level.name()));
    }
    for r in reports {
        let verdict = if r.passed {
            t!("grade.pass")
        } else {
            t!("grade.fail")
        };
        if r.parts.is_empty() {
            crate::outln!("{verdict} {}: {}", r.file, r.shown_message());
            continue;
        }
        crate::outln!("{verdict} {}:", r.file);
        for p in &r.parts {
            let verdict = if p.passed {
                t!("grade.pass")
            } else {
                t!("grade.fail")
            };
            crate::outln!("  {verdict} {}: {}", p.title(), p.shown_message());
        }
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
