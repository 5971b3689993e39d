//! A student's `.zip` submission (`grade --class`), unpacked into a private folder before grading.
//! The archive is the student's, so nothing in it is trusted: an entry whose path is absolute or
//! climbs out with `..` (zip-slip), a symbolic link, more entries than a submission needs, or more
//! bytes than it needs once inflated (a zip bomb) refuses the whole archive with the reason. Bytes
//! are counted as they are inflated, never taken from the sizes the archive declares.

use crate::i18n::Text;
use rust_i18n::t;
use std::io::{Read as _, Write as _};
use std::path::{Component, Path, PathBuf};

/// What one archive may unpack to. The lesson's own `Res/` is 41 files and 0.4 MiB.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Bytes of all entries once inflated (the archive file itself may not be larger either).
    pub max_bytes: u64,
    pub max_entries: usize,
}

pub const LIMITS: Limits = Limits {
    max_bytes: 16 << 20,
    max_entries: 1000,
};

/// Why an archive was refused, in English and the chosen language (the class report shows it as
/// the student's failure).
pub type Refusal = Text;

/// Whether an entry is macOS's resource-fork litter (`__MACOSX/…`), which the Finder adds to every
/// archive it makes; skipped, so that it neither counts as a top folder nor fills the limits.
fn is_litter(name: &str) -> bool {
    name.starts_with("__MACOSX/") || name == "__MACOSX"
}

/// The entry's path below the target folder, or why it may not be written: only plain names,
/// no root, drive or `..` (`\` counts as a separator, as Windows tools write it).
fn safe_path(name: &str) -> Result<PathBuf, Refusal> {
    let unified = name.replace('\\', "/");
    let refuse = || Text::new(|l| t!("class.zip_outside", locale = l, entry = name).into());
    if unified.starts_with('/') || unified.contains(':') {
        return Err(refuse());
    }
    let mut path = PathBuf::new();
    for c in Path::new(&unified).components() {
        match c {
            Component::Normal(part) => path.push(part),
            Component::CurDir => {}
            Component::ParentDir | Component::RootDir | Component::Prefix(_) => {
                return Err(refuse())
            }
        }
    }
    if path.as_os_str().is_empty() {
        return Err(refuse());
    }
    Ok(path)
}

/// An I/O or archive error, naming what it happened to.
fn failed(what: &str, error: &dyn std::fmt::Display) -> Refusal {
    Text::new(|l| t!("class.zip_failed", locale = l, what = what, error = error).into())
}

/// Unpacks `archive` into the empty folder `into` within `limits`; returns the folder that holds
/// the submission: `into`, or the one folder at its top when the archive holds nothing else (a
/// zipped folder). A refused archive may leave part of its files in `into`; the caller removes it.
pub fn extract(archive: &Path, into: &Path, limits: Limits) -> Result<PathBuf, Refusal> {
    let shown = archive.display().to_string();
    let mib = limits.max_bytes >> 20;
    let too_big =
        || Text::new(|l| t!("class.zip_too_big", locale = l, zip = shown, mib = mib).into());
    let size = std::fs::metadata(archive)
        .map_err(|e| failed(&shown, &e))?
        .len();
    if size > limits.max_bytes {
        return Err(too_big());
    }
    let file = std::fs::File::open(archive).map_err(|e| failed(&shown, &e))?;
    let mut zip = zip::ZipArchive::new(std::io::BufReader::new(file)).map_err(|e| {
        Text::new(|l| t!("class.zip_unreadable", locale = l, zip = shown, error = e).into())
    })?;
    if zip.len() > limits.max_entries {
        let (count, max) = (zip.len(), limits.max_entries);
        return Err(Text::new(|l| {
            t!(
                "class.zip_too_many",
                locale = l,
                zip = shown,
                count = count,
                max = max
            )
            .into()
        }));
    }
    let mut left = limits.max_bytes;
    for i in 0..zip.len() {
        let what = format!("{shown} #{i}");
        let mut entry = zip.by_index(i).map_err(|e| failed(&what, &e))?;
        let name = entry.name().map_err(|e| failed(&what, &e))?.into_owned();
        if is_litter(&name) {
            continue;
        }
        let rel = safe_path(&name)?;
        if entry.is_symlink() {
            return Err(Text::new(|l| {
                t!("class.zip_symlink", locale = l, entry = name).into()
            }));
        }
        let to = into.join(&rel);
        let shown_to = to.display().to_string();
        if entry.is_dir() {
            std::fs::create_dir_all(&to).map_err(|e| failed(&shown_to, &e))?;
            continue;
        }
        if entry.size() > left {
            return Err(too_big());
        }
        if let Some(parent) = to.parent() {
            std::fs::create_dir_all(parent)
                .map_err(|e| failed(&parent.display().to_string(), &e))?;
        }
        // create_new: two entries of one name (or a file where a folder was) are refused, never
        // written through.
        let mut out = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&to)
            .map_err(|e| failed(&shown_to, &e))?;
        // One byte more than is left tells an entry over the limit from one that fills it.
        let written = std::io::copy(&mut (&mut entry).take(left + 1), &mut out)
            .map_err(|e| failed(&format!("{shown}: {name}"), &e))?;
        if written > left {
            return Err(too_big());
        }
        left -= written;
        out.flush().map_err(|e| failed(&shown_to, &e))?;
    }
    Ok(top_folder(into))
}

/// `dir`'s only entry when that is a folder and no shader lies beside it (hidden entries aside),
/// else `dir`.
fn top_folder(dir: &Path) -> PathBuf {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return dir.to_path_buf();
    };
    let visible: Vec<_> = entries
        .filter_map(|e| e.ok())
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .collect();
    match visible.as_slice() {
        [only] if only.file_type().is_ok_and(|t| t.is_dir()) => only.path(),
        _ => dir.to_path_buf(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_plain_relative_names_are_safe() {
        assert_eq!(safe_path("sao.frag").unwrap(), PathBuf::from("sao.frag"));
        assert_eq!(
            safe_path("./ada/sao.frag").unwrap(),
            PathBuf::from("ada/sao.frag")
        );
        for bad in [
            "../sao.frag",
            "ada/../../x",
            "/etc/passwd",
            "\\windows\\x",
            "ada\\..\\..\\x",
            "C:/x",
            ".",
        ] {
            assert!(safe_path(bad).is_err(), "{bad}");
        }
    }

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("opengl3d-unzip-{name}-{}", std::process::id()));
        if d.exists() {
            std::fs::remove_dir_all(&d).unwrap();
        }
        std::fs::create_dir_all(d.join("out")).unwrap();
        d
    }

    /// A zip at `path` with `entries` (name, bytes), deflated.
    fn write_zip(path: &Path, entries: &[(&str, Vec<u8>)]) {
        use std::io::Write as _;
        let mut zip = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated);
        for (name, bytes) in entries {
            zip.start_file(*name, options).unwrap();
            zip.write_all(bytes).unwrap();
        }
        zip.finish().unwrap();
    }

    #[test]
    fn the_limits_count_inflated_bytes_and_entries() {
        let d = scratch("limits");
        let archive = d.join("a.zip");
        write_zip(
            &archive,
            &[("a.frag", vec![b'a'; 600]), ("b.frag", vec![b'b'; 400])],
        );
        let limits = |max_bytes, max_entries| Limits {
            max_bytes,
            max_entries,
        };
        // Exactly full is fine; one byte less is not.
        let into = d.join("out");
        assert_eq!(extract(&archive, &into, limits(1000, 2)).unwrap(), into);
        assert_eq!(std::fs::read(into.join("b.frag")).unwrap().len(), 400);
        for (l, says) in [
            (limits(999, 2), "unpacks to more than"),
            (limits(1000, 1), "holds 2 entries"),
        ] {
            let into = d.join(format!("out-{}-{}", l.max_bytes, l.max_entries));
            std::fs::create_dir_all(&into).unwrap();
            let why = extract(&archive, &into, l).unwrap_err().en;
            assert!(why.contains(says), "{why}");
        }
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_zipped_folder_is_graded_from_inside_it() {
        let d = scratch("top");
        let archive = d.join("a.zip");
        write_zip(
            &archive,
            &[
                ("lesson/sao.frag", b"x".to_vec()),
                ("__MACOSX/lesson/._sao.frag", b"fork".to_vec()),
            ],
        );
        let into = d.join("out");
        assert_eq!(
            extract(&archive, &into, LIMITS).unwrap(),
            into.join("lesson")
        );
        assert!(!into.join("__MACOSX").exists());
        // A file beside the folder: the archive's top is the submission.
        let archive = d.join("b.zip");
        write_zip(
            &archive,
            &[
                ("lesson/sao.frag", b"x".to_vec()),
                ("blur.frag", b"y".to_vec()),
            ],
        );
        let into = d.join("out-b");
        std::fs::create_dir_all(&into).unwrap();
        assert_eq!(extract(&archive, &into, LIMITS).unwrap(), into);
        std::fs::remove_dir_all(&d).unwrap();
    }
}
