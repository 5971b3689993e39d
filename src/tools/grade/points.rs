//! `grade --points`: what each graded step is worth, for the teacher's records (`--json`, and
//! `--class`'s results.csv and junit.xml) and for GitHub Classroom's autograding tests. A step
//! earns its points when it passes and none otherwise.

use super::args::Step;
use anyhow::{bail, Result};
use rust_i18n::t;
use std::collections::BTreeMap;

/// The value `--points` takes when given alone (`args.rs` spells it too).
pub const DEFAULT_SPEC: &str = "default";

/// Points per step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Points(BTreeMap<Step, u32>);

impl Default for Points {
    /// 10 points per lesson step that has the file written (`lesson::shaders_for_step`): the
    /// restore pass takes steps 2–3, down-sampling 4, simple 5, SAO 6–10, the blur 11; 100 in all.
    fn default() -> Points {
        Points(BTreeMap::from([
            (Step::Restore, 20),
            (Step::DownSampling, 10),
            (Step::Simple, 10),
            (Step::Sao, 50),
            (Step::Blur, 10),
        ]))
    }
}

impl Points {
    /// `default`, or `STEP=N` pairs separated by commas (`sao=40,blur=20`); steps not named keep
    /// their default.
    pub fn parse(spec: &str) -> Result<Points> {
        let mut points = Points::default();
        if spec.trim() == DEFAULT_SPEC {
            return Ok(points);
        }
        for part in spec.split(',').map(str::trim) {
            let Some((name, value)) = part.split_once('=') else {
                bail!("{}", t!("points.bad_pair", part = part));
            };
            let (name, value) = (name.trim(), value.trim());
            let Some(step) = Step::ALL.into_iter().find(|s| s.name() == name) else {
                let steps = Step::ALL.map(Step::name).join(", ");
                bail!("{}", t!("points.bad_step", name = name, steps = steps));
            };
            let Ok(n) = value.parse::<u32>() else {
                bail!("{}", t!("points.bad_value", part = part));
            };
            points.0.insert(step, n);
        }
        Ok(points)
    }

    /// What step `step` is worth.
    pub fn of(&self, step: Step) -> u32 {
        self.0.get(&step).copied().unwrap_or(0)
    }

    /// What the step called `name` is worth (0 for a name no step has).
    pub fn of_name(&self, name: &str) -> u32 {
        Step::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .map_or(0, |s| self.of(s))
    }

    /// The `STEP=N,...` text that parses back to these points (what the class templates pass on).
    pub fn spec(&self) -> String {
        Step::ALL
            .iter()
            .map(|s| format!("{}={}", s.name(), self.of(*s)))
            .collect::<Vec<_>>()
            .join(",")
    }

    /// What the step called `name` earned: its points when it passed.
    pub fn earned(&self, name: &str, passed: bool) -> u32 {
        if passed {
            self.of_name(name)
        } else {
            0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_a_hundred_and_pairs_override_it() {
        let p = Points::default();
        let total: u32 = Step::ALL.iter().map(|s| p.of(*s)).sum();
        assert_eq!(total, 100);
        let q = Points::parse("sao=40, blur=20").unwrap();
        assert_eq!((q.of(Step::Sao), q.of(Step::Blur)), (40, 20));
        assert_eq!(q.of(Step::Restore), 20, "unnamed steps keep their default");
        assert_eq!(Points::parse("default").unwrap(), p);
        assert_eq!(Points::parse(&q.spec()).unwrap(), q, "{}", q.spec());
    }

    #[test]
    fn bad_points_are_named() {
        for (spec, part) in [("sao", "sao"), ("nosuch=3", "nosuch"), ("sao=-1", "sao=-1")] {
            let e = Points::parse(spec).unwrap_err().to_string();
            assert!(e.contains(part), "{spec}: {e}");
        }
    }
}
