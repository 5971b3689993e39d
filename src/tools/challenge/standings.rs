//! Each entry's place: ranked by its error, or left out with the reason.

use super::entry::{EntryOutcome, EntryScore};
use rust_i18n::t;
use serde::Serialize;
use std::path::PathBuf;

/// One entry's place: ranked (`rank`), or left out with the reason.
#[derive(Clone, Debug, Serialize)]
pub struct Standing {
    pub file: PathBuf,
    pub name: String,
    pub rank: Option<usize>,
    /// Mean over the scenes of their test cameras' mean PSNR (dB).
    pub psnr: Option<f64>,
    /// The largest over the scenes of the AO chain's time over the lesson chain's.
    pub cost_ratio: Option<f64>,
    pub reason: Option<String>,
    pub score: Option<EntryScore>,
    /// Its pictures' folder, relative to the report.
    pub pictures: String,
}

/// The ranking: entries that ran within the budget and are not an engine method, by mean PSNR
/// (ties by cost); then the others, with their reasons.
pub fn rank(measured: Vec<(PathBuf, String, EntryOutcome)>, budget: f64) -> Vec<Standing> {
    let mut ranked = Vec::new();
    let mut left_out = Vec::new();
    for (file, pictures, outcome) in measured {
        // The file's own name when it can be read, even if its shader cannot be built.
        let name = crate::scene::method_file::MethodFile::read(&file)
            .map(|m| m.name)
            .unwrap_or_else(|_| file.display().to_string());
        let mut s = Standing {
            name,
            file,
            rank: None,
            psnr: None,
            cost_ratio: None,
            reason: None,
            score: None,
            pictures,
        };
        match outcome {
            EntryOutcome::Failed(why) => {
                s.reason = Some(t!("challenge.broken", why = why).into_owned());
                left_out.push(s);
            }
            EntryOutcome::Measured(score) => {
                let n = score.scenes.len().max(1) as f64;
                let psnr = score.scenes.iter().map(|x| x.psnr).sum::<f64>() / n;
                let cost = score
                    .scenes
                    .iter()
                    .map(|x| x.cost_ratio)
                    .fold(0.0, f64::max);
                s.name = score.name.clone();
                s.psnr = Some(psnr);
                s.cost_ratio = Some(cost);
                if let Some(m) = &score.same_as {
                    s.reason = Some(t!("challenge.same_as", method = m).into_owned());
                } else if cost > budget {
                    let (cost, budget) = (format!("{cost:.2}"), format!("{budget:.2}"));
                    s.reason = Some(
                        t!("challenge.over_budget", cost = cost, budget = budget).into_owned(),
                    );
                }
                s.score = Some(score);
                if s.reason.is_some() {
                    left_out.push(s);
                } else {
                    ranked.push(s);
                }
            }
        }
    }
    ranked.sort_by(|a, b| {
        let key = |s: &Standing| {
            (
                s.psnr.unwrap_or(f64::MIN),
                -s.cost_ratio.unwrap_or(f64::MAX),
            )
        };
        key(b)
            .partial_cmp(&key(a))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for (i, s) in ranked.iter_mut().enumerate() {
        s.rank = Some(i + 1);
    }
    ranked.extend(left_out);
    ranked
}
