//! `grade --challenge DIR`: a class's own AO methods (method files) ranked by their error against
//! the ray-traced truth on the scenes' test cameras, among those whose AO chain costs at most a
//! budget times the lesson chain's. Each entry runs in a confined child process (memory limit,
//! time limit, killed with the grader), one at a time so that timings do not disturb each other;
//! a broken entry, one over the budget, and one that renders exactly what an engine method renders
//! are listed below the ranking with the reason.

pub mod entry;
pub mod protocol;
mod report;
pub mod standings;

use crate::res::ResDirs;
use crate::tools::bench::perf::{self, references};
use anyhow::{bail, Context as _, Result};
use entry::EntryOutcome;
pub use protocol::{ChallengeConfig, ChallengeProtocol};
use rust_i18n::t;
pub use standings::Standing;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The method files of `dir`: `*.toml` in it and in its folders one level down (one folder per
/// student), in name order.
pub fn find_entries(dir: &Path) -> Result<Vec<PathBuf>> {
    let list = |d: &Path| -> Result<Vec<PathBuf>> {
        let mut v = Vec::new();
        for e in std::fs::read_dir(d).map_err(|e| crate::io::io_error(d, "read", &e))? {
            v.push(e.map_err(|e| crate::io::io_error(d, "read", &e))?.path());
        }
        v.sort();
        Ok(v)
    };
    let is_toml = |p: &Path| p.is_file() && p.extension().is_some_and(|e| e == "toml");
    let mut found = Vec::new();
    for p in list(dir)? {
        if is_toml(&p) {
            found.push(p);
        } else if p.is_dir() && !p.is_symlink() {
            found.extend(list(&p)?.into_iter().filter(|q| is_toml(q)));
        }
    }
    if found.is_empty() {
        bail!("{}", t!("challenge.no_entries", dir = dir.display()));
    }
    Ok(found)
}

pub fn run(res: &ResDirs, cfg: &ChallengeConfig) -> Result<Vec<Standing>> {
    if !(cfg.budget > 0.0 && cfg.budget.is_finite()) {
        bail!("{}", t!("challenge.bad_budget", value = cfg.budget));
    }
    let entries = find_entries(&cfg.dir)?;
    for s in &cfg.protocol.scenes {
        if !s.is_file() {
            bail!("{}", t!("tune.no_scene", path = s.display()));
        }
    }
    crate::io::create_dir_all(&cfg.out)?;
    trace_truths(res, cfg)?;
    let exe = std::env::current_exe().context("cannot find the opengl3d executable")?;
    let pb = crate::tools::bench::progress::bar(
        entries.len() as u64,
        "challenge {bar:40} {pos}/{len} entries [{elapsed_precise} < {eta_precise}] {msg}",
        cfg.progress,
    );
    let mut measured = Vec::new();
    for (i, file) in entries.iter().enumerate() {
        pb.set_message(file.display().to_string());
        let pictures = format!("entries/{:03}", i + 1);
        let outcome = measure(&exe, res, cfg, file, &cfg.out.join(&pictures));
        measured.push((file.clone(), pictures, outcome));
        pb.inc(1);
    }
    pb.finish_and_clear();
    let standings = standings::rank(measured, cfg.budget);
    report::write(cfg, &standings)?;
    Ok(standings)
}

/// Every scene's truths, once, in this process (the children read them from the cache).
fn trace_truths(res: &ResDirs, cfg: &ChallengeConfig) -> Result<()> {
    let perf = cfg.protocol.perf_config();
    let mut loaded = Vec::new();
    for path in &cfg.protocol.scenes {
        let (sd, bvh) =
            references::load_scene(res, path, &perf).with_context(|| path.display().to_string())?;
        loaded.push((sd, bvh));
    }
    let total = loaded.iter().map(|(sd, _)| sd.cameras.len()).sum();
    let (mut done, mut count) = (0, references::RenderCount::default());
    let perf = perf::PerfConfig {
        progress: cfg.progress,
        ..perf
    };
    for (sd, bvh) in &mut loaded {
        let radius = sd.desc.ao.radius;
        references::trace_references(sd, bvh, &[radius], &perf, &mut count, (&mut done, total));
        report::write_truth_pictures(&cfg.out, sd)?;
    }
    Ok(())
}

/// Runs one entry in a confined child; its outcome, or why there is none.
fn measure(
    exe: &Path,
    res: &ResDirs,
    cfg: &ChallengeConfig,
    file: &Path,
    out: &Path,
) -> EntryOutcome {
    let mut cmd = Command::new(exe);
    for d in res.dirs().iter().take(res.dirs().len().saturating_sub(1)) {
        cmd.arg("--res").arg(d);
    }
    let protocol = match serde_json::to_string(&cfg.protocol) {
        Ok(p) => p,
        Err(e) => return EntryOutcome::Failed(e.to_string()),
    };
    cmd.arg("challenge-entry")
        .arg("--file")
        .arg(file)
        .arg("--out")
        .arg(out)
        .arg("--protocol")
        .arg(protocol);
    let mut child = match crate::tools::grade::spawn_confined(cmd) {
        Ok(c) => c,
        Err(e) => return EntryOutcome::Failed(e.to_string()),
    };
    let (stdout, stderr) = (child.stdout.take(), child.stderr.take());
    let drain = |r: Option<Box<dyn std::io::Read + Send>>| {
        std::thread::spawn(move || {
            let mut text = String::new();
            if let Some(mut r) = r {
                let _ = r.read_to_string(&mut text);
            }
            text
        })
    };
    let out_thread = drain(stdout.map(|s| Box::new(s) as Box<dyn std::io::Read + Send>));
    let err_thread = drain(stderr.map(|s| Box::new(s) as Box<dyn std::io::Read + Send>));
    let waited = crate::tools::grade::wait_or_kill(&mut child, Instant::now(), cfg.timeout);
    crate::tools::grade::unregister_group(child.id());
    let (text, err) = (
        out_thread.join().unwrap_or_default(),
        err_thread.join().unwrap_or_default(),
    );
    match waited {
        Ok(None) => {
            let seconds = cfg.timeout.as_secs_f64();
            return EntryOutcome::Failed(t!("challenge.timed_out", seconds = seconds).into_owned());
        }
        Err(e) => return EntryOutcome::Failed(e),
        Ok(Some(_)) => {}
    }
    let line = text.lines().rev().find(|l| l.trim_start().starts_with('{'));
    match line.map(serde_json::from_str::<EntryOutcome>) {
        Some(Ok(outcome)) => outcome,
        _ => {
            let tail = err
                .lines()
                .rev()
                .find(|l| !l.trim().is_empty())
                .unwrap_or("");
            EntryOutcome::Failed(t!("challenge.no_result", tail = tail).into_owned())
        }
    }
}
