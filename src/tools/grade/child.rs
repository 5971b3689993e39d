//! One step's child process, seen from the grader: started, given a deadline and killed past it, and
//! what it printed turned into the step's report.

use super::args::Step;
use super::report::StepReport;
use super::say::say;
use crate::i18n::Text;
use std::io::Read;
#[cfg(unix)]
use std::os::unix::process::CommandExt as _;
use std::process::{Command, ExitStatus, Stdio};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// A thread reading one of the child's pipes to its end.
type Drain = JoinHandle<std::io::Result<String>>;

/// A running child: one step.
pub struct Child {
    step: Step,
    child: std::process::Child,
    started: Instant,
    stdout: Option<Drain>,
    stderr: Option<Drain>,
}

impl Drop for Child {
    fn drop(&mut self) {
        // Reaped (or about to be dropped unreaped, as after an error): no longer one to kill.
        super::interrupt::unregister_group(self.child.id());
    }
}

fn drain<R: Read + Send + 'static>(r: Option<R>) -> Option<Drain> {
    r.map(|mut r| {
        std::thread::spawn(move || {
            let mut buf = Vec::new();
            r.read_to_end(&mut buf)?;
            Ok(String::from_utf8_lossy(&buf).into_owned())
        })
    })
}

/// The text a drained pipe gave, or why it could not be read.
fn collect(drain: Option<Drain>, which: &str) -> Result<String, String> {
    match drain.map(JoinHandle::join) {
        None => Ok(String::new()),
        Some(Ok(Ok(text))) => Ok(text),
        Some(Ok(Err(e))) => Err(format!("cannot read the step's {which}: {e}")),
        Some(Err(_)) => Err(format!("the thread reading the step's {which} panicked")),
    }
}

/// The last non-empty line of `s`, trimmed ("" when none).
fn last_line(s: &str) -> &str {
    s.lines()
        .rev()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or("")
}

/// `": line"` for the last line of the child's stderr, or "" when it printed nothing.
fn stderr_tail(err: &str) -> String {
    match last_line(err) {
        "" => String::new(),
        l => format!(": {l}"),
    }
}

/// The verdict the child printed: its last line that starts with `{`. `None` when it printed none;
/// an error when that line is not a verdict.
fn printed_verdict(out: &str) -> Option<Result<StepReport, String>> {
    let line = out
        .lines()
        .rev()
        .find(|l| l.trim_start().starts_with('{'))?;
    Some(
        serde_json::from_str::<StepReport>(line)
            .map_err(|e| format!("the step printed an unreadable verdict ({e}): {line}")),
    )
}

/// The address space a step may use. The child runs a student's shader through Mesa: a huge array
/// or an endless allocation in the compiler must fail the step, not exhaust the machine's memory
/// (and get the grader or other processes killed). The SAO step peaked at 620 MiB of address space
/// on a 2-core machine (the LLVM code, llvmpipe's threads and their stacks, small targets); more
/// cores add a thread stack each, and glibc falls back to a shared heap when a thread's own cannot
/// be reserved, so 2 GiB leaves room while stopping a runaway shader long before 8 GiB fill (all
/// four steps run at once: 8 GiB at most per student; `--class` grades `--jobs` students at once,
/// so only runaway shaders in several of them together reach `--jobs` × 8 GiB).
#[cfg(unix)]
const STEP_ADDRESS_SPACE: u64 = 2 << 30;

/// Runs in the forked child before it becomes `opengl3d grade-step`: only async-signal-safe calls.
/// Limits its memory, and asks the kernel to kill it when the grader dies (else an endless shader
/// would run on after a Ctrl-C).
#[cfg(unix)]
fn confine_step(grader: libc::pid_t) -> std::io::Result<()> {
    let limit = libc::rlimit {
        rlim_cur: STEP_ADDRESS_SPACE as libc::rlim_t,
        rlim_max: STEP_ADDRESS_SPACE as libc::rlim_t,
    };
    // SAFETY: plain system calls on this process, with valid arguments.
    unsafe {
        if libc::setrlimit(libc::RLIMIT_AS, &limit) != 0
            || libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL as libc::c_ulong) != 0
        {
            return Err(std::io::Error::last_os_error());
        }
        // The grader may have died before the line above: then nobody would kill us.
        if libc::getppid() != grader {
            libc::_exit(1);
        }
    }
    Ok(())
}

/// Kills `child` and whatever it started. On Unix the whole process group: the step is its leader
/// (`process_group(0)`), and not yet waited for, so its id still names the group.
#[cfg(unix)]
fn kill_tree(child: &mut std::process::Child) -> std::io::Result<()> {
    let group = -(child.id() as libc::pid_t);
    // SAFETY: a plain system call.
    if unsafe { libc::kill(group, libc::SIGKILL) } != 0 {
        return Err(std::io::Error::last_os_error());
    }
    Ok(())
}

/// Elsewhere (Windows, where a step has no memory limit and no process group) the step's process
/// tree through `taskkill`, else the step alone.
#[cfg(not(unix))]
pub(super) fn kill_tree(child: &mut std::process::Child) -> std::io::Result<()> {
    let tree = Command::new("taskkill")
        .args(["/F", "/T", "/PID", &child.id().to_string()])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
    match tree {
        Ok(s) if s.success() => Ok(()),
        _ => child.kill(),
    }
}

impl Child {
    /// Starts `cmd` (the hidden `grade-step` command for `step`) with its output piped, in a
    /// process group of its own (so that the time limit kills it and anything it started), with a
    /// memory limit, and bound to die with the grader.
    pub fn spawn(cmd: Command, step: Step) -> std::io::Result<Child> {
        let mut child = spawn_confined(cmd)?;
        let stdout = drain(child.stdout.take());
        let stderr = drain(child.stderr.take());
        Ok(Child {
            step,
            child,
            started: Instant::now(),
            stdout,
            stderr,
        })
    }

    /// Waits for the child until `timeout` after its start, killing it then; turns what it printed
    /// into a report.
    pub fn finish(mut self, timeout: Duration) -> StepReport {
        let step = self.step;
        let fail = |message: Text| StepReport::failed_with(step, message);
        let grader_error = |error: String| fail(say!("grade.verdict.grader_error", error = error));
        let status = match self.wait(timeout) {
            Ok(Some(status)) => status,
            Ok(None) => {
                let seconds = timeout.as_secs_f64();
                return fail(say!("grade.verdict.timed_out", seconds = seconds));
            }
            Err(e) => return grader_error(e),
        };
        let out = match collect(self.stdout.take(), "output") {
            Ok(out) => out,
            Err(e) => return grader_error(e),
        };
        // Only shown when there is no verdict: a reading error then takes the place of the text.
        let err = collect(self.stderr.take(), "error output").unwrap_or_else(|e| e);
        match printed_verdict(&out) {
            Some(Ok(report)) => return report,
            Some(Err(e)) => return grader_error(e),
            None => {}
        }
        fail(no_verdict_message(status, &err))
    }

    /// The child's exit status, or `None` when it ran past `timeout` and was killed.
    fn wait(&mut self, timeout: Duration) -> Result<Option<ExitStatus>, String> {
        wait_or_kill(&mut self.child, self.started, timeout)
    }
}

/// Starts `cmd` with its output piped, in a process group of its own (so that a time limit kills it
/// and anything it started), with the step's memory limit, and bound to die with this process:
/// how every child that runs a student's shader starts (the steps, the challenge's entries).
pub(crate) fn spawn_confined(mut cmd: Command) -> std::io::Result<std::process::Child> {
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    #[cfg(unix)]
    {
        cmd.process_group(0);
        let grader = std::process::id() as libc::pid_t;
        // SAFETY: `confine_step` only makes async-signal-safe system calls and allocates nothing.
        unsafe {
            cmd.pre_exec(move || confine_step(grader));
        }
    }
    super::interrupt::spawn_registered(&mut cmd)
}

/// Waits for `child` until `timeout` after `started`, killing its process tree then: its exit
/// status, or `None` when it was killed.
pub(crate) fn wait_or_kill(
    child: &mut std::process::Child,
    started: Instant,
    timeout: Duration,
) -> Result<Option<ExitStatus>, String> {
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return Ok(Some(status)),
            Ok(None) if started.elapsed() >= timeout => {
                if let Err(e) = kill_tree(child) {
                    return Err(format!("cannot stop the step after its time limit: {e}"));
                }
                child
                    .wait()
                    .map_err(|e| format!("cannot wait for the stopped step: {e}"))?;
                return Ok(None);
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(10)),
            Err(e) => return Err(format!("cannot wait for the step: {e}")),
        }
    }
}

/// Why a child that ended without printing a verdict failed: a crash (a signal) or another exit.
fn no_verdict_message(status: ExitStatus, err: &str) -> Text {
    let tail = stderr_tail(err);
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(signal) = status.signal() {
            return say!("grade.verdict.crashed", signal = signal, tail = tail);
        }
    }
    say!("grade.verdict.no_verdict", status = status, tail = tail)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_json_line_is_the_verdict() {
        let out = "noise\n{\"step\":\"sao\",\"file\":\"sao.frag\",\"passed\":true,\"submitted\":true,\"message\":\"ok\"}\n\n";
        let r = printed_verdict(out)
            .expect("a verdict line")
            .expect("a verdict");
        assert!(r.passed);
        assert_eq!(r.message, "ok");
        assert!(printed_verdict("no verdict here\n").is_none());
    }

    #[test]
    fn an_unreadable_verdict_is_an_error_not_a_missing_one() {
        let e = printed_verdict("{\"step\": \"sao\", truncated\n").expect("a verdict line");
        let e = e.expect_err("not a verdict");
        assert!(e.contains("unreadable verdict"), "{e}");
        assert!(e.contains("truncated"), "{e}");
    }

    #[test]
    fn the_stderr_tail_is_its_last_non_empty_line() {
        assert_eq!(stderr_tail("first\n  last one \n\n"), ": last one");
        assert_eq!(stderr_tail(" \n"), "");
    }
}
