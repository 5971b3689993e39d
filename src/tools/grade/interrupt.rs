//! The grader's private folders outlive neither a normal exit (their owners remove them on drop) nor
//! an interruption: a signal (SIGINT, SIGTERM, SIGHUP, through the `ctrlc` crate's handler thread)
//! kills the step processes still running (they would write into the folders again), removes every
//! folder registered, and ends the grader with status 130.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, Once};

/// Folders to remove if the grader is interrupted. Registered and created under this lock, so that
/// none exists unregistered; the handler keeps the lock until the process ends, so that no thread
/// creates another one meanwhile (a folder created just after the handler looked would outlive it).
static FOLDERS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
/// A step's process group, named by its leader's process id.
type GroupId = i32;

/// Process groups of the running step processes (each step leads its own group). Steps start and
/// register under this lock, which the handler also keeps until the end: a step starting while the
/// handler runs is either killed with the others or never starts (it would write into a folder
/// after its removal).
static GROUPS: Mutex<Vec<GroupId>> = Mutex::new(Vec::new());

/// How many times the handler removes the folders while something still writes into them (20 ms
/// apart: a killed step is gone well within that).
const REMOVAL_ATTEMPTS: usize = 10;

/// The status an interrupted grader exits with (128 + SIGINT, as shells report Ctrl-C).
pub const INTERRUPTED_STATUS: i32 = 130;

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// Kills the step whose process group is `group` (its leader's id) and what it started.
#[cfg(unix)]
fn kill_group(group: GroupId) {
    // SAFETY: a plain system call; the group's leader is a step not yet reaped.
    unsafe { libc::kill(-(group as libc::pid_t), libc::SIGKILL) };
}

/// Elsewhere (Windows) the step's process tree, through `taskkill`.
#[cfg(not(unix))]
fn kill_group(group: GroupId) {
    let _ = std::process::Command::new("taskkill")
        .args(["/F", "/T", "/PID", &group.to_string()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status();
}

fn install() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        // Another handler already set (an embedding program's) keeps its own behaviour: then the
        // folders are only removed on drop.
        let _ = ctrlc::set_handler(|| {
            let folders = lock(&FOLDERS);
            let groups = lock(&GROUPS);
            for &group in groups.iter() {
                kill_group(group);
            }
            // A killed step dies a moment after the signal, and the grader's own threads may be
            // copying into a folder while it is removed ("directory not empty", or recreated):
            // remove until none is left, a few times at most, then end before they write again.
            for _ in 0..REMOVAL_ATTEMPTS {
                for dir in folders.iter() {
                    let _ = std::fs::remove_dir_all(dir);
                }
                if !folders.iter().any(|d| d.exists()) {
                    break;
                }
                std::thread::sleep(std::time::Duration::from_millis(20));
            }
            // `_exit`, not `exit`: the atexit handlers (the GL driver's among them) must not run
            // while the grader's other threads may still be inside the driver; the folders are
            // gone and nothing is left to flush but the standard streams.
            use std::io::Write;
            let _ = std::io::stdout().flush();
            let _ = std::io::stderr().flush();
            // SAFETY: ends the process at once; no Rust state needs to outlive this point.
            unsafe { libc::_exit(INTERRUPTED_STATUS) };
        });
    });
}

/// Creates `dir` (and its parents), registered for removal on interruption.
pub fn create_registered(dir: &Path) -> std::io::Result<()> {
    install();
    let mut folders = lock(&FOLDERS);
    folders.push(dir.to_path_buf());
    std::fs::create_dir_all(dir)
}

/// Forgets `dir` (its owner removed it).
pub fn unregister(dir: &Path) {
    lock(&FOLDERS).retain(|d| d != dir);
}

/// Starts `cmd` (a step leading its own process group) and registers the group, to be killed on
/// interruption.
pub fn spawn_registered(cmd: &mut std::process::Command) -> std::io::Result<std::process::Child> {
    install();
    let mut groups = lock(&GROUPS);
    let child = cmd.spawn()?;
    groups.push(child.id() as i32);
    Ok(child)
}

/// Forgets a step's group (the step was reaped).
pub fn unregister_group(leader: u32) {
    lock(&GROUPS).retain(|g| *g != leader as i32);
}
