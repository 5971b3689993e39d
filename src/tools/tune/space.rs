//! What `opengl3d tune` may change for each method: the `[ao]` keys its shaders read, each with a
//! small fixed list of values inside the range `ao::settings` documents.
//!
//! Two kinds of keys. *Free* ones change what a tap computes, not how many taps or passes there
//! are (bias, intensity, spiral turns, a thickness in metres): they are always searched, at the
//! cost of the scene's setting. Keys that *cost* (sample count or preset, resolution, normals pass,
//! guard band, back-face pass, second layer, rays) are searched only with `--budget`, which bounds
//! what they may spend. The radius is never searched: it defines the truth (rays of length R).

use super::search::{self, Apply};
use crate::ao::settings::{MethodInfo, NormalUse, TunedIntensity};
use crate::ao::{
    AoMethod, AoResolution, AoSettings, GuardBand, NormalSource, SlicePreset, Thickness,
};

/// One value of one `[ao]` key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Choice {
    Bias(f32),
    Intensity(f32),
    SpiralTurns(u32),
    Thickness(Option<Thickness>),
    Layers(u32),
    Normals(NormalSource),
    GuardBand(GuardBand),
    Resolution(AoResolution),
    Samples(u32),
    Quality(Option<SlicePreset>),
    Rays(u32),
}

impl Choice {
    /// `ao` with this value set.
    pub fn apply(self, ao: &AoSettings) -> AoSettings {
        let mut a = *ao;
        match self {
            Choice::Bias(v) => a.bias = v,
            Choice::Intensity(v) => a.intensity = v,
            Choice::SpiralTurns(v) => a.spiral_turns = v,
            Choice::Thickness(v) => a.thickness = v,
            Choice::Layers(v) => a.layers = v,
            Choice::Normals(v) => a.normals = v,
            Choice::GuardBand(v) => a.guard_band = v,
            Choice::Resolution(v) => a.resolution = v,
            Choice::Samples(v) => a.samples = v,
            Choice::Quality(v) => a.quality = v,
            Choice::Rays(v) => a.rays = v,
        }
        a
    }
}

impl Apply<AoSettings> for Choice {
    fn apply_to(&self, ao: &AoSettings) -> AoSettings {
        self.apply(ao)
    }
}

/// One `[ao]` key and the values the search tries, the start's own value first.
pub type Axis = search::Axis<Choice>;

/// Bias (m, `BIAS_RANGE` 0–10): self-occlusion shows below a few millimetres, and beyond a
/// decimetre the bias hides real creases at any radius the scenes use.
const BIASES: [f32; 7] = [0.0, 0.003, 0.006, 0.012, 0.025, 0.05, 0.1];
/// Intensities as the lesson's scale (`INTENSITY_RANGE`; its occlusion is `min(1, sum · intensity / n)`).
const INTENSITIES: [f32; 9] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.5, 8.0, 10.0, 13.0];
/// Intensities as an exponent (`rtao`'s): the exponent of its visibility is `5 / intensity` (5 is the identity).
const RTAO_INTENSITIES: [f32; 5] = [3.0, 4.0, 5.0, 6.0, 7.5];
/// Spiral turns (`SPIRAL_TURNS_RANGE` 1–64); the paper's table uses small counts prime to the
/// sample count.
const SPIRAL_TURNS: [u32; 6] = [1, 2, 3, 5, 7, 9];
/// Slab thickness (`vbao`'s) as a fraction of the radius (`THICKNESS_RANGE` in metres).
pub(super) const THICKNESS_OF_RADIUS: [f32; 8] = [0.125, 0.25, 0.375, 0.5, 0.75, 1.0, 1.5, 2.0];
/// Sample counts of the methods without presets (`SAMPLES_RANGE`).
pub(super) const SAMPLES: [u32; 6] = [4, 8, 11, 16, 24, 32];
/// Rays per pixel and frame (`rtao`'s).
const RAYS: [u32; 4] = [1, 2, 4, 8];

/// Where the descents start: the scene's own table; with a budget, for the engine's methods that
/// read their occluders from the depth buffer, also the configuration that reads the most of what
/// the depth buffer can know for its cost: a quarter of the size, a guard band, the geometric
/// normals (where the method reads a normal it may choose), the back faces and two layers (where it
/// reads them, with the `medium` preset where it has presets). From the scene's table one key at a
/// time, the second layer is not worth its pass without the back faces, nor both at half size
/// within a budget of about the lesson's cost; from this start the descent trades them away where
/// they do not pay.
pub fn starts(method: AoMethod, start: &AoSettings, budgeted: bool) -> Vec<AoSettings> {
    let info = method.info();
    if !budgeted || !reads_the_depth_chain(info) {
        return vec![*start];
    }
    let mut knows_most = AoSettings {
        resolution: AoResolution::Quarter,
        guard_band: GuardBand::Auto,
        ..*start
    };
    if info.normals == NormalUse::Chosen {
        knows_most.normals = NormalSource::Geometric;
    }
    if info.back_faces {
        knows_most.thickness = Some(Thickness::Backface);
    }
    if info.second_layer {
        knows_most.layers = 2;
    }
    // With those passes to pay for, the taps drop to the `medium` preset where there are presets.
    if info.presets.is_some() && (info.back_faces || info.second_layer) {
        knows_most.quality = Some(SlicePreset::Medium);
    }
    if knows_most == *start {
        vec![*start]
    } else {
        vec![*start, knows_most]
    }
}

/// An engine method whose occluders come from the depth chain: the AO size, the guard band and the
/// normals change what it sees.
fn reads_the_depth_chain(info: &MethodInfo) -> bool {
    info.engine_chain && info.reads_depth_occluders
}

/// The keys `method`'s shaders read (its row, `MethodInfo`), from `start` (the scene's `[ao]` with
/// the method set): the free keys always, the costly ones only when `budgeted`. Costly keys come
/// first, so that the free ones are tuned for the chosen taps.
pub fn axes(method: AoMethod, start: &AoSettings, budgeted: bool) -> Vec<Axis> {
    let info = method.info();
    let mut axes = Vec::new();
    if budgeted {
        if info.presets.is_some() {
            let presets = SlicePreset::ALL.map(Some);
            axes.push(axis(
                "quality",
                Choice::Quality(start.quality),
                presets.map(Choice::Quality),
            ));
        } else if info.rays {
            axes.push(axis(
                "rays",
                Choice::Rays(start.rays),
                RAYS.map(Choice::Rays),
            ));
        } else {
            axes.push(axis(
                "samples",
                Choice::Samples(start.samples),
                SAMPLES.map(Choice::Samples),
            ));
        }
        if reads_the_depth_chain(info) {
            axes.push(axis(
                "resolution",
                Choice::Resolution(start.resolution),
                AoResolution::ALL.map(Choice::Resolution),
            ));
            axes.push(axis(
                "guard_band",
                Choice::GuardBand(start.guard_band),
                [GuardBand::Off, GuardBand::Auto].map(Choice::GuardBand),
            ));
            if info.normals == NormalUse::Chosen {
                axes.push(axis(
                    "normals",
                    Choice::Normals(start.normals),
                    NormalSource::ALL.map(Choice::Normals),
                ));
            }
        }
        if info.second_layer {
            axes.push(axis(
                "layers",
                Choice::Layers(start.layers),
                [1, 2].map(Choice::Layers),
            ));
        }
    }
    // Free keys: what each shader reads besides the radius and its counts.
    if info.bias {
        axes.push(axis(
            "bias",
            Choice::Bias(start.bias),
            BIASES.map(Choice::Bias),
        ));
    }
    match info.tuned_intensity {
        Some(TunedIntensity::Scale) => axes.push(axis(
            "intensity",
            Choice::Intensity(start.intensity),
            INTENSITIES.map(Choice::Intensity),
        )),
        Some(TunedIntensity::Exponent) => axes.push(axis(
            "intensity",
            Choice::Intensity(start.intensity),
            RTAO_INTENSITIES.map(Choice::Intensity),
        )),
        None => {}
    }
    if info.spiral_turns {
        axes.push(axis(
            "spiral_turns",
            Choice::SpiralTurns(start.spiral_turns),
            SPIRAL_TURNS.map(Choice::SpiralTurns),
        ));
    }
    if info.thickness {
        let mut values: Vec<Choice> = THICKNESS_OF_RADIUS
            .iter()
            .map(|f| Choice::Thickness(Some(Thickness::Metres(f * start.radius))))
            .collect();
        // The back-face pass costs a depth pass of the scene.
        if budgeted && info.back_faces {
            values.push(Choice::Thickness(Some(Thickness::Backface)));
        }
        axes.push(axis_of(
            "thickness",
            Choice::Thickness(start.thickness),
            values,
        ));
    }
    axes
}

/// `ao` with its free keys (which change no tap or pass) at fixed values: configurations with the
/// same signature cost the same, so `tune` times each signature once instead of letting timing
/// noise rule out some values of a free key.
pub fn cost_signature(ao: &AoSettings) -> AoSettings {
    let defaults = AoSettings::default();
    AoSettings {
        bias: defaults.bias,
        intensity: defaults.intensity,
        spiral_turns: defaults.spiral_turns,
        thickness: match ao.thickness {
            Some(Thickness::Backface) => Some(Thickness::Backface),
            _ => None,
        },
        ..*ao
    }
}

/// An axis whose first value is the start's own, then `grid` without it.
fn axis<const N: usize>(key: &str, start: Choice, grid: [Choice; N]) -> Axis {
    Axis::new(key, start, grid)
}

fn axis_of(key: &str, start: Choice, grid: Vec<Choice>) -> Axis {
    Axis::new(key, start, grid)
}

#[cfg(test)]
mod tests {
    use crate::ao::{AoMethod, AoResolution, AoSettings, NormalSource, SlicePreset, Thickness};
    use crate::tools::tune::search::{max_evaluations, search};
    use crate::tools::tune::space::{axes, cost_signature, starts, Choice};

    // The descent over the engine's keys (`search` is generic; these are its runs on `Choice`).
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
    fn a_budget_adds_the_start_that_knows_most_for_the_engines_methods_only() {
        let vbao = AoSettings {
            method: AoMethod::Vbao,
            ..AoSettings::default()
        };
        assert_eq!(starts(AoMethod::Vbao, &vbao, false), vec![vbao]);
        let both = starts(AoMethod::Vbao, &vbao, true);
        assert_eq!(both.len(), 2);
        assert_eq!(both[0], vbao);
        let rich = both[1];
        assert_eq!(rich.resolution, AoResolution::Quarter);
        assert_eq!(rich.thickness, Some(Thickness::Backface));
        assert_eq!((rich.layers, rich.normals), (2, NormalSource::Geometric));
        let lesson = AoSettings::default();
        assert_eq!(starts(AoMethod::SaoLesson, &lesson, true), vec![lesson]);
        let crytek = AoSettings {
            method: AoMethod::Crytek,
            ..AoSettings::default()
        };
        let c = starts(AoMethod::Crytek, &crytek, true);
        assert_eq!(
            c[1].normals, crytek.normals,
            "Crytek's sphere reads no normal"
        );
    }

    #[test]
    fn every_axis_starts_at_the_scene_value_and_costly_keys_need_a_budget() {
        let start = AoSettings {
            method: AoMethod::Vbao,
            bias: 0.02,
            ..AoSettings::default()
        };
        let free = axes(AoMethod::Vbao, &start, false);
        let keys: Vec<&str> = free.iter().map(|a| a.key.as_str()).collect();
        assert_eq!(keys, ["bias", "thickness"]);
        for a in &free {
            let first = a.values[0].apply(&start);
            assert_eq!(first, start, "{}", a.key);
            let n = a.values.iter().filter(|v| v.apply(&start) == start).count();
            assert_eq!(n, 1, "{}: the start's value once", a.key);
        }
        assert!(!free[1]
            .values
            .contains(&Choice::Thickness(Some(Thickness::Backface))));
        let budgeted = axes(AoMethod::Vbao, &start, true);
        let keys: Vec<&str> = budgeted.iter().map(|a| a.key.as_str()).collect();
        assert_eq!(
            keys,
            [
                "quality",
                "resolution",
                "guard_band",
                "normals",
                "layers",
                "bias",
                "thickness"
            ]
        );
        // The lesson reads bias, intensity and spiral turns; hbao reads none of them.
        let lesson: Vec<String> = axes(AoMethod::SaoLesson, &AoSettings::default(), false)
            .into_iter()
            .map(|a| a.key)
            .collect();
        assert_eq!(lesson, ["bias", "intensity", "spiral_turns"]);
        assert!(axes(AoMethod::Hbao, &AoSettings::default(), false).is_empty());
        // Free keys share a cost; the keys that add taps or passes do not.
        for a in &free {
            for v in &a.values {
                assert_eq!(cost_signature(&v.apply(&start)), cost_signature(&start));
            }
        }
        let costly = |c: Choice| cost_signature(&c.apply(&start)) != cost_signature(&start);
        assert!(costly(Choice::Thickness(Some(Thickness::Backface))));
        assert!(costly(Choice::Layers(2)) && costly(Choice::Quality(Some(SlicePreset::Ultra))));
    }
}
