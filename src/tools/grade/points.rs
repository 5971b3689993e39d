//! `grade --points`: what each graded step is worth, for the teacher's records (`--json`, and
//! `--class`'s results.csv and junit.xml) and for the autograding tests. A step earns its points
//! when it passes and none otherwise; a step graded in sub-steps (SAO: one per lesson that writes
//! it, `SAO_PARTS`) earns the points of each sub-step that passes.

use super::args::Step;
use anyhow::{bail, Result};
use rust_i18n::t;
use std::collections::BTreeMap;

/// The value `--points` takes when given alone (`args.rs` spells it too).
pub const DEFAULT_SPEC: &str = "default";

/// The SAO step's sub-steps, named after the lessons that write them (6: view position and
/// normal, 7: spiral sampling and the mip choice, 8: the occlusion term, 9: the 2×2 smoothing,
/// 10: the SAO view), with their default points: 10 per lesson, as for the other steps.
pub const SAO_PARTS: [(&str, u32); 5] = [
    ("sao.normal", 10),
    ("sao.sampling", 10),
    ("sao.occlusion", 10),
    ("sao.smoothing", 10),
    ("sao.view", 10),
];

/// The sub-steps of `step` with their default points (none for a step graded as one).
pub fn parts_of(step: Step) -> &'static [(&'static str, u32)] {
    match step {
        Step::Sao => &SAO_PARTS,
        _ => &[],
    }
}

/// Points per step, and per sub-step for the steps that have them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Points {
    steps: BTreeMap<Step, u32>,
    parts: BTreeMap<&'static str, u32>,
}

impl Default for Points {
    /// 10 points per lesson step that has the file written (`lesson::shaders_for_step`): the
    /// restore pass takes steps 2–3, down-sampling 4, simple 5, SAO 6–10 (10 per sub-step), the
    /// blur 11; 100 in all.
    fn default() -> Points {
        Points {
            steps: BTreeMap::from([
                (Step::Restore, 20),
                (Step::DownSampling, 10),
                (Step::Simple, 10),
                (Step::Blur, 10),
            ]),
            parts: SAO_PARTS.into_iter().collect(),
        }
    }
}

/// `total` spread over `weights` in proportion, rounded so that the shares add up to `total`
/// (largest remainders first, ties to the earlier).
fn spread(total: u32, weights: &[u32]) -> Vec<u32> {
    let sum = weights.iter().map(|w| u64::from(*w)).sum::<u64>();
    if sum == 0 {
        let n = weights.len().max(1) as u32;
        return (0..weights.len() as u32)
            .map(|i| total / n + u32::from(i < total % n))
            .collect();
    }
    let exact: Vec<u64> = weights
        .iter()
        .map(|w| u64::from(total) * u64::from(*w))
        .collect();
    let mut shares: Vec<u32> = exact.iter().map(|e| (e / sum) as u32).collect();
    let left = total - shares.iter().sum::<u32>();
    let mut order: Vec<usize> = (0..weights.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(exact[i] % sum));
    for &i in order.iter().take(left as usize) {
        shares[i] += 1;
    }
    shares
}

impl Points {
    /// `default`, or `NAME=N` pairs separated by commas (`sao=40,blur=20`, `sao.smoothing=5`); a
    /// step with sub-steps given as a whole spreads its points over them in the default
    /// proportions; names not given keep their default.
    pub fn parse(spec: &str) -> Result<Points> {
        let mut points = Points::default();
        if spec.trim() == DEFAULT_SPEC {
            return Ok(points);
        }
        for pair in spec.split(',').map(str::trim) {
            let Some((name, value)) = pair.split_once('=') else {
                bail!("{}", t!("points.bad_pair", part = pair));
            };
            let (name, value) = (name.trim(), value.trim());
            let Ok(n) = value.parse::<u32>() else {
                bail!("{}", t!("points.bad_value", part = pair));
            };
            if let Some(step) = Step::ALL.into_iter().find(|s| s.name() == name) {
                let parts = parts_of(step);
                if parts.is_empty() {
                    points.steps.insert(step, n);
                } else {
                    let weights: Vec<u32> = parts.iter().map(|p| p.1).collect();
                    for (p, share) in parts.iter().zip(spread(n, &weights)) {
                        points.parts.insert(p.0, share);
                    }
                }
            } else if let Some((id, _)) = SAO_PARTS.iter().find(|p| p.0 == name) {
                points.parts.insert(id, n);
            } else {
                let names = Step::ALL
                    .map(Step::name)
                    .into_iter()
                    .chain(SAO_PARTS.iter().map(|p| p.0))
                    .collect::<Vec<_>>()
                    .join(", ");
                bail!("{}", t!("points.bad_step", name = name, steps = names));
            }
        }
        Ok(points)
    }

    /// What step `step` is worth (the sum of its sub-steps' points when it has them).
    pub fn of(&self, step: Step) -> u32 {
        let parts = parts_of(step);
        if parts.is_empty() {
            self.steps.get(&step).copied().unwrap_or(0)
        } else {
            parts.iter().map(|p| self.of_part(p.0)).sum()
        }
    }

    /// What the sub-step `id` (`sao.smoothing`) is worth (0 for an id no sub-step has).
    pub fn of_part(&self, id: &str) -> u32 {
        self.parts.get(id).copied().unwrap_or(0)
    }

    /// What the step called `name` is worth (0 for a name no step has).
    pub fn of_name(&self, name: &str) -> u32 {
        Step::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .map_or(0, |s| self.of(s))
    }

    /// The `NAME=N,...` text that parses back to these points (what the class templates pass on):
    /// a step graded as one by its name, a step graded in sub-steps by each sub-step's id.
    pub fn spec(&self) -> String {
        let mut pairs = Vec::new();
        for s in Step::ALL {
            let parts = parts_of(s);
            if parts.is_empty() {
                pairs.push(format!("{}={}", s.name(), self.of(s)));
            }
            for (id, _) in parts {
                pairs.push(format!("{id}={}", self.of_part(id)));
            }
        }
        pairs.join(",")
    }

    /// What the step called `name` earned as a whole: its points when it passed. A step graded in
    /// sub-steps earns theirs (`StepReport::earned_points`).
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
        assert_eq!(p.of(Step::Sao), 50);
        assert_eq!(p.of_part("sao.smoothing"), 10);
        let q = Points::parse("sao=40, blur=20").unwrap();
        assert_eq!((q.of(Step::Sao), q.of(Step::Blur)), (40, 20));
        assert_eq!(q.of_part("sao.normal"), 8, "sao=40 spreads 8 per sub-step");
        assert_eq!(q.of(Step::Restore), 20, "unnamed steps keep their default");
        assert_eq!(Points::parse("default").unwrap(), p);
        assert_eq!(Points::parse(&q.spec()).unwrap(), q, "{}", q.spec());
    }

    #[test]
    fn sub_steps_take_their_own_points_and_wholes_spread_without_losing_any() {
        let p = Points::parse("sao.smoothing=20,sao.view=0").unwrap();
        assert_eq!(p.of_part("sao.smoothing"), 20);
        assert_eq!(p.of(Step::Sao), 50);
        for total in [0, 1, 7, 13, 49, 50, 51, 99] {
            let q = Points::parse(&format!("sao={total}")).unwrap();
            assert_eq!(q.of(Step::Sao), total, "sao={total}");
            let shares: Vec<u32> = SAO_PARTS.iter().map(|s| q.of_part(s.0)).collect();
            let (lo, hi) = (shares.iter().min().unwrap(), shares.iter().max().unwrap());
            assert!(hi - lo <= 1, "sao={total}: {shares:?}");
        }
        assert_eq!(spread(10, &[1, 3]), vec![3, 7]);
        assert_eq!(spread(3, &[0, 0]), vec![2, 1]);
    }

    #[test]
    fn bad_points_are_named() {
        for (spec, part) in [
            ("sao", "sao"),
            ("nosuch=3", "nosuch"),
            ("sao=-1", "sao=-1"),
            ("sao.nosuch=2", "sao.nosuch"),
        ] {
            let e = Points::parse(spec).unwrap_err().to_string();
            assert!(e.contains(part), "{spec}: {e}");
        }
    }
}
