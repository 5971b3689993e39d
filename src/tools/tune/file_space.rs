//! What `opengl3d tune --method-file` may change for a method of one's own: the file's
//! `[[parameter]]`s over their ranges, and the engine keys the file says its shader reads.
//!
//! The format gives each parameter a range and nothing else (no step, no integer flag), so each is
//! tried at its default and at `PARAMETER_STEPS + 1` evenly spaced values from `min` to `max`.
//! The engine keys follow `space`: the thickness (when the file reads it) is free; the sample
//! budget (when a count spends it), the AO size, the guard band, the normals pass, the back faces
//! and the second layer cost, and are searched only with `--budget`. The radius is never searched.
//! Nor are the scene's bias and intensity: a method of one's own that wants one tuned declares it
//! as a parameter.

use super::search::{Apply, Axis};
use super::space::{Choice, SAMPLES, THICKNESS_OF_RADIUS};
use crate::ao::{AoResolution, AoSettings, GuardBand, NormalSource, Thickness};
use crate::scene::method_file::{CountRule, MethodFile};

/// Intervals each parameter's range is cut into: 9 values, the default besides.
pub const PARAMETER_STEPS: u32 = 8;

/// One configuration of a method file's method: the engine's `[ao]` it runs with (narrowed to what
/// the file reads) and one value per parameter, in the file's order.
#[derive(Clone, Debug, PartialEq)]
pub struct FileConfig {
    pub ao: AoSettings,
    pub values: Vec<f32>,
}

/// One value of one key of a method file's search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FileChoice {
    Engine(Choice),
    /// Parameter `index` (the file's order) at `value`.
    Parameter(usize, f32),
}

impl Apply<FileConfig> for FileChoice {
    fn apply_to(&self, c: &FileConfig) -> FileConfig {
        let mut out = c.clone();
        match *self {
            FileChoice::Engine(choice) => out.ao = choice.apply(&c.ao),
            FileChoice::Parameter(i, v) => {
                if let Some(slot) = out.values.get_mut(i) {
                    *slot = v;
                }
            }
        }
        out
    }
}

/// The file's method at its defaults with `start` (the scene's `[ao]`, narrowed to what it reads).
pub fn start(file: &MethodFile, start: &AoSettings) -> FileConfig {
    FileConfig {
        ao: crate::ao::user_method::settings_for(file, start),
        values: file.parameters.iter().map(|p| p.default).collect(),
    }
}

/// `file` with its parameters at `values` (the search's grid stays inside their ranges).
pub fn with_values(file: &MethodFile, values: &[f32]) -> MethodFile {
    let mut f = file.clone();
    for (p, v) in f.parameters.iter_mut().zip(values) {
        p.value = *v;
    }
    f
}

/// `steps + 1` evenly spaced values from `min` to `max` (one when the range is a point), each
/// rounded to `f32` once, the ends exact.
pub fn grid(min: f32, max: f32, steps: u32) -> Vec<f32> {
    if max <= min || steps == 0 {
        return vec![min];
    }
    let (lo, hi) = (min as f64, max as f64);
    (0..=steps)
        .map(|k| match k {
            0 => min,
            k if k == steps => max,
            k => (lo + (hi - lo) * k as f64 / steps as f64) as f32,
        })
        .collect()
}

/// Where the descents start: the file's defaults with the scene's table; with a budget also the
/// configuration that reads the most of what the depth buffer can know (a quarter of the size, a
/// guard band, and the geometric normals, back faces and second layer where the file reads them),
/// as `space::starts` does for the engine's methods.
pub fn starts(file: &MethodFile, first: &FileConfig, budgeted: bool) -> Vec<FileConfig> {
    if !budgeted {
        return vec![first.clone()];
    }
    let mut rich = first.ao;
    rich.resolution = AoResolution::Quarter;
    rich.guard_band = GuardBand::Auto;
    if file.reads.normals {
        rich.normals = NormalSource::Geometric;
    }
    if file.reads.back_faces {
        rich.thickness = Some(Thickness::Backface);
    }
    if file.reads.second_layer {
        rich.layers = 2;
    }
    let knows_most = FileConfig {
        ao: rich,
        values: first.values.clone(),
    };
    if knows_most == *first {
        vec![first.clone()]
    } else {
        vec![first.clone(), knows_most]
    }
}

/// The keys of `file`'s search from `start`: costly engine keys first (with a budget), then the
/// thickness, then the parameters, so that the free ones are tuned for the chosen taps.
pub fn axes(file: &MethodFile, start: &FileConfig, budgeted: bool) -> Vec<Axis<FileChoice>> {
    let ao = &start.ao;
    let engine = |key: &str, at: Choice, grid: Vec<Choice>| -> Axis<FileChoice> {
        Axis::new(
            key,
            FileChoice::Engine(at),
            grid.into_iter().map(FileChoice::Engine),
        )
    };
    let mut axes = Vec::new();
    if budgeted {
        let spends_samples = file
            .counts
            .iter()
            .any(|c| matches!(c, CountRule::SamplesPer(_)));
        if spends_samples {
            axes.push(engine(
                "samples",
                Choice::Samples(ao.samples),
                SAMPLES.map(Choice::Samples).to_vec(),
            ));
        }
        axes.push(engine(
            "resolution",
            Choice::Resolution(ao.resolution),
            AoResolution::ALL.map(Choice::Resolution).to_vec(),
        ));
        axes.push(engine(
            "guard_band",
            Choice::GuardBand(ao.guard_band),
            vec![
                Choice::GuardBand(GuardBand::Off),
                Choice::GuardBand(GuardBand::Auto),
            ],
        ));
        if file.reads.normals {
            axes.push(engine(
                "normals",
                Choice::Normals(ao.normals),
                NormalSource::ALL.map(Choice::Normals).to_vec(),
            ));
        }
        if file.reads.second_layer {
            axes.push(engine(
                "layers",
                Choice::Layers(ao.layers),
                vec![Choice::Layers(1), Choice::Layers(2)],
            ));
        }
    }
    let mut thickness = Vec::new();
    if file.reads.thickness {
        thickness.extend(
            THICKNESS_OF_RADIUS
                .iter()
                .map(|f| Choice::Thickness(Some(Thickness::Metres(f * ao.radius)))),
        );
    }
    // The back-face pass costs a depth pass of the scene.
    if budgeted && file.reads.back_faces {
        thickness.push(Choice::Thickness(Some(Thickness::Backface)));
    }
    if !thickness.is_empty() {
        axes.push(engine(
            "thickness",
            Choice::Thickness(ao.thickness),
            thickness,
        ));
    }
    for (i, p) in file.parameters.iter().enumerate() {
        let values = grid(p.min, p.max, PARAMETER_STEPS);
        let axis = Axis::new(
            &p.name,
            FileChoice::Parameter(i, start.values[i]),
            values.into_iter().map(|v| FileChoice::Parameter(i, v)),
        );
        if axis.values.len() > 1 {
            axes.push(axis);
        }
    }
    axes
}

/// The parameters' values and the costly engine keys: configurations with the same signature run
/// the same shader on the same passes. A parameter may set a loop's length, so unlike the engine's
/// free keys each value of one is timed.
pub fn cost_signature(c: &FileConfig) -> String {
    format!(
        "{:?} {:?}",
        super::space::cost_signature(&c.ao),
        c.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    )
}

#[cfg(test)]
mod tests {
    use crate::scene::method_file::{MethodParameter, MethodReads};
    use crate::tools::tune::file_space::*;
    use crate::tools::tune::search::search;
    use std::path::PathBuf;

    fn file(reads: MethodReads, counts: [CountRule; 2], params: &[(f32, f32, f32)]) -> MethodFile {
        MethodFile {
            path: PathBuf::from("my.toml"),
            name: "mine".into(),
            shader: PathBuf::from("my.frag"),
            reads,
            counts,
            parameters: params
                .iter()
                .enumerate()
                .map(|(i, &(default, min, max))| MethodParameter {
                    name: format!("P{i}"),
                    default,
                    min,
                    max,
                    value: default,
                })
                .collect(),
            recommended: crate::scene::ao_defaults::PLAIN,
        }
    }

    #[test]
    fn the_grid_spans_the_range_with_exact_ends() {
        assert_eq!(grid(0.0, 1.0, 4), [0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(grid(0.1, 0.7, 3).first(), Some(&0.1));
        assert_eq!(grid(0.1, 0.7, 3).last(), Some(&0.7));
        assert_eq!(grid(2.0, 2.0, 8), [2.0]);
        let g = grid(-3.0, 5.0, PARAMETER_STEPS);
        assert_eq!(g.len(), PARAMETER_STEPS as usize + 1);
        assert!(g.windows(2).all(|w| w[0] < w[1]), "{g:?}");
    }

    #[test]
    fn axes_hold_each_parameter_from_its_default_and_costly_keys_need_a_budget() {
        let reads = MethodReads {
            normals: true,
            thickness: true,
            ..MethodReads::default()
        };
        let counts = [CountRule::Fixed(4), CountRule::SamplesPer(4)];
        let f = file(reads, counts, &[(0.17, 0.0, 0.5), (3.0, 3.0, 3.0)]);
        let s = start(&f, &AoSettings::default());
        assert_eq!(s.values, [0.17, 3.0]);
        let free = axes(&f, &s, false);
        let keys: Vec<&str> = free.iter().map(|a| a.key.as_str()).collect();
        // The second parameter's range is a point: nothing to try.
        assert_eq!(keys, ["thickness", "P0"]);
        let p0 = &free[1];
        assert_eq!(p0.values[0], FileChoice::Parameter(0, 0.17));
        assert_eq!(p0.values.len(), PARAMETER_STEPS as usize + 2);
        for v in &p0.values {
            let c = v.apply_to(&s);
            assert!((0.0..=0.5).contains(&c.values[0]), "{c:?}");
            assert_eq!((c.ao, c.values[1]), (s.ao, 3.0));
        }
        let budgeted = axes(&f, &s, true);
        let keys: Vec<&str> = budgeted.iter().map(|a| a.key.as_str()).collect();
        assert_eq!(
            keys,
            [
                "samples",
                "resolution",
                "guard_band",
                "normals",
                "thickness",
                "P0"
            ]
        );
        // Fixed counts spend no sample budget; an unread input is not searched.
        let fixed = file(
            MethodReads::default(),
            [CountRule::Fixed(8), CountRule::Fixed(2)],
            &[(1.0, 0.0, 2.0)],
        );
        let keys: Vec<String> = axes(&fixed, &start(&fixed, &AoSettings::default()), true)
            .into_iter()
            .map(|a| a.key)
            .collect();
        assert_eq!(keys, ["resolution", "guard_band", "P0"]);
        assert_eq!(starts(&fixed, &s, false).len(), 1);
        let two = starts(&f, &s, true);
        assert_eq!(two.len(), 2);
        assert_eq!(two[1].ao.normals, NormalSource::Geometric);
        assert_eq!(two[1].values, s.values);
    }

    /// The search over a method file's axes finds the grid value nearest a known optimum, and a
    /// parameter's value changes the cost signature.
    #[test]
    fn descent_over_parameters_finds_the_nearest_grid_value() {
        let f = file(
            MethodReads::default(),
            [CountRule::Fixed(4), CountRule::Fixed(1)],
            &[(0.1, 0.0, 2.0), (5.0, 0.0, 8.0)],
        );
        let s = start(&f, &AoSettings::default());
        let space = axes(&f, &s, false);
        let found = search(std::slice::from_ref(&s), &space, 3, |c: &FileConfig| {
            let (a, b) = (c.values[0] as f64, c.values[1] as f64);
            Ok(Some(-(a - 1.3).powi(2) - (b - 2.0).powi(2)))
        })
        .unwrap();
        // Grid of 0..2 in steps of 0.25: 1.25 is nearest 1.3; of 0..8 in steps of 1: 2.
        assert_eq!(found.best.values, [1.25, 2.0]);
        assert_eq!(found.best.ao, s.ao);
        assert_ne!(cost_signature(&s), cost_signature(&found.best));
        assert_eq!(
            with_values(&f, &found.best.values).defines()[0].1,
            crate::gl::preprocess::glsl_float(1.25)
        );
    }
}
