//! `grade --challenge DIR` on the command line: the run's settings from the flags, the ranking on
//! stdout.

use crate::res::ResDirs;
use anyhow::{bail, Result};
use rust_i18n::t;

/// `grade --challenge DIR`: ranks the class's method files and writes the report.
#[cfg(feature = "bench")]
pub fn run(res: &ResDirs, args: &crate::tools::grade::GradeArgs) -> Result<()> {
    use crate::tools::challenge::{self, ChallengeConfig, ChallengeProtocol};
    let Some(dir) = &args.challenge else {
        return Ok(());
    };
    if !(args.entry_timeout > 0.0 && args.entry_timeout.is_finite()) {
        bail!("{}", t!("grade.bad_timeout", value = args.entry_timeout));
    }
    let scenes = match args.scene.is_empty() {
        true => vec![res
            .find("scenes/demo.toml")
            .map_err(|e| anyhow::anyhow!("{e}"))?],
        false => args.scene.clone(),
    };
    let cfg = ChallengeConfig {
        dir: dir.clone(),
        protocol: ChallengeProtocol::new(
            scenes,
            crate::tools::reference::reference_cache_dir(None)?,
        ),
        budget: args.budget,
        out: args
            .out
            .clone()
            .unwrap_or_else(|| "challenge-report".into()),
        timeout: std::time::Duration::from_secs_f64(args.entry_timeout),
        progress: std::io::IsTerminal::is_terminal(&std::io::stderr()),
    };
    let standings = challenge::run(res, &cfg)?;
    for s in &standings {
        let place = s.rank.map_or("–".to_string(), |r| r.to_string());
        let psnr = s.psnr.map_or("–".to_string(), |p| format!("{p:.2} dB"));
        let cost = s.cost_ratio.map_or("–".to_string(), |c| format!("{c:.2}×"));
        let reason = s.reason.as_deref().unwrap_or("");
        crate::outln!("{place:>3}  {:<24} {psnr:>9} {cost:>7}  {reason}", s.name);
    }
    crate::outln!(
        "{}",
        t!(
            "challenge.wrote",
            path = cfg.out.join("report.html").display()
        )
    );
    Ok(())
}

#[cfg(not(feature = "bench"))]
pub fn run(_: &ResDirs, _: &crate::tools::grade::GradeArgs) -> Result<()> {
    bail!("{}", t!("challenge.no_bench_feature"))
}
