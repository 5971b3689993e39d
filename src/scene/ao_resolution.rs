//! The size the engine's AO methods run at, relative to the output.

use serde::{Deserialize, Serialize};

/// The size the engine's AO methods run at (`--ao-resolution`, `[ao] resolution`); `sao-lesson`
/// always runs at half size, as the course teaches it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AoResolution {
    /// Half the main size in each axis (the course's choice: a quarter of the pixels).
    #[default]
    Half,
    /// The main size: no up-sampling, exact depth at every pixel.
    Full,
    /// A quarter of the main size in each axis (a sixteenth of the pixels): for large outputs, where
    /// a texel still covers little of what AO varies over. The engine draws the depth (and every
    /// surface pass) at this size itself, each texel the scene at its centre.
    Quarter,
}

impl AoResolution {
    pub const ALL: [AoResolution; 3] = [
        AoResolution::Half,
        AoResolution::Full,
        AoResolution::Quarter,
    ];
    pub fn name(self) -> &'static str {
        match self {
            AoResolution::Half => "half",
            AoResolution::Full => "full",
            AoResolution::Quarter => "quarter",
        }
    }

    /// Main pixels per AO texel along each axis.
    pub fn divisor(self) -> u32 {
        match self {
            AoResolution::Full => 1,
            AoResolution::Half => 2,
            AoResolution::Quarter => 4,
        }
    }
    pub fn from_name(name: &str) -> Option<AoResolution> {
        AoResolution::ALL.into_iter().find(|r| r.name() == name)
    }
}
