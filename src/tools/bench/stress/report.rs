//! The stress run's report: per case, the outputs checked and what failed; the linear-depth
//! error against distance. Serialised as `stress.json`, rendered by `markdown.rs`.

use serde::Serialize;

/// One output buffer of one method in one case.
#[derive(Clone, Debug, Serialize)]
pub struct OutputCheck {
    pub method: String,
    pub output: String,
    pub values: usize,
    pub non_finite: usize,
    pub min: f32,
    pub max: f32,
}

#[derive(Clone, Debug, Serialize)]
pub struct CaseResult {
    pub category: String,
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub near: f32,
    pub far: f32,
    pub fov_y: f32,
    pub radius: f32,
    pub intensity: f32,
    pub bias: f32,
    pub methods: Vec<String>,
    /// NaN/Inf values over every output of every method (must be 0).
    pub non_finite: usize,
    /// Failed range checks (visibility outside [0, 1], depth ≤ 0, sky not fully visible, ...).
    pub failures: Vec<String>,
    /// Observations: mean visibility of the non-sky pixels per method, and the like.
    pub notes: Vec<String>,
    pub ok: bool,
    pub ms: f64,
    pub outputs: Vec<OutputCheck>,
}

#[derive(Clone, Debug, Serialize)]
pub struct DepthSample {
    pub distance: f64,
    /// The engine (DEPTH_COMPONENT32, standard Z): restored − exact, metres.
    pub engine_d32: f64,
    /// The stand-alone probe per mode (label, restored − exact), `None` when the mode is unavailable.
    pub probe: Vec<(String, Option<f64>)>,
    /// Theoretical distance step of one depth unit per mode (label, metres).
    pub step: Vec<(String, f64)>,
}

#[derive(Clone, Debug, Serialize)]
pub struct DepthConfigResult {
    pub near: f32,
    pub far: f32,
    pub samples: Vec<DepthSample>,
}

#[derive(Clone, Debug, Serialize)]
pub struct StressReport {
    pub renderer: String,
    pub software: bool,
    pub cases: Vec<CaseResult>,
    pub total_non_finite: usize,
    pub depth_precision: Vec<DepthConfigResult>,
    pub depth_probe_note: String,
    pub skipped: Vec<String>,
    pub run_s: f64,
}
