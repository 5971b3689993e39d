//! The bench's progress bars (stderr), hidden when the caller asks for quiet runs (tests).

use indicatif::{ProgressBar, ProgressStyle};

/// A bar of `len` steps drawn with `template`, or a hidden one when `show` is false.
pub fn bar(len: u64, template: &str, show: bool) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let b = ProgressBar::new(len);
    // The templates are literals of this crate; a bad one only loses the styling, never the run.
    match ProgressStyle::with_template(template) {
        Ok(s) => b.set_style(s.progress_chars("=> ")),
        Err(e) => eprintln!("progress bar template {template:?}: {e}"),
    }
    b
}
