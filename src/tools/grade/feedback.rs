//! One student's feedback page: their verdicts, the grader's messages and the heat maps of the
//! steps that failed, in the class's language, as one self-contained HTML file a teacher can hand
//! out (`grade --class` writes one per student; `grade --out` and `--format classroom50` write
//! `feedback.html` beside the pictures, which Classroom 50 can attach to the submission).

use super::points::Points;
use super::report::StepReport;
use rust_i18n::t;

/// `text` escaped for HTML text and quoted attribute values.
pub fn html(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&#39;"),
            c => s.push(c),
        }
    }
    s
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em;max-width:60em}\
section{border:1px solid #999;margin:.8em 0;padding:.5em .8em}\
.pass{border-left:.6em solid #3a3}.fail{border-left:.6em solid #c33}.missing{border-left:.6em solid #999}\
.why{white-space:pre-wrap;overflow-wrap:anywhere}figure{display:inline-block;margin:.3em .8em .3em 0}\
figure img{width:240px;image-rendering:pixelated;border:1px solid #666}figcaption{font-size:.8em}";

/// One graded step on the page: its report and, when it failed and left pictures, the path of its
/// pictures relative to the page without the `-difference.png` ending.
pub struct Entry<'a> {
    pub report: &'a StepReport,
    pub pictures: Option<String>,
}

/// The page for the student `name` (`None`: the student of this checkout), with points when
/// `points` is given and the grading level when known.
pub fn page(name: Option<&str>, entries: &[Entry], points: Option<&Points>) -> String {
    let title = match name {
        Some(n) => t!("feedback.title_named", name = n).into_owned(),
        None => t!("feedback.title").into_owned(),
    };
    let passed = entries.iter().filter(|e| e.report.passed).count();
    let mut h = format!(
        "<!DOCTYPE html>\n<html lang=\"{lang}\">\n<head>\n<meta charset=\"utf-8\">\n<title>{t}</title>\n\
         <style>{STYLE}</style>\n</head>\n<body>\n<h1>{t}</h1>\n<p>{summary}</p>\n",
        lang = crate::i18n::current().code(),
        t = html(&title),
        summary = html(&t!(
            "feedback.summary",
            passed = passed,
            count = entries.len()
        )),
    );
    if let Some(first) = entries.first() {
        h.push_str(&format!(
            "<p>{}</p>\n",
            html(&t!("grade.level", level = first.report.level.name()))
        ));
    }
    if let Some(p) = points {
        let earned: u32 = entries.iter().map(|e| e.report.earned_points(p)).sum();
        let max: u32 = entries.iter().map(|e| e.report.max_points(p)).sum();
        h.push_str(&format!(
            "<p><b>{}</b></p>\n",
            html(&t!("feedback.points", earned = earned, max = max))
        ));
    }
    for e in entries {
        let r = e.report;
        let (class, verdict) = if r.passed {
            ("pass", t!("grade.pass"))
        } else if r.submitted {
            ("fail", t!("grade.fail"))
        } else {
            ("missing", t!("class.html_not_submitted"))
        };
        let worth = points
            .map(|p| {
                format!(
                    " ({})",
                    t!(
                        "feedback.step_points",
                        earned = r.earned_points(p),
                        max = r.max_points(p)
                    )
                )
            })
            .unwrap_or_default();
        h.push_str(&format!(
            "<section class=\"{class}\">\n<h2>{verdict}: {file}{worth}</h2>\n<p class=\"why\">{why}</p>\n",
            verdict = html(&verdict),
            file = html(&r.file),
            worth = html(&worth),
            why = html(r.shown_message()),
        ));
        if !r.parts.is_empty() {
            h.push_str("<ul>\n");
            for part in &r.parts {
                let mark = if part.passed {
                    t!("grade.pass")
                } else {
                    t!("grade.fail")
                };
                let key = format!("grade.part.{}", part.part);
                let title = t!(&key);
                let worth = points
                    .map(|p| {
                        let max = p.of_part(&part.part);
                        let earned = if part.passed { max } else { 0 };
                        format!(
                            " ({})",
                            t!("feedback.step_points", earned = earned, max = max)
                        )
                    })
                    .unwrap_or_default();
                h.push_str(&format!(
                    "<li><b>{}</b>: {}{}<br><span class=\"why\">{}</span></li>\n",
                    html(&mark),
                    html(&title),
                    html(&worth),
                    html(part.shown_message())
                ));
            }
            h.push_str("</ul>\n");
        }
        if let Some(stem) = &e.pictures {
            for (kind, label) in [
                ("difference", t!("feedback.heat_map")),
                ("expected", t!("class.html_expected")),
                ("actual", t!("class.html_actual")),
            ] {
                let src = html(&format!("{stem}-{kind}.png"));
                h.push_str(&format!(
                    "<figure><a href=\"{src}\"><img src=\"{src}\" alt=\"{alt}\"></a>\
                     <figcaption>{label}</figcaption></figure>\n",
                    alt = html(&format!("{}: {label}", r.file)),
                    label = html(&label),
                ));
            }
            h.push_str(&format!(
                "<p><small>{}</small></p>\n",
                html(&t!("class.html_legend"))
            ));
        }
        h.push_str("</section>\n");
    }
    h.push_str("</body>\n</html>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tools::grade::Step;

    #[test]
    fn a_page_escapes_what_the_student_wrote_and_links_only_failing_pictures() {
        let mut failed = StepReport::failed(Step::Sao, "<script>x</script> & more".into());
        failed.submitted = true;
        let mut passed = StepReport::failed(Step::Blur, "fine".into());
        passed.passed = true;
        let entries = [
            Entry {
                report: &failed,
                pictures: Some("sao".into()),
            },
            Entry {
                report: &passed,
                pictures: None,
            },
        ];
        let h = page(Some("a\"b"), &entries, Some(&Points::default()));
        assert!(!h.contains("<script>"), "{h}");
        assert!(h.contains("&lt;script&gt;x&lt;/script&gt; &amp; more"));
        assert!(h.contains("a&quot;b"));
        assert!(h.contains("src=\"sao-difference.png\""));
        assert!(!h.contains("blur-difference.png"));
        assert!(h.contains("10/60") || h.contains("10 / 60"), "{h}");
    }
}
