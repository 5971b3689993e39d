//! `opengl3d grade-step STEP` (hidden), the child: stages the graded file, builds the rig, grades the
//! one step and prints its report as one JSON line on stdout. Each step uses the project's passes
//! for everything but the graded file.

use super::args::{GradeStepArgs, Step};
use super::picture;
use super::report::StepReport;
use super::rig::{build_rig, Subject, Verdict};
use super::staging::stage;
use super::steps;
use super::submission;
use crate::ao::AoSettings;
use crate::math::Camera;
use crate::res::project_res_dir;
use anyhow::Result;
use std::path::Path;

/// Grades one step; `subject.work_dir` holds a copy of the graded file.
fn grade(step: Step, subject: &Subject, project_res: &Path) -> Verdict {
    let camera = Camera::default();
    let params = AoSettings::default();
    let main_size = match step {
        Step::Restore | Step::DownSampling => steps::MAIN_SIZE,
        Step::Sao => (2 * steps::SAO_SIZE, 2 * steps::SAO_SIZE),
        Step::Blur => (2 * steps::BLUR_SIZE, 2 * steps::BLUR_SIZE),
    };
    let rig = match build_rig(subject, project_res, main_size, &camera, &params) {
        Ok(r) => r,
        Err(v) => return v,
    };
    let mut v = match step {
        Step::Restore => steps::restore(&rig, &camera),
        Step::DownSampling => steps::down_sampling(&rig),
        Step::Sao => steps::sao(&rig, &params),
        Step::Blur => steps::blur(&rig, &params),
    };
    // A GL error means some call of the step did nothing, so its measurements may not be what they
    // claim: say so with the verdict.
    if let Some(e) = crate::gl::take_error(&rig.gl) {
        v.message = format!("{} (note: OpenGL reported {e} while grading)", v.message);
    }
    v
}

/// Renders the mutation-testing probe and adds what it found to the report's metrics; a probe the
/// grader cannot run is said with the verdict (and leaves no metric, so the mutant is not counted).
fn add_probe(step: Step, subject: &Subject, project: &Path, report: &mut StepReport) {
    use super::mutation_probe::{probe, Probe};
    use super::mutation_score::{PROBE_BUILDS_METRIC, PROBE_METRIC};
    match probe(step, subject, project) {
        Ok(Probe::Difference(d)) => {
            report.metrics.insert(PROBE_METRIC.into(), d);
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
                println!(
                    "{}",
                    serde_json::to_string(&StepReport::not_submitted(step, &reason))?
                );
                return Ok(());
            }
        },
    };
    let mut report = StepReport::failed(step, String::new());
    match stage(&file, &args.work) {
        Err(e) => report.message = format!("{e:#}"),
        Ok(_) => {
            let shown = file.parent().unwrap_or(Path::new("")).to_path_buf();
            let subject = Subject {
                work_dir: &args.work,
                shown_dir: &shown,
            };
            let v = grade(step, &subject, &project);
            report.passed = v.passed;
            report.message = v.message;
            report.metrics = v.metrics;
            if args.probe {
                add_probe(step, &subject, &project, &mut report);
            }
            if let Some(out) = &args.out {
                if !v.panels.is_empty() {
                    // The verdict is the shader's; pictures that cannot be written are the
                    // grader's problem, said with the verdict (the child's stderr is not shown).
                    if let Err(e) = picture::write(out, step.name(), &v.panels) {
                        report.message =
                            format!("{} (pictures not written: {e:#})", report.message);
                    }
                }
            }
        }
    }
    // The verdict stands whatever happens to the copy: a folder left behind is only reported.
    if let Err(e) = std::fs::remove_dir_all(&args.work) {
        if e.kind() != std::io::ErrorKind::NotFound {
            eprintln!("warning: cannot remove {}: {e}", args.work.display());
        }
    }
    println!("{}", serde_json::to_string(&report)?);
    Ok(())
}
