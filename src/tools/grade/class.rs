//! `opengl3d grade --class DIR`: every folder in DIR is one student, graded exactly as
//! `grade --res FOLDER` grades it (each step in its own child process with its time and memory
//! limits), and so is every `.zip` (unpacked with limits into a private folder, see `unzip`);
//! several students at once (`--jobs`), then one report for the class: results.csv, report.html
//! (with the failing steps' heat maps, kept in `pictures/`) and junit.xml in the `--out` folder. A
//! student whose shaders crash or hang, or whose archive is refused, fails with the reason; the
//! class goes on.

use super::args::{GradeArgs, Step};
use super::class_report::{self, StudentResult};
use super::feedback;
use super::points::Points;
use super::report::StepReport;
use super::student::{self, Grading};
use super::unzip;
use crate::i18n::Text;
use anyhow::{anyhow, bail, Context as _, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use rust_i18n::t;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The report folder when `--out` is not given.
const DEFAULT_REPORT: &str = "grade-report";
/// The report's folder for the failing steps' pictures, one folder per student.
const PICTURES: &str = "pictures";
/// The pictures a step may leave (see `picture::write`).
const KINDS: [&str; 3] = ["difference", "expected", "actual"];

/// Where a student's shaders are.
enum Source {
    Folder(PathBuf),
    /// A `.zip`, unpacked into a private folder when the student is graded.
    Zip(PathBuf),
}

/// One student: the name (the folder's, or the archive's without `.zip`), where the shaders are,
/// and the report's subfolder for their pictures.
struct Student {
    name: String,
    source: Source,
    pictures: String,
}

fn is_zip(name: &str) -> bool {
    name.len() > 4 && name[name.len() - 4..].eq_ignore_ascii_case(".zip")
}

/// The student folders and `.zip` files in `dir`, sorted by name. Hidden entries (`.git`) are not
/// students; any other file is skipped with a note. A `.zip` named like a folder beside it keeps
/// its `.zip` in its name, so both are graded and told apart.
fn students(dir: &Path) -> Result<Vec<Student>> {
    let shown = dir.display();
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => bail!("{}", t!("class.not_folder", dir = shown)),
        Err(e) => bail!("{} ({e})", t!("class.not_folder", dir = shown)),
    }
    let entries = std::fs::read_dir(dir).with_context(|| format!("cannot read folder {shown}"))?;
    let (mut folders, mut zips) = (Vec::new(), Vec::new());
    for entry in entries {
        let entry = entry.with_context(|| format!("cannot read folder {shown}"))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let path = entry.path();
        // Following links: a class folder made of links to the students' own folders is fine.
        match std::fs::metadata(&path) {
            Ok(m) if m.is_dir() => folders.push((name, Source::Folder(path))),
            Ok(m) if m.is_file() && is_zip(&name) => zips.push((name, path)),
            Ok(_) => eprintln!("{}", t!("class.skipping", path = path.display())),
            Err(e) => eprintln!(
                "{}",
                t!(
                    "class.cannot_read",
                    path = path.display(),
                    error = crate::i18n::io_cause(&e, &rust_i18n::locale())
                )
            ),
        }
    }
    for (name, path) in zips {
        let stem = name[..name.len() - 4].to_string();
        let taken = folders.iter().any(|(n, _)| *n == stem);
        folders.push((if taken { name } else { stem }, Source::Zip(path)));
    }
    if folders.is_empty() {
        bail!("{}", t!("class.no_students", dir = shown));
    }
    folders.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(folders
        .into_iter()
        .enumerate()
        .map(|(i, (name, source))| Student {
            pictures: format!("{PICTURES}/{:03}-{}", i + 1, file_safe(&name)),
            name,
            source,
        })
        .collect())
}

/// `name` as part of a file name and a link: ASCII letters, digits, `-` and `_` kept, anything
/// else `_`, at most 40 characters (the number in front keeps students apart).
fn file_safe(name: &str) -> String {
    name.chars()
        .take(40)
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// A private folder for one unpacked archive, removed whatever happens to the grading.
struct Unpacked(PathBuf);

impl Unpacked {
    fn new() -> std::io::Result<Unpacked> {
        // The pid keeps concurrent graders apart, the counter the archives of one grader.
        static NEXT: AtomicU64 = AtomicU64::new(0);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("opengl3d-class-{}-{n}", std::process::id()));
        // A folder left by an earlier grader of the same pid is stale: start empty.
        if dir.exists() {
            std::fs::remove_dir_all(&dir)?;
        }
        super::interrupt::create_registered(&dir)?;
        Ok(Unpacked(dir))
    }
}

impl Drop for Unpacked {
    fn drop(&mut self) {
        super::interrupt::unregister(&self.0);
        // The verdicts stand whatever happens to the copy: a folder left behind is only reported.
        match std::fs::remove_dir_all(&self.0) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                eprintln!("warning: cannot remove {}: {e}", self.0.display())
            }
            _ => {}
        }
    }
}

/// Removes a picture the report does not show; one that cannot be removed is only reported (the
/// report does not link it).
fn remove_picture(path: &Path) {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            eprintln!("warning: cannot remove {}: {e}", path.display())
        }
        _ => {}
    }
}

/// Every step failed with the same reason (an archive that cannot be unpacked, a grader error).
fn all_failed(steps: &[Step], why: &Text) -> Vec<StepReport> {
    steps
        .iter()
        .map(|&step| StepReport {
            message_localised: why.localised.clone(),
            ..StepReport::failed(step, why.en.clone())
        })
        .collect()
}

/// `text` with the private folder's path replaced by the archive's name, so that messages name
/// what the student handed in.
fn as_submitted(text: &str, private: &Path, archive: &str) -> String {
    text.replace(&*private.display().to_string(), archive)
}

/// Grades one student, the failing steps' pictures into `report/<student.pictures>`; a grader
/// error (no private folder) or an archive that cannot be unpacked fails each step with it.
fn grade_student(g: &Grading, report: &Path, s: &Student, steps: &[Step]) -> StudentResult {
    let start = Instant::now();
    let pictures = report.join(&s.pictures);
    // Pictures of an earlier run in the same report folder would show for a step that now has none.
    for step in steps {
        for kind in KINDS {
            remove_picture(&pictures.join(format!("{}-{kind}.png", step.name())));
        }
    }
    let grading = Grading {
        pictures: Some(&pictures),
        ..*g
    };
    let grader_error = |e: &dyn std::fmt::Display| {
        let e = format!("{e:#}");
        Text::new(|l| t!("class.grader_error", locale = l, error = e).into())
    };
    let reports = match &s.source {
        Source::Folder(dir) => student::grade(&grading, Some(dir), steps)
            .unwrap_or_else(|e| all_failed(steps, &grader_error(&e))),
        Source::Zip(archive) => match Unpacked::new() {
            Err(e) => all_failed(steps, &grader_error(&e)),
            Ok(private) => {
                let shown = archive.file_name().map_or_else(
                    || archive.display().to_string(),
                    |n| n.to_string_lossy().into(),
                );
                match unzip::extract(archive, &private.0, unzip::LIMITS) {
                    Err(why) => all_failed(steps, &why),
                    Ok(dir) => student::grade(&grading, Some(&dir), steps)
                        .unwrap_or_else(|e| all_failed(steps, &grader_error(&e)))
                        .into_iter()
                        .map(|mut r| {
                            r.message = as_submitted(&r.message, &private.0, &shown);
                            r.message_localised = r
                                .message_localised
                                .map(|m| as_submitted(&m, &private.0, &shown));
                            r
                        })
                        .collect(),
                }
            }
        },
    };
    // The report shows the failing steps' pictures only.
    let mut heat_maps = Vec::new();
    for r in &reports {
        let stem = r.step.clone();
        if r.passed {
            for kind in KINDS {
                remove_picture(&pictures.join(format!("{stem}-{kind}.png")));
            }
        }
        let shown = !r.passed && pictures.join(format!("{stem}-difference.png")).is_file();
        heat_maps.push(shown.then(|| format!("{}/{stem}", s.pictures)));
    }
    // Only removes the folder when no picture is left in it (a student without failing pictures).
    match std::fs::remove_dir(&pictures) {
        Err(e)
            if !matches!(
                e.kind(),
                std::io::ErrorKind::NotFound | std::io::ErrorKind::DirectoryNotEmpty
            ) =>
        {
            eprintln!("warning: cannot remove {}: {e}", pictures.display())
        }
        _ => {}
    }
    StudentResult {
        name: s.name.clone(),
        reports,
        heat_maps,
        seconds: start.elapsed().as_secs_f64(),
        page: student_page(s),
    }
}

/// Where a student's feedback page goes in the report (beside the class's table, one folder down).
fn student_page(s: &Student) -> String {
    let stem = s.pictures.rsplit('/').next().unwrap_or(&s.pictures);
    format!("{STUDENT_PAGES}/{stem}.html")
}

/// The folder of the students' feedback pages in the report.
const STUDENT_PAGES: &str = "students";

/// Writes each student's feedback page (its pictures are one folder up from the page).
fn write_student_pages(
    out: &Path,
    results: &[StudentResult],
    points: Option<&Points>,
) -> Result<()> {
    crate::io::create_dir_all(&out.join(STUDENT_PAGES))?;
    for r in results {
        let entries: Vec<feedback::Entry> = r
            .reports
            .iter()
            .zip(&r.heat_maps)
            .map(|(report, stem)| feedback::Entry {
                report,
                pictures: stem.as_ref().map(|s| format!("../{s}")),
            })
            .collect();
        let path = out.join(&r.page);
        std::fs::write(&path, feedback::page(Some(&r.name), &entries, points))
            .map_err(|e| crate::io::io_error(&path, "write", &e))?;
    }
    Ok(())
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
    points: Option<&Points>,
) -> Result<i32> {
    let jobs = match args.jobs {
        Some(0) => bail!("{}", t!("class.jobs_zero")),
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
    crate::outln!(
        "{}",
        t!(
            "class.grading",
            count = students.len(),
            dir = dir.display(),
            steps = steps.len(),
            jobs = jobs
        )
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| anyhow!("cannot start {jobs} grading threads: {e}"))?;
    let grading = Grading {
        exe,
        pictures: None,
        timeout,
        lesson: super::args::lesson_of(args),
        level: args.level,
    };
    let bar = progress_bar(students.len());
    let start = Instant::now();
    let results: Vec<StudentResult> = pool.install(|| {
        students
            .par_iter()
            .map(|s| {
                let r = grade_student(&grading, &out, s, steps);
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
    write(
        &out,
        "results.csv",
        &class_report::to_csv(steps, &results, points),
    )?;
    write(
        &out,
        "report.html",
        &class_report::to_html(&title, steps, &results),
    )?;
    write(
        &out,
        "junit.xml",
        &class_report::to_junit(&title, &results, seconds, points),
    )?;
    write_student_pages(&out, &results, points)?;
    for r in &results {
        let verdict = if r.all_passed() {
            t!("grade.pass")
        } else {
            t!("grade.fail")
        };
        crate::outln!(
            "{}",
            t!(
                "class.student_line",
                verdict = verdict,
                name = r.name,
                passed = r.passed(),
                count = r.reports.len()
            )
        );
    }
    let all = results.iter().filter(|r| r.all_passed()).count();
    let seconds = format!("{seconds:.1}");
    crate::outln!(
        "{}",
        t!(
            "class.summary",
            all = all,
            count = results.len(),
            seconds = seconds,
            dir = out.display()
        )
    );
    Ok(if all == results.len() { 0 } else { 1 })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_and_zips_are_students_named_apart() {
        let d = std::env::temp_dir().join(format!("opengl3d-class-names-{}", std::process::id()));
        for f in ["ada", "zoe", ".git"] {
            std::fs::create_dir_all(d.join(f)).unwrap();
        }
        for f in ["ada.zip", "Bob.ZIP", "notes.txt", ".hidden.zip"] {
            std::fs::write(d.join(f), "x").unwrap();
        }
        let found = students(&d).unwrap();
        let names: Vec<(&str, &str, bool)> = found
            .iter()
            .map(|s| {
                let zip = matches!(s.source, Source::Zip(_));
                (s.name.as_str(), s.pictures.as_str(), zip)
            })
            .collect();
        // Sorted by name (upper case first, as bytes); a zip named like a folder keeps ".zip".
        assert_eq!(
            names,
            [
                ("Bob", "pictures/001-Bob", true),
                ("ada", "pictures/002-ada", false),
                ("ada.zip", "pictures/003-ada_zip", true),
                ("zoe", "pictures/004-zoe", false),
            ]
        );
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn picture_folders_are_plain_ascii() {
        assert_eq!(file_safe("bob, \"<b>\" & 'co'"), "bob____b______co_");
        assert_eq!(file_safe("山田 太郎"), "_____");
        assert_eq!(file_safe(&"x".repeat(100)).len(), 40);
    }
}
