//! `grade --format classroom50`: the grader's verdicts as the `result.json` a Classroom 50
//! autograder must leave in the student's checkout (schema `classroom50/result/v1`): the runner's
//! identity fields from its environment, one test per graded unit (a step, or each part of a step
//! that is graded in parts) with its points, and `score` / `max-score` as their sums.

use super::args::Step;
use super::points::Points;
use super::report::StepReport;
use serde::Serialize;
use std::path::Path;

/// The schema name the contract requires, exactly.
pub const SCHEMA: &str = "classroom50/result/v1";

/// The runner's environment variables the result is stamped with (`USERNAME`/`OWNER` and
/// `ASSIGNMENT_TYPE` are stamped by the runner itself and are copied when present).
pub const IDENTITY_VARS: [&str; 6] = [
    "CLASSROOM",
    "ASSIGNMENT",
    "SUBMISSION_TAG",
    "COMMIT_URL",
    "RELEASE_URL",
    "REVIEW_URL",
];

/// One test of the result.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct ResultTest {
    #[serde(rename = "test-name")]
    pub name: String,
    pub passed: bool,
    pub score: u32,
    #[serde(rename = "max-score")]
    pub max_score: u32,
    /// Diagnostic fields (the contract keeps extra fields of a test as they are): the unit's stable
    /// id (`restore`, `sao.smoothing`, …), the graded file, the grader's message in the class's
    /// language and the grading level.
    pub id: String,
    pub file: String,
    pub message: String,
    /// How strictly it was graded (`grade --level`).
    pub level: &'static str,
}

#[derive(Debug, Serialize)]
pub struct ClassroomResult {
    pub schema: &'static str,
    pub classroom: String,
    pub assignment: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub assignment_type: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub owner: Option<String>,
    pub submission: String,
    pub commit: String,
    pub release: String,
    pub review: String,
    pub datetime: String,
    pub graded_at: String,
    pub score: u32,
    #[serde(rename = "max-score")]
    pub max_score: u32,
    pub tests: Vec<ResultTest>,
}

/// A step's title as the class reads it: its name in the chosen language and its file.
fn step_name(step: &str, file: &str) -> String {
    let key = format!("classroom.step_{}", step.replace('-', "_"));
    let title = rust_i18n::t!(&key);
    let title = if title == key {
        step.to_string()
    } else {
        title.into_owned()
    };
    format!("{title} ({file})")
}

/// A sub-step's title: its step's, then the sub-step's own (`SAO (sao.frag): 2×2 smoothing`).
fn part_name(step: &str, file: &str, part: &str) -> String {
    let key = format!("grade.part.{part}");
    let title = rust_i18n::t!(&key);
    let title = if title == key {
        part.to_string()
    } else {
        title.into_owned()
    };
    format!("{}: {title}", step_name(step, file))
}

/// A graded unit: a step graded as one, or one sub-step of a step graded in parts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unit {
    pub id: String,
    pub name: String,
    pub max_score: u32,
}

/// Every unit the grader gives points to, in the lesson's order (what the templates' tests list).
pub fn units(points: &Points) -> Vec<Unit> {
    let mut units = Vec::new();
    for s in Step::ALL {
        let parts = super::points::parts_of(s);
        if parts.is_empty() {
            units.push(Unit {
                id: s.name().to_string(),
                name: step_name(s.name(), s.file()),
                max_score: points.of(s),
            });
        }
        for (id, _) in parts {
            units.push(Unit {
                id: id.to_string(),
                name: part_name(s.name(), s.file(), id),
                max_score: points.of_part(id),
            });
        }
    }
    units
}

/// One test per graded unit of `reports`, worth its points.
pub fn tests(reports: &[StepReport], points: &Points) -> Vec<ResultTest> {
    let mut tests = Vec::new();
    for r in reports {
        if r.parts.is_empty() {
            tests.push(ResultTest {
                name: step_name(&r.step, &r.file),
                passed: r.passed,
                score: r.earned_points(points),
                max_score: r.max_points(points),
                id: r.step.clone(),
                file: r.file.clone(),
                message: r.shown_message().to_string(),
                level: r.level.name(),
            });
        }
        for p in &r.parts {
            let max = points.of_part(&p.part);
            tests.push(ResultTest {
                name: part_name(&r.step, &r.file, &p.part),
                passed: p.passed,
                score: if p.passed { max } else { 0 },
                max_score: max,
                id: p.part.clone(),
                file: r.file.clone(),
                message: p.shown_message().to_string(),
                level: r.level.name(),
            });
        }
    }
    tests
}

/// `seconds` since 1970 (UTC) as `YYYY-MM-DDTHH:MM:SSZ` (days to a civil date: the proleptic
/// Gregorian calendar, counted in 400-year eras).
pub fn utc_timestamp(seconds: u64) -> String {
    let days = (seconds / 86_400) as i64;
    let rem = seconds % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1_460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        rem / 3_600,
        rem % 3_600 / 60,
        rem % 60
    )
}

fn now_utc() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    utc_timestamp(secs)
}

/// The submission instant: the committer date of the checkout's HEAD in UTC (the same on every
/// regrade), or `None` when `dir` is not a git checkout or git is missing.
fn commit_time(dir: &Path) -> Option<String> {
    let out = std::process::Command::new("git")
        .args(["log", "-1", "--format=%ct"])
        .current_dir(dir)
        .stderr(std::process::Stdio::null())
        .output()
        .ok()?;
    let secs: u64 = String::from_utf8(out.stdout).ok()?.trim().parse().ok()?;
    Some(utc_timestamp(secs))
}

/// The result for `reports`, stamped from `env` (a variable's value by name). Missing identity
/// variables are left empty and named in the returned list, so that a run outside the runner says
/// what it lacked instead of pretending.
pub fn result(
    reports: &[StepReport],
    points: &Points,
    env: &dyn Fn(&str) -> Option<String>,
    checkout: &Path,
) -> (ClassroomResult, Vec<&'static str>) {
    let mut missing = Vec::new();
    let mut var = |name: &'static str| {
        let v = env(name).filter(|v| !v.is_empty());
        if v.is_none() {
            missing.push(name);
        }
        v.unwrap_or_default()
    };
    let (classroom, assignment, submission) =
        (var("CLASSROOM"), var("ASSIGNMENT"), var("SUBMISSION_TAG"));
    let (commit, release) = (var("COMMIT_URL"), var("RELEASE_URL"));
    let review = env("REVIEW_URL")
        .filter(|v| !v.is_empty())
        .unwrap_or_else(|| commit.clone());
    let owner = env("OWNER")
        .or_else(|| env("USERNAME"))
        .filter(|v| !v.is_empty());
    let tests = tests(reports, points);
    let now = now_utc();
    let result = ClassroomResult {
        schema: SCHEMA,
        classroom,
        assignment,
        assignment_type: env("ASSIGNMENT_TYPE").filter(|v| !v.is_empty()),
        owner,
        submission,
        commit,
        release,
        review,
        datetime: commit_time(checkout).unwrap_or_else(|| now.clone()),
        graded_at: now,
        score: tests.iter().map(|t| t.score).sum(),
        max_score: tests.iter().map(|t| t.max_score).sum(),
        tests,
    };
    (result, missing)
}

/// Writes `result` as `dir/result.json`.
pub fn write(dir: &Path, result: &ClassroomResult) -> anyhow::Result<std::path::PathBuf> {
    let path = dir.join("result.json");
    let text = serde_json::to_string_pretty(result)?;
    std::fs::write(&path, text + "\n").map_err(|e| crate::io::io_error(&path, "write", &e))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timestamps_are_utc_civil_dates() {
        assert_eq!(utc_timestamp(0), "1970-01-01T00:00:00Z");
        // 2000-02-29 12:34:56 UTC (a leap day of a year divisible by 400).
        assert_eq!(utc_timestamp(951_827_696), "2000-02-29T12:34:56Z");
        // 2026-08-28 00:00:00 UTC.
        assert_eq!(utc_timestamp(1_787_875_200), "2026-08-28T00:00:00Z");
    }
}
