//! `sao.frag` at lesson steps 6 and 7, which write only its start and show it through a temporary
//! debug output: step 6 the normal's y where there is a normal (0 elsewhere), step 7 the mip level
//! of the last tap ÷ 3. The student's output on the SAO step's three scenes is compared with the
//! project's version of that checkpoint (`Res/lesson-checkpoints/N/sao.frag`, the lesson's listings
//! and its debug line) run on the same mip chain. Mistakes the lessons list are named: the normal
//! flipped, the level one step finer or coarser (`logMipOffset`), an output of 0 everywhere (the
//! debug line missing).

use crate::ao::{AoSettings, SaoLesson};
use crate::i18n::Text;
use crate::res::ResDirs;
use crate::tools::grade::measure::matches;
use crate::tools::grade::passes::run_sao_pair;
use crate::tools::grade::picture::{Panel, Shade};
use crate::tools::grade::rig::{float_targets, Rig, Verdict};
use crate::tools::grade::say::say;
use crate::tools::grade::scene::sao_scenes;
use crate::tools::grade::steps::sao::place;
use crate::tools::grade::steps::SAO_SIZE;
use crate::tools::grade::tol;
use anyhow::Result;
use std::collections::BTreeMap;
use std::path::Path;

/// Both sides' debug outputs, all scenes one after the other.
struct Outputs {
    student: Vec<f32>,
    reference: Vec<f32>,
    panels: Vec<Panel>,
}

fn render(rig: &Rig, lesson: u32, project_res: &Path, params: &AoSettings) -> Result<Outputs> {
    let camera = crate::math::Camera::default();
    let checkpoint = project_res
        .join("lesson-checkpoints")
        .join(lesson.to_string());
    let res = ResDirs::only(vec![checkpoint, project_res.to_path_buf()]);
    let (w, h) = rig.student.targets.size();
    let mut reference = SaoLesson::new(&rig.gl, &res, 2 * w, 2 * h, &camera, params)?;
    float_targets(&rig.gl, &mut reference)?;
    let (mut student_all, mut reference_all, mut panels) = (Vec::new(), Vec::new(), Vec::new());
    for scene in sao_scenes(SAO_SIZE) {
        let depth = scene.depth();
        let (r, s) = run_sao_pair(
            &reference,
            &rig.student,
            &rig.meshes,
            &scene.camera,
            &depth,
            params,
        )?;
        let (w, h) = (SAO_SIZE.0 as usize, SAO_SIZE.1 as usize);
        panels.push(Panel::absolute(
            w,
            h,
            r.clone(),
            s.clone(),
            Shade::Occlusion,
            0.5,
        ));
        student_all.extend(s);
        reference_all.extend(r);
    }
    Ok(Outputs {
        student: student_all,
        reference: reference_all,
        panels,
    })
}

/// Grades the debug output of the student's `sao.frag` at lesson step `lesson` (6 or 7). `unread`:
/// what the program does not read of what the lesson's start reads (said when the output is wrong
/// but not 0 everywhere, which is a checkpoint line left out).
pub fn sao_checkpoint(
    rig: &Rig,
    lesson: u32,
    project_res: &Path,
    params: &AoSettings,
    unread: Option<Text>,
) -> Verdict {
    let Outputs {
        student,
        reference,
        panels,
    } = match render(rig, lesson, project_res, params) {
        Ok(o) => o,
        Err(e) => return Verdict::grader_error(&e),
    };
    let allowed = if lesson == 6 {
        tol::CHECKPOINT_NORMAL_ABS
    } else {
        tol::CHECKPOINT_LEVEL_ABS
    };
    // A NaN is a difference too.
    let differs = |s: f32, r: f32| {
        let d = (s - r).abs() as f64;
        d.is_nan() || d > allowed
    };
    let bad = student
        .iter()
        .zip(&reference)
        .filter(|(s, r)| differs(**s, **r))
        .count();
    let n = student.len().max(1);
    let bad_fraction = bad as f64 / n as f64;
    let mut metrics = BTreeMap::new();
    metrics.insert("checkpoint_bad_fraction".into(), bad_fraction);
    let verdict = |passed: bool, message: Text| Verdict {
        passed,
        message,
        metrics: metrics.clone(),
        panels: panels.clone(),
        parts: Vec::new(),
    };
    let complete = crate::tools::lesson::SAO_COMPLETE_STEP;
    if bad_fraction <= tol::CHECKPOINT_BAD_FRACTION {
        let percent = format!("{:.1}", 100.0 * (1.0 - bad_fraction));
        let message = if lesson == 6 {
            say!(
                "grade.verdict.checkpoint_6_pass",
                percent = percent,
                complete = complete
            )
        } else {
            say!(
                "grade.verdict.checkpoint_7_pass",
                percent = percent,
                complete = complete
            )
        };
        return verdict(true, message);
    }
    let predicted =
        |f: &dyn Fn(f32) -> f32| -> Vec<f64> { reference.iter().map(|r| f(*r) as f64).collect() };
    let message = if student.iter().all(|s| *s == 0.0) {
        say!("grade.verdict.checkpoint_zero", lesson = lesson)
    } else if let Some(unread) = unread {
        unread
    } else if lesson == 6 && matches(&student, &predicted(&|r| -r)) {
        say!("grade.verdict.checkpoint_6_flipped")
    } else if lesson == 7 && matches(&student, &predicted(&|r| (r - 1.0 / 3.0).max(0.0))) {
        say!("grade.verdict.checkpoint_7_finer")
    } else if lesson == 7 && matches(&student, &predicted(&|r| (r + 1.0 / 3.0).min(1.0))) {
        say!("grade.verdict.checkpoint_7_coarser")
    } else {
        let i = student
            .iter()
            .zip(&reference)
            .position(|(s, r)| differs(*s, *r))
            .unwrap_or(0);
        let w = SAO_SIZE.0 as usize;
        let per_scene = w * SAO_SIZE.1 as usize;
        let scenes = sao_scenes(SAO_SIZE);
        let scene = scenes[(i / per_scene).min(scenes.len() - 1)].name;
        let (x, y) = ((i % per_scene) % w, (i % per_scene) / w);
        let (got, expected) = (format!("{:.3}", student[i]), format!("{:.3}", reference[i]));
        let percent = format!("{:.1}", 100.0 * bad_fraction);
        say!(
            l => "grade.verdict.checkpoint_differs",
            lesson = lesson,
            percent = percent,
            scene = place(l, scene),
            x = x,
            y = y,
            got = got,
            expected = expected
        )
    };
    verdict(false, message)
}
