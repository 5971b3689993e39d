//! The bytes behind a glTF document: the `.glb`'s binary chunk, base64 `data:` URIs, or files beside
//! the `.gltf`; and the bounds check every accessor passes before it is read, so that a file that
//! lies about its sizes is an error naming the accessor rather than a read past the end.

use anyhow::{bail, Result};
use base64::Engine as _;
use gltf::accessor::{DataType, Dimensions};
use gltf::Accessor;
use rust_i18n::t;
use std::path::Path;

/// Every buffer of `doc`, in order; `blob` is the `.glb`'s binary chunk.
pub fn load(
    doc: &gltf::Document,
    blob: Option<Vec<u8>>,
    path: &Path,
    limit: u64,
) -> Result<Vec<Vec<u8>>> {
    let shown = path.display().to_string();
    let mut blob = blob;
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let index = buffer.index();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob
                .take()
                .ok_or_else(|| anyhow::anyhow!("{}", t!("gltf.no_bin_chunk", path = shown)))?,
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => data_uri(uri)
                .ok_or_else(|| {
                    anyhow::anyhow!("{}", t!("gltf.bad_data_uri", path = shown, index = index))
                })?,
            gltf::buffer::Source::Uri(uri) => {
                if let Some(scheme) = uri_scheme(uri) {
                    let message = t!(
                        "gltf.uri_scheme",
                        path = shown,
                        index = index,
                        uri = uri,
                        scheme = scheme
                    );
                    bail!("{message}");
                }
                // The declared length, and a little for the padding some writers add.
                let cap = (buffer.length() as u64)
                    .saturating_add(BIN_SLACK)
                    .min(limit);
                let what = t!("gltf.buffer_what", index = index);
                crate::gl::model_refs::read_beside(path, &what, &percent_decoded(uri), cap)?
            }
        };
        if data.len() < buffer.length() {
            let (has, declared) = (data.len(), buffer.length());
            let message = t!(
                "gltf.short_buffer",
                path = shown,
                index = index,
                has = has,
                declared = declared
            );
            bail!("{message}");
        }
        out.push(data);
    }
    Ok(out)
}

/// Bytes a `.bin` may hold past its buffer's `byteLength` (alignment padding).
const BIN_SLACK: u64 = 4096;

/// The scheme of an absolute URI (`http`, `file`, …), which a model's buffer may not name; `None`
/// for a relative reference. A one-letter "scheme" is a Windows drive (`C:`): absolute too.
fn uri_scheme(uri: &str) -> Option<&str> {
    let (scheme, _) = uri.split_once(':')?;
    let mut chars = scheme.chars();
    let first = chars.next()?;
    let valid = first.is_ascii_alphabetic()
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'));
    valid.then_some(scheme)
}

/// The bytes of a `data:[<type>];base64,<data>` URI (the only kind glTF writers embed).
fn data_uri(uri: &str) -> Option<Vec<u8>> {
    let (_, data) = uri.split_once(";base64,")?;
    base64::engine::general_purpose::STANDARD.decode(data).ok()
}

/// A relative URI as a file name: `%20` and the like decoded (glTF URIs are percent-encoded).
fn percent_decoded(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(b)) => {
                out.push(b);
                i += 3;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Checks that `acc` (the `what` of a primitive) has one of the component types `types` and the
/// shape `dims`, is not sparse, and lies inside its buffer view and buffer.
pub fn check_accessor(
    acc: &Accessor,
    buffers: &[Vec<u8>],
    types: &[DataType],
    dims: Dimensions,
    what: &str,
    shown: &str,
) -> Result<()> {
    let index = acc.index();
    let bad = |problem: String| {
        let message = t!(
            "gltf.bad_accessor",
            path = shown,
            index = index,
            what = what,
            problem = problem
        );
        anyhow::anyhow!("{message}")
    };
    if acc.sparse().is_some() {
        return Err(bad(t!("gltf.sparse").into_owned()));
    }
    if !types.contains(&acc.data_type()) || acc.dimensions() != dims {
        let found = format!("{:?} {:?}", acc.dimensions(), acc.data_type());
        let wanted = format!("{dims:?} {types:?}");
        let problem = t!("gltf.wrong_type", found = found, wanted = wanted);
        return Err(bad(problem.into_owned()));
    }
    let view = acc
        .view()
        .ok_or_else(|| bad(t!("gltf.no_view").into_owned()))?;
    let count = acc.count();
    if count == 0 {
        return Err(bad(t!("gltf.no_elements").into_owned()));
    }
    let size = acc.size();
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        let problem = t!("gltf.short_stride", stride = stride, size = size);
        return Err(bad(problem.into_owned()));
    }
    let end = stride
        .checked_mul(count - 1)
        .and_then(|n| n.checked_add(size))
        .and_then(|n| n.checked_add(acc.offset()));
    let view_end = view.offset().checked_add(view.length());
    let buffer_len = buffers.get(view.buffer().index()).map_or(0, Vec::len);
    match (end, view_end) {
        (Some(end), Some(view_end)) if end <= view.length() && view_end <= buffer_len => Ok(()),
        _ => {
            let problem = t!(
                "gltf.out_of_bounds",
                count = count,
                view = view.index(),
                buffer = view.buffer().index()
            );
            Err(bad(problem.into_owned()))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris_are_percent_decoded_and_data_uris_base64_decoded() {
        assert_eq!(percent_decoded("my%20model.bin"), "my model.bin");
        assert_eq!(percent_decoded("100%"), "100%");
        let uri = "data:application/octet-stream;base64,AAECAw==";
        assert_eq!(data_uri(uri), Some(vec![0, 1, 2, 3]));
        assert_eq!(data_uri("data:application/octet-stream,plain"), None);
    }

    #[test]
    fn absolute_uris_are_told_from_relative_ones() {
        assert_eq!(uri_scheme("http://example.com/a.bin"), Some("http"));
        assert_eq!(uri_scheme("file:///etc/passwd"), Some("file"));
        assert_eq!(uri_scheme("C:/models/a.bin"), Some("C"));
        assert_eq!(uri_scheme("a.bin"), None);
        assert_eq!(uri_scheme("sub/a:b.bin"), None);
        assert_eq!(uri_scheme("../a.bin"), None);
    }
}
