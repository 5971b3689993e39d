//! Coordinate descent over axes: each key in turn tries its values with the others held, and keeps
//! the best; passes repeat until one changes nothing. Deterministic: fixed order, and a value must
//! beat the current one strictly to replace it (ties keep the earlier).
//!
//! Generic over what a configuration is: an engine method's `[ao]` table (`space::Choice` values)
//! or a method file's parameters with the engine keys it reads (`file_space::FileChoice`).

use anyhow::{bail, Result};
use std::collections::BTreeMap;
use std::fmt::Debug;

/// One value of one key: sets it in a configuration of type `C`.
pub trait Apply<C> {
    fn apply_to(&self, config: &C) -> C;
}

/// One key and the values the search tries, the start's own value first.
#[derive(Clone, Debug)]
pub struct Axis<V> {
    pub key: String,
    pub values: Vec<V>,
}

impl<V: PartialEq> Axis<V> {
    /// An axis whose first value is the start's own, then `grid` without it.
    pub fn new(key: &str, start: V, grid: impl IntoIterator<Item = V>) -> Axis<V> {
        let mut values = vec![];
        for v in std::iter::once(start).chain(grid) {
            if !values.contains(&v) {
                values.push(v);
            }
        }
        Axis {
            key: key.to_string(),
            values,
        }
    }
}

/// What one configuration scored: the training figure, or `None` when it is over the budget.
pub type Score = Option<f64>;

/// The outcome of a search.
#[derive(Clone, Debug)]
pub struct Found<C> {
    pub best: C,
    pub best_score: f64,
    /// The start's score (`None`: over the budget).
    pub start_score: Score,
    /// Distinct configurations scored, and how many of them were over the budget.
    pub evaluated: usize,
    pub over_budget: usize,
}

/// The most configurations `search` can score with `starts` starts, `axes` and `passes` (for the
/// progress bar): per start, the start, then each pass every value but the current one of every key.
pub fn max_evaluations<V>(starts: usize, axes: &[Axis<V>], passes: u32) -> usize {
    starts
        * (1 + passes as usize
            * axes
                .iter()
                .map(|a| a.values.len().saturating_sub(1))
                .sum::<usize>())
}

/// Coordinate descent over `axes` from each of `starts` in turn (at most `passes` passes each),
/// keeping the best it reaches; `score` is called once per distinct configuration, whichever descent
/// meets it. One axis at a time cannot reach a corner where several keys must change together (a
/// second layer pays off only with the back faces, and both fit a budget only at a smaller size),
/// so a caller may give more than one start. `start_score` is the first start's. `Err` when there is
/// no start, or no configuration scored is within the budget.
pub fn search<C, V>(
    starts: &[C],
    axes: &[Axis<V>],
    passes: u32,
    mut score: impl FnMut(&C) -> Result<Score>,
) -> Result<Found<C>>
where
    C: Clone + PartialEq + Debug,
    V: Apply<C>,
{
    let Some(first) = starts.first() else {
        bail!("no configuration to start from");
    };
    let mut seen: BTreeMap<String, Score> = BTreeMap::new();
    let mut over_budget = 0;
    let mut eval = |config: &C| -> Result<Score> {
        let key = format!("{config:?}");
        if let Some(s) = seen.get(&key) {
            return Ok(*s);
        }
        let s = score(config)?;
        if let Some(v) = s {
            if !v.is_finite() {
                bail!("a configuration scored {v}");
            }
        } else {
            over_budget += 1;
        }
        seen.insert(key, s);
        Ok(s)
    };
    let start_score = eval(first)?;
    let mut overall = first.clone();
    let mut overall_score = f64::NEG_INFINITY;
    for start in starts {
        let mut best = start.clone();
        let mut best_score = eval(start)?.unwrap_or(f64::NEG_INFINITY);
        for _ in 0..passes {
            let mut changed = false;
            for axis in axes {
                for choice in &axis.values {
                    let candidate = choice.apply_to(&best);
                    if candidate == best {
                        continue;
                    }
                    if let Some(s) = eval(&candidate)? {
                        if s > best_score {
                            best = candidate;
                            best_score = s;
                            changed = true;
                        }
                    }
                }
            }
            if !changed {
                break;
            }
        }
        // Strictly better only: a tie keeps the earlier start's result.
        if best_score > overall_score {
            overall = best;
            overall_score = best_score;
        }
    }
    if !overall_score.is_finite() {
        bail!("{}", rust_i18n::t!("tune.nothing_in_budget"));
    }
    Ok(Found {
        best: overall,
        best_score: overall_score,
        start_score,
        evaluated: seen.len(),
        over_budget,
    })
}

#[cfg(test)]
mod tests {
    use crate::ao::{AoMethod, AoSettings, Thickness};
    use crate::tools::tune::search::{max_evaluations, search};
    use crate::tools::tune::space::{axes, Choice};

    fn lesson() -> AoSettings {
        AoSettings {
            method: AoMethod::SaoLesson,
            ..AoSettings::default()
        }
    }

    /// A smooth score peaking at bias 0.025, intensity 8: separable, so one pass finds the grid's
    /// best and a second changes nothing.
    fn peak(ao: &AoSettings) -> f64 {
        let (b, i) = (ao.bias as f64, ao.intensity as f64);
        -((b - 0.025) * 100.0).powi(2) - (i - 8.0).powi(2)
    }

    #[test]
    fn descent_finds_the_grid_optimum_and_never_ends_below_the_start() {
        let start = lesson();
        let space = axes(AoMethod::SaoLesson, &start, false);
        let mut calls = 0;
        let found = search(&[start], &space, 3, |ao| {
            calls += 1;
            Ok(Some(peak(ao)))
        })
        .unwrap();
        assert_eq!((found.best.bias, found.best.intensity), (0.025, 8.0));
        assert_eq!(
            found.best.spiral_turns, start.spiral_turns,
            "ties keep the start"
        );
        assert!(found.best_score >= found.start_score.unwrap());
        assert_eq!(found.evaluated, calls, "each configuration scored once");
        assert!(calls <= max_evaluations(1, &space, 3));
        // A score the start already maximises leaves it unchanged.
        let found = search(&[start], &space, 2, |ao| {
            Ok(Some(-(ao.bias - 0.012).abs() as f64))
        })
        .unwrap();
        assert_eq!(found.best, start);
    }

    #[test]
    fn over_budget_configurations_are_skipped_and_an_empty_budget_is_an_error() {
        let start = AoSettings {
            method: AoMethod::Vbao,
            ..AoSettings::default()
        };
        let space = axes(AoMethod::Vbao, &start, false);
        // Thicker is better but above 0.4 m is "over budget", the start (0.5 m) too.
        let score = |ao: &AoSettings| {
            let t = ao.thickness_metres();
            Ok((t <= 0.4).then_some(t as f64))
        };
        let found = search(&[start], &space, 2, score).unwrap();
        assert_eq!(found.start_score, None);
        assert_eq!(found.best.thickness, Some(Thickness::Metres(0.375)));
        assert!(found.over_budget > 0);
        assert!(search(&[start], &space, 2, |_| Ok(None)).is_err());
        assert!(search(&[], &space, 2, |_| Ok(Some(0.0))).is_err());
        assert_ne!(Choice::Bias(0.0), Choice::Bias(0.1));
    }

    /// A score that pays only when bias and intensity change together: one axis at a time from the
    /// lesson's table never leaves it, a second start at the corner finds it and is kept.
    #[test]
    fn a_second_start_reaches_a_corner_one_axis_at_a_time_cannot() {
        let start = lesson();
        let space = axes(AoMethod::SaoLesson, &start, false);
        let corner = |ao: &AoSettings| {
            let both = ao.bias == 0.05 && ao.intensity == 8.0;
            Ok(Some(if both { 1.0 } else { -(ao.bias as f64) }))
        };
        let alone = search(&[start], &space, 3, corner).unwrap();
        assert_ne!((alone.best.bias, alone.best.intensity), (0.05, 8.0));
        let seed = AoSettings {
            bias: 0.05,
            intensity: 8.0,
            ..start
        };
        let both = search(&[start, seed], &space, 3, corner).unwrap();
        assert_eq!((both.best.bias, both.best.intensity), (0.05, 8.0));
        assert_eq!(both.best_score, 1.0);
        assert_eq!(
            both.start_score, alone.start_score,
            "the first start's score"
        );
    }

    /// The descent knows nothing of `AoSettings`: any configuration type with values that set one
    /// key of it searches the same way, and an axis lists each value once, the start's first.
    #[test]
    fn the_descent_is_generic_over_the_configuration() {
        use crate::tools::tune::search::{Apply, Axis};
        #[derive(Clone, Copy, Debug, PartialEq)]
        struct XY(i32, i32);
        #[derive(Clone, Copy, Debug, PartialEq)]
        enum Set {
            X(i32),
            Y(i32),
        }
        impl Apply<XY> for Set {
            fn apply_to(&self, c: &XY) -> XY {
                match *self {
                    Set::X(x) => XY(x, c.1),
                    Set::Y(y) => XY(c.0, y),
                }
            }
        }
        let x = Axis::new("x", Set::X(0), (-3..=3).map(Set::X));
        assert_eq!(x.values.len(), 7, "the start's value once");
        assert_eq!(x.values[0], Set::X(0));
        let y = Axis::new("y", Set::Y(9), (-3..=3).map(Set::Y));
        assert_eq!((y.values.len(), y.values[0]), (8, Set::Y(9)));
        let found = search(&[XY(0, 9)], &[x, y], 2, |c: &XY| {
            Ok(Some(
                -(((c.0 - 2) * (c.0 - 2) + (c.1 + 1) * (c.1 + 1)) as f64),
            ))
        })
        .unwrap();
        assert_eq!(found.best, XY(2, -1));
        assert_eq!(found.best_score, 0.0);
        assert_eq!(found.start_score, Some(-104.0));
    }
}
