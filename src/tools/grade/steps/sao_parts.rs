//! The SAO step's sub-steps (`points::SAO_PARTS`): each check of `sao` belongs to the lesson that
//! teaches what it measures, and each sub-step gets its own verdict. A mistake that leaves nothing
//! to measure (NaN everywhere, a flipped normal) fails its own sub-step and every one not yet
//! decided, saying so; a shader that keeps an erratum of the original course has it named in the
//! sub-step it fails.

use crate::i18n::Text;
use crate::tools::grade::picture::Panel;
use crate::tools::grade::rig::{PartVerdict, Verdict};
use crate::tools::grade::say::say;
use std::collections::BTreeMap;

pub const NORMAL: &str = "sao.normal";
pub const SAMPLING: &str = "sao.sampling";
pub const OCCLUSION: &str = "sao.occlusion";
pub const SMOOTHING: &str = "sao.smoothing";
pub const VIEW: &str = "sao.view";

/// Appendix A's title of erratum `n` in `locale` ("#20: …"), for the errata a shader may keep.
pub fn erratum_name(n: u32, locale: &str) -> String {
    let key = format!("grade.erratum.e{n}");
    let title = rust_i18n::t!(key.as_str(), locale = locale).into_owned();
    rust_i18n::t!("grade.erratum.name", locale = locale, n = n, title = title).into_owned()
}

/// A sub-step's failure: the message, and the erratum it keeps.
struct Failure {
    message: Text,
    erratum: Option<u32>,
}

/// The sub-steps graded (in the lessons' order) and the first failure found in each.
pub struct Parts {
    ids: Vec<&'static str>,
    failures: BTreeMap<&'static str, Failure>,
    /// The sub-step whose mistake leaves the rest unmeasurable.
    broken_by: Option<&'static str>,
}

impl Parts {
    /// All five sub-steps, or without the smoothing before the lesson that teaches it.
    pub fn new(smoothing_taught: bool) -> Parts {
        let ids = crate::tools::grade::points::SAO_PARTS
            .iter()
            .map(|p| p.0)
            .filter(|id| smoothing_taught || *id != SMOOTHING)
            .collect();
        Parts {
            ids,
            failures: BTreeMap::new(),
            broken_by: None,
        }
    }

    /// Records that `id` fails with `message` (its first failure is kept).
    pub fn fail(&mut self, id: &'static str, message: Text) {
        self.fail_keeping(id, message, None);
    }

    /// Records that `id` fails with `message` because the shader keeps the course's erratum
    /// `erratum`, named after the message.
    pub fn fail_keeping(&mut self, id: &'static str, message: Text, erratum: Option<u32>) {
        if !self.ids.contains(&id) || self.failures.contains_key(id) {
            return;
        }
        let message = match erratum {
            None => message,
            Some(n) => Text::new(|l| {
                let name = erratum_name(n, l);
                let m = if l == "en" {
                    &message.en
                } else {
                    message.localised.as_ref().unwrap_or(&message.en)
                };
                rust_i18n::t!(
                    "grade.verdict.keeps_erratum",
                    locale = l,
                    message = m,
                    erratum = name
                )
                .into_owned()
            }),
        };
        self.failures.insert(id, Failure { message, erratum });
    }

    /// Records that `id` fails with `message` and that nothing after it can be measured: every
    /// sub-step not yet failed fails, naming `id`.
    pub fn break_all(&mut self, id: &'static str, message: Text) {
        self.fail(id, message);
        self.broken_by.get_or_insert(id);
    }

    /// Whether a mistake already left the rest unmeasurable.
    pub fn broken(&self) -> bool {
        self.broken_by.is_some()
    }

    /// The verdict: each sub-step's, and the step's (passing when all pass, with `pass_message`;
    /// failing with the failing sub-steps' messages, each after its title).
    pub fn verdict(
        mut self,
        pass_message: Text,
        metrics: BTreeMap<String, f64>,
        panels: Vec<Panel>,
    ) -> Verdict {
        if let Some(first) = self.broken_by {
            for id in self.ids.clone() {
                if !self.failures.contains_key(id) {
                    let message = say!(
                        l => "grade.verdict.part_unreadable",
                        part = crate::tools::grade::report::part_title(first, l)
                    );
                    self.failures.insert(
                        id,
                        Failure {
                            message,
                            erratum: None,
                        },
                    );
                }
            }
        }
        let mut parts = Vec::new();
        for id in &self.ids {
            parts.push(match self.failures.remove(id) {
                Some(f) => PartVerdict {
                    id,
                    passed: false,
                    message: f.message,
                    erratum: f.erratum,
                },
                None => PartVerdict {
                    id,
                    passed: true,
                    message: if *id == VIEW {
                        pass_message.clone()
                    } else {
                        say!("grade.verdict.part_pass")
                    },
                    erratum: None,
                },
            });
        }
        let failing: Vec<&PartVerdict> = parts.iter().filter(|p| !p.passed).collect();
        let passed = failing.is_empty();
        let message = if passed {
            pass_message
        } else {
            let (failed, count) = (failing.len(), parts.len());
            Text::new(|l| {
                let list = failing
                    .iter()
                    .map(|p| {
                        let m = if l == "en" {
                            &p.message.en
                        } else {
                            p.message.localised.as_ref().unwrap_or(&p.message.en)
                        };
                        let title = crate::tools::grade::report::part_title(p.id, l);
                        rust_i18n::t!(
                            "grade.verdict.part_line",
                            locale = l,
                            part = title,
                            message = m
                        )
                        .into_owned()
                    })
                    .collect::<Vec<_>>()
                    .join("; ");
                rust_i18n::t!(
                    "grade.verdict.sao_parts_failed",
                    locale = l,
                    failed = failed,
                    count = count,
                    list = list
                )
                .into_owned()
            })
        };
        Verdict {
            passed,
            message,
            metrics,
            panels,
            parts,
        }
    }
}
