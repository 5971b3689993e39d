//! Where cached references live when no `--cache` is given: the user's cache folder (the XDG Base
//! Directory convention), never the current directory.
//!
//! Order: `OPENGL3D_CACHE` (the folder itself), then `$XDG_CACHE_HOME/opengl3d/reference`, then
//! `~/.cache/opengl3d/reference`. A relative `XDG_CACHE_HOME` is ignored, as the convention says.

use anyhow::{bail, Result};
use std::ffi::OsString;
use std::path::PathBuf;

/// The environment variable that names the cache folder outright (tests point it at a temp dir).
pub const CACHE_ENV: &str = "OPENGL3D_CACHE";

/// The cache folder: `flag` when given, else from the environment (see the module's order).
pub fn reference_cache_dir(flag: Option<&std::path::Path>) -> Result<PathBuf> {
    if let Some(dir) = flag {
        return Ok(dir.to_path_buf());
    }
    resolve(
        std::env::var_os(CACHE_ENV),
        std::env::var_os("XDG_CACHE_HOME"),
        std::env::var_os("HOME"),
    )
}

/// The order of the module's doc, on given values (an empty value counts as unset).
fn resolve(
    explicit: Option<OsString>,
    xdg_cache_home: Option<OsString>,
    home: Option<OsString>,
) -> Result<PathBuf> {
    let set = |v: Option<OsString>| v.filter(|s| !s.is_empty()).map(PathBuf::from);
    if let Some(dir) = set(explicit) {
        return Ok(dir);
    }
    if let Some(dir) = set(xdg_cache_home).filter(|p| p.is_absolute()) {
        return Ok(dir.join("opengl3d").join("reference"));
    }
    match set(home) {
        Some(home) => Ok(home.join(".cache").join("opengl3d").join("reference")),
        None => {
            bail!("no cache folder: set {CACHE_ENV}, XDG_CACHE_HOME or HOME, or give --cache DIR")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::resolve;
    use std::path::PathBuf;

    fn os(s: &str) -> Option<std::ffi::OsString> {
        Some(s.into())
    }

    #[test]
    fn explicit_then_xdg_then_home() {
        let r = |e, x, h| resolve(e, x, h).unwrap();
        assert_eq!(r(os("/tmp/c"), os("/x"), os("/h")), PathBuf::from("/tmp/c"));
        assert_eq!(
            r(None, os("/x"), os("/h")),
            PathBuf::from("/x/opengl3d/reference")
        );
        // Relative or empty XDG_CACHE_HOME is ignored.
        for x in [os("rel"), os(""), None] {
            assert_eq!(
                r(None, x, os("/h")),
                PathBuf::from("/h/.cache/opengl3d/reference")
            );
        }
        let e = resolve(None, None, None).unwrap_err().to_string();
        assert!(e.contains("OPENGL3D_CACHE") && e.contains("--cache"), "{e}");
    }
}
