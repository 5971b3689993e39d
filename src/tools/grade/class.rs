//! `opengl3d grade --class DIR`: every folder in DIR is one student, graded exactly as
//! `grade --res FOLDER` grades it (each step in its own child process with its time and memory
//! limits), several students at once (`--jobs`), then one report for the class: results.csv,
//! report.html and junit.xml in the `--out` folder. A student whose shaders crash or hang fails
//! those steps with the reason; the class goes on.

use super::args::{GradeArgs, Step};
use super::class_report::{self, StudentResult};
use super::report::StepReport;
use super::student::{self, Grading};
use anyhow::{anyhow, bail, Context as _, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The report folder when `--out` is not given.
const DEFAULT_REPORT: &str = "grade-report";

/// One student: the folder's name and path.
struct Student {
    name: String,
    dir: PathBuf,
}

/// The student folders in `dir`, sorted by name. Hidden entries (`.git`) are not students; a file
/// (a .zip, say) is skipped with a note, since only unpacked folders are graded.
fn students(dir: &Path) -> Result<Vec<Student>> {
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => bail!("--class {}: not a folder", dir.display()),
        Err(e) => bail!("--class {}: not a folder ({e})", dir.display()),
    }
    let entries =
        std::fs::read_dir(dir).with_context(|| format!("cannot read folder {}", dir.display()))?;
    let mut found = Vec::new();
    for entry in entries {
        let entry = entry.with_context(|| format!("cannot read folder {}", dir.display()))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let path = entry.path();
        // Following links: a class folder made of links to the students' own folders is fine.
        match std::fs::metadata(&path) {
            Ok(m) if m.is_dir() => found.push(Student { name, dir: path }),
            Ok(_) => eprintln!(
                "note: skipping {}: not a folder (unpack a .zip into a folder to grade it)",
                path.display()
            ),
            Err(e) => eprintln!("note: skipping {}: {e}", path.display()),
        }
    }
    if found.is_empty() {
        bail!(
            "--class {}: holds no student folder (each folder in it is one student)",
            dir.display()
        );
    }
    found.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(found)
}

/// Grades one student; a grader error (no private folder) fails each step with it.
fn grade_student(g: &Grading, s: &Student, steps: &[Step]) -> StudentResult {
    let start = Instant::now();
    let reports = student::grade(g, Some(&s.dir), steps).unwrap_or_else(|e| {
        steps
            .iter()
            .map(|&step| StepReport::failed(step, format!("grader error: {e:#}")))
            .collect()
    });
    StudentResult {
        name: s.name.clone(),
        reports,
        seconds: start.elapsed().as_secs_f64(),
    }
}

fn progress_bar(students: usize) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(students as u64), ProgressDrawTarget::stderr());
    // The template is a constant: were it ever rejected, the default style still shows progress.
    if let Ok(style) =
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} students {msg}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// Writes `text` to `dir/name`, naming the file on error.
fn write(dir: &Path, name: &str, text: &str) -> Result<PathBuf> {
    let path = dir.join(name);
    std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(path)
}

/// Grades every student in `dir`; returns the exit code (0: every student passed every step).
pub fn run(
    exe: &Path,
    dir: &Path,
    steps: &[Step],
    args: &GradeArgs,
    timeout: Duration,
) -> Result<i32> {
    let jobs = match args.jobs {
        Some(0) => bail!("--jobs 0: give at least 1"),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let students = students(dir)?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(DEFAULT_REPORT));
    std::fs::create_dir_all(&out)
        .with_context(|| format!("cannot create folder {}", out.display()))?;
    println!(
        "grading {} student(s) in {} ({} step(s), {jobs} at once)",
        students.len(),
        dir.display(),
        steps.len()
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| anyhow!("cannot start {jobs} grading threads: {e}"))?;
    // Each student's pictures would be as many PNGs as steps; the class report does without them.
    let grading = Grading {
        exe,
        pictures: None,
        timeout,
        lesson: super::args::lesson_of(args),
    };
    let bar = progress_bar(students.len());
    let start = Instant::now();
    let results: Vec<StudentResult> = pool.install(|| {
        students
            .par_iter()
            .map(|s| {
                let r = grade_student(&grading, s, steps);
                bar.set_message(s.name.clone());
                bar.inc(1);
                r
            })
            .collect()
    });
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    let title = dir
        .file_name()
        .map_or_else(|| dir.display().to_string(), |n| n.to_string_lossy().into());
    write(&out, "results.csv", &class_report::to_csv(steps, &results))?;
    write(
        &out,
        "report.html",
        &class_report::to_html(&title, steps, &results),
    )?;
    write(
        &out,
        "junit.xml",
        &class_report::to_junit(&title, &results, seconds),
    )?;
    for r in &results {
        println!(
            "{} {}: {}/{} step(s) passed",
            if r.all_passed() { "PASS" } else { "FAIL" },
            r.name,
            r.passed(),
            r.reports.len()
        );
    }
    let all = results.iter().filter(|r| r.all_passed()).count();
    println!(
        "{all} of {} student(s) passed every step ({seconds:.1} s); report in {} (results.csv, report.html, junit.xml)",
        results.len(),
        out.display()
    );
    Ok(if all == results.len() { 0 } else { 1 })
}
