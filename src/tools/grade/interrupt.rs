//! The grader's private folders outlive neither a normal exit (their owners remove them on drop) nor
//! an interruption: a signal (SIGINT, SIGTERM, SIGHUP, through the `ctrlc` crate's handler thread)
//! removes every folder still registered and ends the grader with status 130. Its step processes die
//! with it (they ask the kernel for that, `child.rs`).

use std::path::{Path, PathBuf};
use std::sync::{Mutex, Once};

/// Folders to remove if the grader is interrupted.
static FOLDERS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The status an interrupted grader exits with (128 + SIGINT, as shells report Ctrl-C).
pub const INTERRUPTED_STATUS: i32 = 130;

/// Registers `dir` for removal on interruption, installing the handler on first use.
pub fn register(dir: &Path) {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        // Another handler already set (an embedding program's) keeps its own behaviour: then the
        // folders are only removed on drop, as before.
        let _ = ctrlc::set_handler(|| {
            let folders = std::mem::take(&mut *FOLDERS.lock().unwrap_or_else(|e| e.into_inner()));
            for dir in folders {
                let _ = std::fs::remove_dir_all(&dir);
            }
            std::process::exit(INTERRUPTED_STATUS);
        });
    });
    FOLDERS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .push(dir.to_path_buf());
}

/// Forgets `dir` (its owner removed it).
pub fn unregister(dir: &Path) {
    FOLDERS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|d| d != dir);
}
