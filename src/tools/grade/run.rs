//! `opengl3d grade`: grades the selected steps of one folder (`--res DIR`, or the project's own
//! files) and prints their verdicts, or a whole class (`--class DIR`, see `class`).

use super::args::{selected_steps, GradeArgs};
use super::class;
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
    let points = args.points.as_deref().map(Points::parse).transpose()?;
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
        if args.json {
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
    if let Some(out) = &args.out {
        std::fs::create_dir_all(out)
            .with_context(|| format!("cannot create folder {}", out.display()))?;
    }
    if !args.json {
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
        pictures: args.out.as_deref(),
        timeout,
        lesson: super::args::lesson_of(args),
        level: args.level,
    };
    let reports = student::grade(&grading, student, &steps)?;
    let passed = reports.iter().all(|r| r.passed);
    if args.verbose {
        report::print_metrics(&reports);
    }
    if args.json {
        crate::outln!("{}", report::to_json(&reports, points.as_ref())?);
    } else {
        report::print_text(&reports, args.out.as_deref());
    }
    Ok(if passed { 0 } else { 1 })
}
