//! From a file's bytes to a validated glTF document. The JSON is read as a tree first, so that what
//! the engine draws can be taken out of it and what it does not use cannot refuse the file:
//! `extras` (free-form application data) are dropped unread, and `EXT_mesh_gpu_instancing` (Khronos
//! Group, 2021: per-node TRANSLATION/ROTATION/SCALE accessors, one mesh drawn once per instance) is
//! read here and taken off `extensionsRequired`, which the `gltf` crate would otherwise refuse.
//! Files that are not glTF 2.0 JSON in UTF-8 (glTF 1.0, UTF-16) get an error that says so.

use anyhow::{bail, Result};
use rust_i18n::t;
use serde_json::Value;

/// The instancing extension the loader implements.
pub const INSTANCING: &str = "EXT_mesh_gpu_instancing";

/// One node's instancing accessors (indices into the document's accessors).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Instancing {
    pub translation: Option<usize>,
    pub rotation: Option<usize>,
    pub scale: Option<usize>,
}

/// A parsed glTF file: the document, the `.glb`'s binary chunk, and each node's instancing.
pub struct Parsed {
    pub document: gltf::Document,
    pub blob: Option<Vec<u8>>,
    /// Per node index; `None` for a node drawn once.
    pub instancing: Vec<Option<Instancing>>,
}

/// Parses `bytes` (a `.gltf` or a `.glb`); `shown` names the file in errors.
pub fn parse(bytes: &[u8], shown: &str) -> Result<Parsed> {
    let not_gltf = |problem: String| {
        anyhow::anyhow!("{}", t!("gltf.not_gltf", path = shown, problem = problem))
    };
    let (json, blob) = if bytes.starts_with(b"glTF") {
        let glb = gltf::Glb::from_slice(bytes).map_err(|e| not_gltf(e.to_string()))?;
        (glb.json.into_owned(), glb.bin.map(|b| b.into_owned()))
    } else {
        (bytes.to_vec(), None)
    };
    if is_utf16(&json) {
        bail!("{}", t!("gltf.utf16", path = shown));
    }
    // A byte-order mark is not JSON, but editors on Windows write one.
    let text = json.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&json);
    let mut tree: Value = serde_json::from_slice(text).map_err(|e| not_gltf(e.to_string()))?;
    if let Some(version) = tree.pointer("/asset/version").and_then(Value::as_str) {
        if !version.starts_with("2.") {
            bail!("{}", t!("gltf.version", path = shown, version = version));
        }
    }
    drop_extras(&mut tree);
    let instancing = instancing(&tree, shown)?;
    if let Some(Value::Array(required)) = tree.get_mut("extensionsRequired") {
        required.retain(|e| e.as_str() != Some(INSTANCING));
    }
    let root: gltf::json::Root =
        serde_json::from_value(tree).map_err(|e| not_gltf(e.to_string()))?;
    let document = gltf::Document::from_json(root).map_err(|e| not_gltf(e.to_string()))?;
    Ok(Parsed {
        document,
        blob,
        instancing,
    })
}

/// UTF-16 text (with or without its byte-order mark): JSON of ASCII then has a zero in every pair.
fn is_utf16(bytes: &[u8]) -> bool {
    if bytes.starts_with(b"\xFF\xFE") || bytes.starts_with(b"\xFE\xFF") {
        return true;
    }
    bytes.len() >= 2 && (bytes[0] == 0) != (bytes[1] == 0)
}

/// Removes every `extras` member: application data of any JSON type, which the engine never reads.
fn drop_extras(v: &mut Value) {
    match v {
        Value::Object(map) => {
            map.remove("extras");
            map.values_mut().for_each(drop_extras);
        }
        Value::Array(items) => items.iter_mut().for_each(drop_extras),
        _ => {}
    }
}

/// Each node's `EXT_mesh_gpu_instancing` attributes.
fn instancing(tree: &Value, shown: &str) -> Result<Vec<Option<Instancing>>> {
    let Some(nodes) = tree.get("nodes").and_then(Value::as_array) else {
        return Ok(Vec::new());
    };
    let mut out = Vec::with_capacity(nodes.len());
    for (index, node) in nodes.iter().enumerate() {
        let Some(ext) = node.pointer(&format!("/extensions/{INSTANCING}")) else {
            out.push(None);
            continue;
        };
        let attributes = ext.get("attributes").and_then(Value::as_object);
        let mut found = Instancing::default();
        for (name, accessor) in attributes.into_iter().flatten() {
            let slot = match name.as_str() {
                "TRANSLATION" => &mut found.translation,
                "ROTATION" => &mut found.rotation,
                "SCALE" => &mut found.scale,
                _ => continue, // custom attributes (`_ID`, colours) change no geometry
            };
            let Some(a) = accessor.as_u64() else {
                let message = t!(
                    "gltf.instance_attribute",
                    path = shown,
                    index = index,
                    name = name
                );
                bail!("{message}");
            };
            *slot = Some(a as usize);
        }
        out.push(Some(found));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_is_told_from_utf8() {
        assert!(is_utf16(b"\xFF\xFE{\0"));
        assert!(is_utf16(b"{\0\"\0"));
        assert!(is_utf16(b"\0{\0\""));
        assert!(!is_utf16(b"{\"asset\""));
        assert!(!is_utf16(b"\xEF\xBB\xBF{"));
    }

    #[test]
    fn extras_of_any_type_are_dropped_everywhere() {
        let mut v: Value =
            serde_json::from_str(r#"{"extras":[1],"nodes":[{"extras":"x","name":"a"}]}"#).unwrap();
        drop_extras(&mut v);
        assert_eq!(v.to_string(), r#"{"nodes":[{"name":"a"}]}"#);
    }
}
