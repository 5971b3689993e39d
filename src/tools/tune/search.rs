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
    use crate::tools::tune::search::search;

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
