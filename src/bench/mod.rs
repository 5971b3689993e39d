//! Benchmarks: run time against error versus the ray-traced reference, and numerical stress tests.

use crate::res::ResDirs;
use anyhow::{bail, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Args, Debug, Clone)]
pub struct BenchArgs {
    /// Scene files (default: the demo scene).
    #[arg(long = "scene")]
    pub scenes: Vec<PathBuf>,
    #[arg(long, default_value_t = 1920)]
    pub width: u32,
    #[arg(long, default_value_t = 1080)]
    pub height: u32,
    /// Output folder for report.json, report.md and the charts.
    #[arg(long, default_value = "out/bench")]
    pub out: PathBuf,
    /// Run the numerical stress tests instead.
    #[arg(long)]
    pub stress: bool,
}

pub fn run(_res: &ResDirs, _args: &BenchArgs) -> Result<()> {
    bail!("the benchmark is not built yet")
}
