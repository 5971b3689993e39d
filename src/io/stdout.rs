//! The commands' results on standard output. A reader that goes away (`| head -c1`, `| true`) closes
//! the pipe: the next write fails with EPIPE (Rust ignores SIGPIPE), and `println!` would panic.
//! Lines written through [`line`] (the `outln!` macro) stop quietly instead, so the command finishes
//! its work (files written, the grader's verdict) and exits with its own status. Any other write
//! error (a full disk behind `>`) is reported once on stderr, output stops there too, and a command
//! that otherwise succeeded exits with status 1 ([`failed`]).

use std::fmt;
use std::io::{ErrorKind, Write as _};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once a write to stdout has failed: later lines are dropped.
static CLOSED: AtomicBool = AtomicBool::new(false);
/// Set when that failure was not a closed pipe.
static FAILED: AtomicBool = AtomicBool::new(false);

/// Writes one line (`args` and a newline) to stdout, or nothing once stdout is closed.
pub fn line(args: fmt::Arguments) {
    if CLOSED.load(Ordering::Relaxed) {
        return;
    }
    let mut out = std::io::stdout().lock();
    let result = out.write_fmt(args).and_then(|_| out.write_all(b"\n"));
    // Stdout is line-buffered; flushing here makes the error show at this line, not at exit.
    if let Err(e) = result.and_then(|_| out.flush()) {
        if !CLOSED.swap(true, Ordering::Relaxed) && e.kind() != ErrorKind::BrokenPipe {
            FAILED.store(true, Ordering::Relaxed);
            let error = e.to_string();
            eprintln!("{}", rust_i18n::t!("cli.stdout_error", error = error));
        }
    }
}

/// Whether a write to stdout has failed (a closed pipe or another error).
pub fn closed() -> bool {
    CLOSED.load(Ordering::Relaxed)
}

/// Whether a write to stdout has failed for another reason than a closed pipe: output was lost.
pub fn failed() -> bool {
    FAILED.load(Ordering::Relaxed)
}

/// `println!` for a command's results: a closed stdout stops the output without a panic.
#[macro_export]
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::io::stdout::line(format_args!($($arg)*))
    };
}
