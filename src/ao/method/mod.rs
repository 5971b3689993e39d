//! One file per AO method, each owning its programs, uniform counts and presets, and its row
//! (`MethodRow`: how it is built, what its occlusion shader declares). What a method reads is its
//! row of the layer below, `AoMethod::info`.

pub mod angle_based;
pub mod crytek;
pub mod gtao;
pub mod hbao;
pub mod hemisphere;
pub mod rtao;
pub mod sao;
pub mod sao_lesson;
pub mod vbao;

use super::method_pass::{method_defines, AoMethodPass};
use super::settings::{AoMethod, AoSettings};
pub use crate::ao::method_row::{BuildFn, MethodRow};
use crate::gl::{Gl, ProgramError};
use crate::math::Camera;
use crate::res::ResDirs;
use crate::shader_interface::ProgramInterface;

/// `method`'s row, from its own file (a new `AoMethod` names its file here or nothing compiles).
pub fn row(method: AoMethod) -> &'static MethodRow {
    match method {
        AoMethod::SaoLesson => &sao_lesson::ROW,
        AoMethod::Sao => &sao::ROW,
        AoMethod::Crytek => &crytek::ROW,
        AoMethod::Hemisphere => &hemisphere::ROW,
        AoMethod::Hbao => &hbao::ROW,
        AoMethod::AngleBased => &angle_based::ROW,
        AoMethod::Gtao => &gtao::ROW,
        AoMethod::Vbao => &vbao::ROW,
        AoMethod::Rtao => &rtao::ROW,
    }
}

/// What `method`'s occlusion program declares (checked against the shader by
/// `tests/gl/shader_interface.rs`).
pub fn interface(method: AoMethod) -> ProgramInterface {
    let row = row(method);
    ProgramInterface {
        vert: "simple.vert",
        frag: method.info().shader,
        uniforms: row.uniforms,
        samplers: row.samplers,
    }
}

/// The files of a new built-in method (`NAME`: its module for the Rust file and the shader, its
/// name for the pages), as `docs/architecture.md` lists them.
pub const NEW_METHOD_FILES: [&str; 7] = [
    "src/scene/ao_method.rs",
    "src/scene/ao_defaults.rs",
    "src/ao/method/mod.rs",
    "src/ao/method/NAME.rs",
    "Res/ao/NAME.frag",
    "lessons/methods/NAME.md",
    "lessons/ja/methods/NAME.md",
];

/// Every define any program the engine builds reads, for `camera` and `settings`: the camera
/// planes, the lesson's sample count and spiral turns, and `method_defines` (what a test builds
/// every shader with).
pub fn every_define(camera: &Camera, settings: &AoSettings) -> Vec<(&'static str, String)> {
    let mut all = sao_lesson::sao_defines(camera, settings);
    for d in method_defines(camera) {
        if !all.iter().any(|(name, _)| *name == d.0) {
            all.push(d);
        }
    }
    all
}

/// `method`'s passes.
pub fn build(
    method: AoMethod,
    gl: &Gl,
    res: &ResDirs,
    camera: &Camera,
    settings: &AoSettings,
) -> Result<Box<dyn AoMethodPass>, ProgramError> {
    (row(method).build)(gl, res, camera, settings)
}

#[cfg(test)]
mod tests {
    use super::{interface, NEW_METHOD_FILES};
    use crate::ao::{AoMethod, AoSettings};
    use std::collections::BTreeSet;
    use std::path::Path;

    fn read(path: &str) -> String {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        std::fs::read_to_string(root.join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
    }

    #[test]
    fn every_define_comes_from_the_camera_the_settings_and_the_constants() {
        let camera = crate::math::Camera {
            near: 0.5,
            far: 250.0,
            ..Default::default()
        };
        let settings = AoSettings {
            samples: 13,
            spiral_turns: 5,
            ..Default::default()
        };
        let d = super::every_define(&camera, &settings);
        let value = |name: &str| {
            let found: Vec<&String> = d.iter().filter(|(n, _)| *n == name).map(|v| &v.1).collect();
            assert_eq!(found.len(), 1, "{name} once: {d:?}");
            found[0].parse::<f32>().unwrap()
        };
        assert_eq!(value("CAMERA_NEAR"), 0.5);
        assert_eq!(value("CAMERA_FAR"), 250.0);
        assert_eq!(value("SAO_SAMPLE_COUNT"), 13.0);
        assert_eq!(value("SAO_SPIRAL_TURNS"), 5.0);
        let log = crate::ao::method_pass::LOG_MAX_OFFSET;
        assert_eq!(value("LOG_MAX_OFFSET"), log as f32);
        assert_eq!(value("BLUR_REACH"), crate::ao::blur::BLUR_REACH as f32);
    }

    #[test]
    fn every_row_has_its_files_and_the_architecture_pages_list_them() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for m in AoMethod::ALL {
            let info = m.info();
            let rust = format!("src/ao/method/{}.rs", info.module);
            let shader = format!("Res/{}", info.shader);
            let pages = [
                format!("lessons/methods/{}.md", info.name),
                format!("lessons/ja/methods/{}.md", info.name),
            ];
            for f in [&rust, &shader].into_iter().chain(&pages) {
                assert!(root.join(f).is_file(), "{}: {f} is missing", info.name);
            }
            // The lesson's shader is the course's `Res/sao.frag`; every other lies under `Res/ao/`.
            if info.engine_chain {
                assert_eq!(info.shader, format!("ao/{}.frag", info.module));
            }
            assert_eq!(interface(m).frag, info.shader);
            assert_eq!(AoMethod::from_name(info.name), Some(m));
        }
        // Every file of src/ao/method/ but mod.rs is a row's.
        let on_disk: BTreeSet<String> = std::fs::read_dir(root.join("src/ao/method"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|f| f != "mod.rs")
            .collect();
        let rows: BTreeSet<String> = AoMethod::ALL
            .iter()
            .map(|m| format!("{}.rs", m.info().module))
            .collect();
        assert_eq!(on_disk, rows);
        for page in ["docs/architecture.md", "docs/architecture.ja.md"] {
            let text = read(page);
            // The list of a new method's files: the first path of each item after the heading.
            let heading = text
                .find("\n## Adding a built-in AO method")
                .or_else(|| text.find("\n## 組み込みのAO手法を追加する"))
                .unwrap_or_else(|| panic!("{page} has no section on adding a method"));
            let listed: Vec<&str> = text[heading..]
                .lines()
                .skip_while(|l| !l.starts_with("- "))
                .take_while(|l| l.starts_with("- ") || l.starts_with("  "))
                .filter(|l| l.starts_with("- "))
                .filter_map(|l| l.split('`').nth(1))
                .collect();
            assert_eq!(listed, NEW_METHOD_FILES, "{page}");
            // The folder table names every method's file.
            let modules = text
                .split("`method/<name>.rs`")
                .nth(1)
                .and_then(|rest| rest.split(')').next())
                .unwrap_or_else(|| panic!("{page} lists no method files"));
            for m in AoMethod::ALL {
                let module = format!("`{}`", m.info().module);
                assert!(modules.contains(&module), "{page} does not list {module}");
            }
        }
    }

    /// Depth taps per pixel each method spends for `--samples n`.
    fn taps(n: u32) -> Vec<(&'static str, u32, u32)> {
        let s = AoSettings {
            samples: n,
            ..Default::default()
        };
        let slices = |c: [i32; 2]| (c[0] * 2 * c[1]) as u32;
        vec![
            ("sao", super::sao::counts(&s)[0] as u32, 1),
            ("crytek", super::crytek::counts(&s)[0] as u32, 1),
            ("hemisphere", super::hemisphere::counts(&s)[0] as u32, 1),
            (
                "angle-based",
                super::angle_based::counts(&s)[0] as u32 * 2,
                2,
            ),
            (
                "hbao",
                {
                    let c = super::hbao::counts(&s);
                    (c[0] * c[1]) as u32
                },
                super::hbao::DIRECTIONS as u32,
            ),
            ("gtao", slices(super::gtao::counts(&s)), 4),
            ("vbao", slices(super::vbao::counts(&s)), 4),
        ]
    }

    #[test]
    fn samples_buy_every_method_the_same_taps_within_half_a_unit() {
        for n in 1..=256 {
            for (name, taps, unit) in taps(n) {
                // Below half a unit, the one unit every method needs at least.
                assert!(
                    taps.abs_diff(n) <= unit / 2 || (n <= unit / 2 && taps == unit),
                    "{name}: {taps} taps for --samples {n} (unit {unit})"
                );
            }
        }
        let eleven: Vec<u32> = taps(11).iter().map(|t| t.1).collect();
        assert_eq!(eleven, [11, 11, 11, 12, 12, 12, 12]);
    }
}
