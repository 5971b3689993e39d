//! The class report (`grade --class`): one CSV row per student, one offline HTML table with the
//! reason of each failure, and JUnit XML (a test suite per student, a test case per step) for CI
//! pages such as GitHub Classroom's or GitLab's. Every text from a student (folder names, compiler
//! messages echoing their shaders) is quoted or escaped for the format it lands in.

use super::args::Step;
use super::feedback::html;
use super::points::Points;
use super::report::StepReport;
use rust_i18n::t;

/// One student's verdicts, in the order of the graded steps.
pub struct StudentResult {
    pub name: String,
    pub reports: Vec<StepReport>,
    /// For each report, the path of its pictures relative to the report, without
    /// `-difference.png` (`pictures/001-ada/sao`), when a failing step left them.
    pub heat_maps: Vec<Option<String>>,
    /// Wall time spent grading the student.
    pub seconds: f64,
    /// The student's own feedback page, relative to the report (`students/001-ada.html`).
    pub page: String,
}

impl StudentResult {
    pub fn passed(&self) -> usize {
        self.reports.iter().filter(|r| r.passed).count()
    }
    pub fn all_passed(&self) -> bool {
        self.reports.iter().all(|r| r.passed)
    }
}

/// What became of a step.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Outcome {
    Pass,
    Fail,
    Missing,
}

fn outcome(r: &StepReport) -> Outcome {
    if r.passed {
        Outcome::Pass
    } else if r.submitted {
        Outcome::Fail
    } else {
        Outcome::Missing
    }
}

/// The outcome in the chosen language (PASS, FAIL, not submitted in English).
fn verdict(r: &StepReport) -> String {
    match outcome(r) {
        Outcome::Pass => t!("class.csv_pass"),
        Outcome::Fail => t!("class.csv_fail"),
        Outcome::Missing => t!("class.csv_not_submitted"),
    }
    .into_owned()
}

/// `field` as one CSV field (RFC 4180): quoted, with quotes doubled, when it holds a comma, a
/// quote, a line break or edge spaces.
fn csv_field(field: &str) -> String {
    let needs =
        field.contains([',', '"', '\n', '\r']) || field.starts_with(' ') || field.ends_with(' ');
    if needs {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_string()
    }
}

fn csv_row(fields: &[String]) -> String {
    let mut row = fields
        .iter()
        .map(|f| csv_field(f))
        .collect::<Vec<_>>()
        .join(",");
    row.push_str("\r\n");
    row
}

/// A student's name as a CSV field a spreadsheet shows as text: a folder named `=HYPERLINK(…)`
/// (or starting with `+`, `-`, `@`) would otherwise be run as a formula when the teacher opens the
/// file, so such a name gets a leading `'`, as spreadsheets themselves mark text.
fn csv_name(name: &str) -> String {
    if name.starts_with(['=', '+', '-', '@']) {
        format!("'{name}")
    } else {
        name.to_string()
    }
}

/// results.csv: `student`, one column per step (PASS, FAIL, not submitted), `passed` (how many);
/// with `points`, after each step's column the points it earned (`sao points`), and at the end
/// `points` and `max points`. Headings and verdicts are in the chosen language; the step names
/// are the grader's (`--step` takes them).
pub fn to_csv(steps: &[Step], results: &[StudentResult], points: Option<&Points>) -> String {
    let mut header = vec![t!("class.csv_student").into_owned()];
    for s in steps {
        header.push(s.name().to_string());
        if points.is_some() {
            header.push(t!("class.csv_step_points", step = s.name()).into_owned());
        }
    }
    header.push(t!("class.csv_passed").into_owned());
    if points.is_some() {
        header.extend([
            t!("class.csv_points").into_owned(),
            t!("class.csv_max_points").into_owned(),
        ]);
    }
    header.push(t!("class.csv_level").into_owned());
    let mut csv = csv_row(&header);
    for r in results {
        let mut row = vec![csv_name(&r.name)];
        for s in &r.reports {
            row.push(verdict(s));
            if let Some(p) = points {
                row.push(s.earned_points(p).to_string());
            }
        }
        row.push(r.passed().to_string());
        if let Some(p) = points {
            let (earned, max) = student_points(p, r);
            row.extend([earned.to_string(), max.to_string()]);
        }
        row.push(level_of(r).to_string());
        csv.push_str(&csv_row(&row));
    }
    csv
}

/// How strictly the student was graded (`--level`; every step of a class has the same).
fn level_of(r: &StudentResult) -> &'static str {
    r.reports.first().map_or("", |s| s.level.name())
}

/// What a student earned and could have earned.
fn student_points(points: &Points, r: &StudentResult) -> (u32, u32) {
    r.reports.iter().fold((0, 0), |(e, m), s| {
        (e + s.earned_points(points), m + s.max_points(points))
    })
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}\
th,td{border:1px solid #999;padding:.3em .5em;vertical-align:top;text-align:left}\
td{max-width:28em}.pass{background:#c8f0c8}.fail{background:#f5c0c0}.missing{background:#e4e4e4}\
.why{font-size:.8em;white-space:pre-wrap;overflow-wrap:anywhere}small{font-weight:normal}\
.heat{display:block;margin-top:.3em}.heat img{width:160px;image-rendering:pixelated;border:1px solid #666}";

/// The thumbnail of a failing step's heat map, linked to the full picture, and links to the
/// expected and actual pictures beside it. `stem` is built by the grader from a sanitised name.
fn heat_map(step: &str, stem: &str) -> String {
    let (heat, expected, actual) = (
        html(&format!("{stem}-difference.png")),
        html(&format!("{stem}-expected.png")),
        html(&format!("{stem}-actual.png")),
    );
    format!(
        "<a class=\"heat\" href=\"{heat}\"><img src=\"{heat}\" alt=\"{alt}\"></a>\
         <small><a href=\"{expected}\">{e}</a> · <a href=\"{actual}\">{a}</a></small>",
        alt = html(&t!("class.html_heat_alt", step = step)),
        e = html(&t!("class.html_expected")),
        a = html(&t!("class.html_actual")),
    )
}

/// report.html: one self-contained table (no scripts, nothing from outside the report folder), a
/// row per student, a cell per step with its verdict and message (in the chosen language) and, for
/// a failing step, its heat map's thumbnail linked to the pictures in `pictures/`.
pub fn to_html(title: &str, steps: &[Step], results: &[StudentResult]) -> String {
    let all = results.iter().filter(|r| r.all_passed()).count();
    let mut h = String::new();
    h.push_str(&format!(
        "<!DOCTYPE html>\n<html lang=\"{lang}\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{t}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <h1>{t}</h1>\n<p>{summary}</p>\n<p>{level}</p>\n<p><small>{legend}</small></p>\n\
         <table>\n<thead><tr><th>{student}</th>",
        lang = crate::i18n::current().code(),
        t = html(&t!("class.html_title", title = title)),
        summary = html(&t!("class.html_summary", all = all, count = results.len())),
        legend = html(&t!("class.html_legend")),
        student = html(&t!("class.html_student")),
        level = html(&t!(
            "grade.level",
            level = results.first().map_or("", level_of)
        )),
    ));
    for s in steps {
        h.push_str(&format!(
            "<th>{}<br><small>{}</small></th>",
            html(s.name()),
            html(s.file())
        ));
    }
    h.push_str(&format!(
        "<th>{}</th></tr></thead>\n<tbody>\n",
        html(&t!("class.html_passed"))
    ));
    for r in results {
        h.push_str(&format!(
            "<tr><th><a href=\"{}\">{}</a></th>",
            html(&r.page),
            html(&r.name)
        ));
        for (i, s) in r.reports.iter().enumerate() {
            let (class, shown) = match outcome(s) {
                Outcome::Pass => ("pass", t!("grade.pass")),
                Outcome::Fail => ("fail", t!("grade.fail")),
                Outcome::Missing => ("missing", t!("class.html_not_submitted")),
            };
            let picture = match r.heat_maps.get(i) {
                Some(Some(stem)) => heat_map(&s.step, stem),
                _ => String::new(),
            };
            // The cell's heading already says "not submitted": the line below gives only why.
            let said = t!("grade.not_submitted", reason = "");
            let why = s.shown_message();
            let why = match class {
                "missing" => why.strip_prefix(said.as_ref()).unwrap_or(why),
                _ => why,
            };
            h.push_str(&format!(
                "<td class=\"{class}\"><b>{}</b><div class=\"why\">{}</div>{picture}</td>",
                html(&shown),
                html(why)
            ));
        }
        h.push_str(&format!(
            "<td>{}/{}</td></tr>\n",
            r.passed(),
            r.reports.len()
        ));
    }
    h.push_str("</tbody>\n</table>\n</body>\n</html>\n");
    h
}

/// `text` escaped for XML 1.0 text and attribute values: markup characters and line breaks as
/// references (attribute values keep them), characters XML cannot hold at all (NUL, most control
/// characters) as U+FFFD.
fn xml(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            '\n' => s.push_str("&#10;"),
            '\r' => s.push_str("&#13;"),
            '\t' => s.push_str("&#9;"),
            '\u{0}'..='\u{1f}' | '\u{fffe}' | '\u{ffff}' => s.push('\u{fffd}'),
            c => s.push(c),
        }
    }
    s
}

/// junit.xml: a `<testsuite>` per student, a `<testcase>` per step, a `<failure>` with the reason
/// for each step that did not pass ("not submitted" included), in the chosen language; with
/// `points`, `points` and `max_points` properties on each test case and each suite.
pub fn to_junit(
    title: &str,
    results: &[StudentResult],
    seconds: f64,
    points: Option<&Points>,
) -> String {
    let properties = |earned: u32, max: u32| {
        format!(
            "<properties><property name=\"points\" value=\"{earned}\"/>\
             <property name=\"max_points\" value=\"{max}\"/></properties>"
        )
    };
    let tests: usize = results.iter().map(|r| r.reports.len()).sum();
    let failures: usize = results.iter().map(|r| r.reports.len() - r.passed()).sum();
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    x.push_str(&format!(
        "<testsuites name=\"{}\" tests=\"{tests}\" failures=\"{failures}\" errors=\"0\" \
         time=\"{seconds:.3}\">\n",
        xml(title)
    ));
    for r in results {
        let name = xml(&r.name);
        x.push_str(&format!(
            "  <testsuite name=\"{name}\" tests=\"{}\" failures=\"{}\" errors=\"0\" \
             skipped=\"0\" time=\"{:.3}\">\n",
            r.reports.len(),
            r.reports.len() - r.passed(),
            r.seconds
        ));
        let level = format!("<property name=\"level\" value=\"{}\"/>", xml(level_of(r)));
        match points {
            Some(p) => {
                let (earned, max) = student_points(p, r);
                let props = properties(earned, max)
                    .replace("</properties>", &format!("{level}</properties>"));
                x.push_str(&format!("    {props}\n"));
            }
            None => x.push_str(&format!("    <properties>{level}</properties>\n")),
        }
        for s in &r.reports {
            x.push_str(&format!(
                "    <testcase classname=\"{name}\" name=\"{} ({})\">",
                xml(&s.step),
                xml(&s.file)
            ));
            if let Some(p) = points {
                x.push_str(&properties(s.earned_points(p), s.max_points(p)));
            }
            let message = xml(s.shown_message());
            if s.passed {
                x.push_str(&format!("<system-out>{message}</system-out>"));
            } else {
                let kind = xml(&verdict(s));
                x.push_str(&format!(
                    "<failure type=\"{kind}\" message=\"{message}\">{message}</failure>"
                ));
            }
            x.push_str("</testcase>\n");
        }
        x.push_str("  </testsuite>\n");
    }
    x.push_str("</testsuites>\n");
    x
}
