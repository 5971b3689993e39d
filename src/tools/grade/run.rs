//! `opengl3d grade`: grades the selected steps of one folder (`--res DIR`, or the project's own
//! files) and prints their verdicts, or a whole class (`--class DIR`, see `class`).

use super::args::{selected_steps, GradeArgs, GradeFormat};
use super::class;
use super::classroom50;
use super::feedback;
use super::mutation_score;
use super::points::Points;
use super::report;
use super::student::{self, Grading};
use crate::res::{project_res_dir, ResDirs};
use anyhow::{bail, Context as _, Result};
use rust_i18n::t;
use std::path::Path;
use std::time::Duration;

/// Grades the shaders found through `res`, or every student of `--class`; returns the process exit
/// code (0: every step passed).
pub fn run(_res: &ResDirs, student: Option<&Path>, args: &GradeArgs) -> Result<i32> {
    let steps = selected_steps(args)?;
    let mut points = args.points.as_deref().map(Points::parse).transpose()?;
    let format = match (args.format, args.json) {
        (Some(f), _) => f,
        (None, true) => GradeFormat::Json,
        (None, false) => GradeFormat::Text,
    };
    let json = format == GradeFormat::Json;
    let classroom = format == GradeFormat::Classroom50;
    if classroom && points.is_none() {
        points = Some(Points::default());
    }
    // Classroom 50 attaches files it finds after grading: the pictures and the feedback page go
    // to a folder with a fixed name unless one is given.
    let out = match (&args.out, classroom) {
        (Some(o), _) => Some(o.clone()),
        (None, true) => Some(std::path::PathBuf::from(DEFAULT_CLASSROOM_OUT)),
        (None, false) => None,
    };
    if !(args.timeout > 0.0 && args.timeout.is_finite()) {
        bail!("{}", t!("grade.bad_timeout", value = args.timeout));
    }
    let timeout = Duration::from_secs_f64(args.timeout);
    let exe = std::env::current_exe().context("cannot find the opengl3d executable")?;
    if args.mutation_score {
        if let Some(res) = student {
            bail!("{}", t!("mutation.with_res", dir = res.display()));
        }
        return mutation_score::run(&exe, &steps, args, timeout);
    }
    if args.jobs.is_some() && args.class.is_none() {
        bail!("{}", t!("mutation.jobs_alone"));
    }
    if steps.is_empty() {
        // `--lesson 1`: that step is maths only, and the restore pass is still the stub it starts
        // from, so there is nothing to grade yet (and nothing has failed).
        if json {
            println!("{}", report::to_json_at(&[], points.as_ref(), args.level)?);
        } else {
            let (lesson, first) = (
                args.lesson.unwrap_or(1),
                crate::tools::lesson::FIRST_SHADER_STEP,
            );
            println!(
                "{}",
                t!("grade.nothing_yet", lesson = lesson, first = first)
            );
        }
        return Ok(0);
    }
    if let Some(dir) = &args.class {
        if let Some(res) = student {
            bail!(
                "{}",
                t!(
                    "class.res_and_class",
                    res = res.display(),
                    class = dir.display()
                )
            );
        }
        return class::run(&exe, dir, &steps, args, timeout, points.as_ref());
    }
    if let Some(dir) = student {
        match std::fs::metadata(dir) {
            Ok(m) if m.is_dir() => {}
            Ok(_) => bail!("{}", t!("grade.res_not_folder", dir = dir.display())),
            Err(e) => {
                // The cause in the chosen language: the system's own message is English.
                let cause = crate::i18n::io_cause(&e, &rust_i18n::locale());
                bail!(
                    "{}",
                    t!("grade.res_unusable", dir = dir.display(), cause = cause)
                )
            }
        }
    }
    if let Some(out) = &out {
        std::fs::create_dir_all(out)
            .with_context(|| format!("cannot create folder {}", out.display()))?;
    }
    if !json {
        match student {
            Some(d) => crate::outln!(
                "{}",
                t!("grade.grading_dir", dir = d.display(), count = steps.len())
            ),
            None => crate::outln!(
                "{}",
                t!("grade.grading_project", dir = project_res_dir().display())
            ),
        }
    }
    let grading = Grading {
        exe: &exe,
        pictures: out.as_deref(),
        timeout,
        lesson: super::args::lesson_of(args),
        level: args.level,
    };
    let reports = student::grade(&grading, student, &steps)?;
    let passed = reports.iter().all(|r| r.passed);
    if args.verbose {
        report::print_metrics(&reports);
    }
    if json {
        crate::outln!("{}", report::to_json(&reports, points.as_ref())?);
    } else {
        report::print_text(&reports, out.as_deref());
    }
    if let Some(dir) = &out {
        write_feedback(dir, &reports, points.as_ref())?;
    }
    if classroom {
        let points = points.unwrap_or_default();
        let cwd = std::env::current_dir().context("cannot read the working directory")?;
        let env = |name: &str| std::env::var(name).ok();
        let (result, missing) = classroom50::result(&reports, &points, &env, &cwd);
        if !missing.is_empty() {
            eprintln!(
                "{}",
                t!("classroom.result_missing_env", vars = missing.join(", "))
            );
        }
        let path = classroom50::write(&cwd, &result)?;
        crate::outln!(
            "{}",
            t!(
                "classroom.result_wrote",
                path = path.display(),
                score = result.score,
                max = result.max_score
            )
        );
        // Pass or fail is in result.json: the autograder's exit status says only that it ran.
        return Ok(0);
    }
    Ok(if passed { 0 } else { 1 })
}

/// Where `--format classroom50` puts the pictures and the feedback page without `--out`.
pub const DEFAULT_CLASSROOM_OUT: &str = "grade-report";

/// `dir/feedback.html`: the verdicts with the pictures of the failing steps that `dir` holds.
fn write_feedback(
    dir: &Path,
    reports: &[report::StepReport],
    points: Option<&Points>,
) -> Result<()> {
    let entries: Vec<feedback::Entry> = reports
        .iter()
        .map(|r| feedback::Entry {
            report: r,
            pictures: (!r.passed && dir.join(format!("{}-difference.png", r.step)).is_file())
                .then(|| r.step.clone()),
        })
        .collect();
    let path = dir.join("feedback.html");
    std::fs::write(&path, feedback::page(None, &entries, points))
        .map_err(|e| crate::io::io_error(&path, "write", &e))?;
    Ok(())
}
