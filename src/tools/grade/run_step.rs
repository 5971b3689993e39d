//! `opengl3d grade-step STEP` (hidden), the child: stages the graded file, builds the rig, grades the
//! one step and prints its report as one JSON line on stdout. Each step uses the project's passes
//! for everything but the graded file.

use super::args::{GradeStepArgs, Level, Step};
use super::interface::{self, Written};
use super::picture;
use super::report::{PartReport, StepReport};
use super::rig::{build_rig, Rig, Subject, Verdict};
use super::say::say;
use super::staging::stage;
use super::steps;
use super::submission;
use crate::ao::AoSettings;
use crate::gl::ProgramObject;
use crate::i18n::Text;
use crate::math::Camera;
use crate::res::project_res_dir;
use crate::tools::lesson;
use anyhow::Result;
use std::path::Path;

/// The student's program that `step` grades.
fn program_of(rig: &Rig, step: Step) -> &ProgramObject {
    let s = &rig.student;
    match step {
        Step::Restore => &s.prog_restore_depth,
        Step::DownSampling => &s.prog_down_sampling,
        Step::Simple => &s.prog_simple,
        Step::Sao => &s.prog_sao,
        Step::Blur => &s.prog_blur,
    }
}

/// Grades one step; `subject.work_dir` holds a copy of the graded file. `begun`: the lesson step that
/// has written only the start of the file (`sao.frag` in lessons 6–7) and what that start reads, so
/// it is checked for building, keeping its interface and reading those, and for that lesson's debug
/// output instead of the occlusion. `at_lesson`: the lesson step graded (`--lesson N`), for a file
/// that a later step finishes (`sao.frag`'s smoothing); `None` grades every file finished.
fn grade(
    step: Step,
    subject: &Subject,
    project_res: &Path,
    begun: Option<(u32, lesson::Begun)>,
    at_lesson: Option<u32>,
    level: Level,
) -> Verdict {
    let camera = Camera::default();
    let params = AoSettings::default();
    let main_size = match step {
        Step::Restore | Step::DownSampling => steps::MAIN_SIZE,
        Step::Simple => (2 * steps::SIMPLE_SIZE.0, 2 * steps::SIMPLE_SIZE.1),
        Step::Sao => (2 * steps::SAO_SIZE.0, 2 * steps::SAO_SIZE.1),
        Step::Blur => (2 * steps::BLUR_SIZE.0, 2 * steps::BLUR_SIZE.1),
    };
    let rig = match build_rig(subject, project_res, main_size, &camera, &params) {
        Ok(r) => r,
        Err(v) => return v,
    };
    // What the program declares must be where the engine sets it, before anything is rendered.
    let program = program_of(&rig, step).id();
    if let Some(problem) = interface::check(&rig.gl, program, step.file(), Written::Begun(&[])) {
        return Verdict::fail(problem);
    }
    // What it leaves unread is told after rendering: a begun file's only when its debug output is
    // wrong (a checkpoint line left out makes the whole start unread, and then that is the message),
    // and a complete file's unless its output is Inf or NaN (a shader writing a constant Inf reads
    // none of its inputs: the compiler drops them, and the unread input is not the cause).
    let unread = match begun {
        Some(_) => None,
        None => interface::check(&rig.gl, program, step.file(), Written::Complete),
    };
    let mut v = match (step, begun) {
        (_, Some((lesson, b))) => {
            let unread = interface::check(&rig.gl, program, step.file(), Written::Begun(b.reads));
            steps::sao_checkpoint(&rig, lesson, project_res, &params, unread)
        }
        (Step::Restore, None) => steps::restore(&rig, &camera),
        (Step::DownSampling, None) => steps::down_sampling(&rig),
        (Step::Simple, None) => steps::simple(&rig),
        (Step::Sao, None) => steps::sao(&rig, &params, at_lesson, level),
        (Step::Blur, None) => steps::blur(&rig, &params),
    };
    if let Some(problem) = unread {
        let nonfinite = v.metrics.get(super::rig::NONFINITE_METRIC).copied();
        if v.passed || !nonfinite.is_some_and(|f| f > super::tol::NONFINITE_OVER_UNREAD) {
            return Verdict::fail(problem);
        }
    }
    // A GL error means some call of the step did nothing, so its measurements may not be what they
    // claim: say so with the verdict.
    if let Some(e) = crate::gl::take_error(&rig.gl) {
        let note = say!("grade.verdict.gl_error_note", error = e);
        v.message = joined(&v.message, &note);
    }
    v
}

/// `message` followed by `note` (" (note: …)"), in each language.
fn joined(message: &Text, note: &Text) -> Text {
    Text {
        en: format!("{}{}", message.en, note.en),
        localised: message
            .localised
            .as_ref()
            .zip(note.localised.as_ref())
            .map(|(m, n)| format!("{m}{n}")),
    }
}

/// Puts `message` into `report`: English in `message`, the chosen language in `message_localised`.
fn set_message(report: &mut StepReport, message: Text) {
    report.message = message.en;
    report.message_localised = message.localised;
}

/// Renders the mutation-testing probe and adds what it found to the report's metrics; a probe the
/// grader cannot run is said with the verdict (and leaves no metric, so the mutant is not counted).
fn add_probe(step: Step, subject: &Subject, project: &Path, report: &mut StepReport) {
    use super::mutation_probe::{probe, Probe};
    use super::mutation_score::{PROBE_BUILDS_METRIC, PROBE_LISTING_METRIC, PROBE_METRIC};
    match probe(step, subject, project) {
        Ok(Probe::Difference { tolerance, listing }) => {
            report.metrics.insert(PROBE_METRIC.into(), tolerance);
            report.metrics.insert(PROBE_LISTING_METRIC.into(), listing);
        }
        Ok(Probe::DoesNotBuild) => {
            report.metrics.insert(PROBE_BUILDS_METRIC.into(), 0.0);
        }
        Err(e) => report.message = format!("{} (grader error in the probe: {e:#})", report.message),
    }
}

/// The child: grades one step and prints its report as one JSON line on stdout.
pub fn run_step(student: Option<&Path>, args: &GradeStepArgs) -> Result<()> {
    let project = project_res_dir();
    let step = args.step;
    // Without --res the project grades its own files; with it, only the student's count.
    let file = match student {
        None => project.join(step.file()),
        Some(dir) => match submission::find(dir, step) {
            Ok(file) => file,
            Err(reason) => {
                crate::outln!(
                    "{}",
                    serde_json::to_string(&StepReport::not_submitted(step, &reason))?
                );
                return Ok(());
            }
        },
    };
    let mut report = StepReport::failed(step, String::new());
    report.level = args.level;
    match stage(&file, &args.work) {
        Err(e) => {
            // Already names the student's file and what is wrong with it (size, encoding, include).
            let error = format!("{e:#}");
            set_message(
                &mut report,
                say!("grade.verdict.build_refused", error = error),
            );
        }
        Ok(_) => {
            let shown = file.parent().unwrap_or(Path::new("")).to_path_buf();
            let subject = Subject {
                work_dir: &args.work,
                shown_dir: &shown,
            };
            let begun = args.lesson.and_then(|n| {
                lesson::begun_at_step(n)
                    .filter(|b| b.file == step.file())
                    .map(|b| (n, b))
            });
            let v = grade(step, &subject, &project, begun, args.lesson, args.level);
            report.passed = v.passed;
            report.metrics = v.metrics;
            report.parts = v
                .parts
                .into_iter()
                .map(|p| PartReport {
                    part: p.id.to_string(),
                    passed: p.passed,
                    message: p.message.en,
                    message_localised: p.message.localised,
                    erratum: p.erratum.map(|n| steps::erratum_name(n, "en")),
                })
                .collect();
            let mut message = v.message;
            if let Some(out) = &args.out {
                if !v.panels.is_empty() {
                    // The verdict is the shader's; pictures that cannot be written are the
                    // grader's problem, said with the verdict (the child's stderr is not shown).
                    if let Err(e) = picture::write(out, step.name(), &v.panels) {
                        let error = format!("{e:#}");
                        let note = say!("grade.verdict.pictures_not_written", error = error);
                        message = joined(&message, &note);
                    }
                }
            }
            set_message(&mut report, message);
            if args.probe {
                add_probe(step, &subject, &project, &mut report);
            }
        }
    }
    // The verdict stands whatever happens to the copy: a folder left behind is only reported.
    if let Err(e) = std::fs::remove_dir_all(&args.work) {
        if e.kind() != std::io::ErrorKind::NotFound {
            eprintln!("warning: cannot remove {}: {e}", args.work.display());
        }
    }
    crate::outln!("{}", serde_json::to_string(&report)?);
    Ok(())
}
