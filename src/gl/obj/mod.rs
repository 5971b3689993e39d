//! Loading Wavefront OBJ files as real exporters write them: UTF-8, UTF-16 with a byte-order mark,
//! or a legacy 8-bit encoding (Latin-1 material names); polygons of any shape, concave ones
//! triangulated by ear clipping on their best-fit plane; polylines (`l`), points (`p`) and faces of
//! fewer than 3 vertices skipped with a warning that names the file and line, since they are not
//! surfaces. Every error names the file (and the line where there is one): an OBJ with nothing
//! surface-like in it, an index that does not exist, a material library written wrong.

mod mtl;
mod parse;
pub mod polygon;

use super::mesh::{MeshData, Vertex};
use anyhow::{bail, Context as _, Result};
use glam::{DVec3, Vec3};
use parse::{ObjFile, Skipped};
use rust_i18n::t;
use std::collections::{HashMap, HashSet};
use std::path::Path;

/// The largest OBJ file read (a bigger one is refused by name rather than filling memory).
pub const MAX_OBJ_BYTES: u64 = 512 << 20;
/// The largest material library read.
const MAX_MTL_BYTES: u64 = 16 << 20;

/// A loaded OBJ: its triangles and what was skipped on the way, as warnings naming file and line.
#[derive(Debug)]
pub struct ObjMesh {
    pub mesh: MeshData,
    pub warnings: Vec<String>,
}

/// The text of an OBJ or MTL file: UTF-16 (by its byte-order mark, or by its zero bytes), UTF-8,
/// Shift-JIS, else Windows-1252 (Latin-1), which decodes any bytes.
fn decode(bytes: &[u8]) -> String {
    match crate::gl::preprocess::decode_shader_bytes(bytes) {
        Some((text, _)) => text,
        None => encoding_rs::WINDOWS_1252.decode(bytes).0.into_owned(),
    }
}

/// Reads `path` as an OBJ file (all objects and groups merged into one mesh).
pub fn read_obj(path: &Path) -> Result<ObjMesh> {
    let shown = path.display().to_string();
    let bytes =
        crate::io::read_capped(path, MAX_OBJ_BYTES).with_context(|| t!("obj.read_error"))?;
    if bytes.is_empty() {
        bail!("{}", t!("obj.empty", path = shown));
    }
    let obj = parse::parse(&decode(&bytes), &shown)?;
    let mut warnings = skipped_warnings(&obj, &shown);
    for (name, line) in &obj.mtllibs {
        check_mtllib(path, name, &format!("{shown}:{line}"), &mut warnings)?;
    }
    if obj.faces.is_empty() {
        let holds = t!(
            "obj.holds",
            vertices = obj.positions.len(),
            lines = obj.lines.count,
            points = obj.points.count,
            short = obj.short_faces.count
        );
        bail!("{}", t!("obj.no_faces", path = shown, holds = holds));
    }
    let (mesh, flat) = triangles(&obj);
    if flat.count > 0 {
        let place = format!("{shown}:{}", flat.first);
        let more = more(&flat);
        warnings.push(t!("obj.no_area", place = place, more = more).into_owned());
    }
    if mesh.indices.is_empty() {
        let place = format!("{shown}:{}", flat.first);
        bail!("{}", t!("obj.all_flat", place = place, count = flat.count));
    }
    Ok(ObjMesh { mesh, warnings })
}

/// " (N such lines, the last at line L)" when there is more than one.
fn more(s: &Skipped) -> String {
    if s.count > 1 {
        t!("obj.more", count = s.count, last = s.last).into_owned()
    } else {
        String::new()
    }
}

/// One warning per kind of statement skipped, at its first line.
fn skipped_warnings(obj: &ObjFile, shown: &str) -> Vec<String> {
    let kinds = [
        (&obj.lines, "obj.skipped_lines"),
        (&obj.points, "obj.skipped_points"),
        (&obj.short_faces, "obj.skipped_short_faces"),
        (&obj.free_form, "obj.skipped_free_form"),
        (&obj.unknown, "obj.skipped_unknown"),
    ];
    kinds
        .into_iter()
        .filter(|(s, _)| s.count > 0)
        .map(|(s, key)| {
            let place = format!("{shown}:{}", s.first);
            let more = more(s);
            let keyword = &obj.unknown_keyword;
            t!(key, place = place, more = more, keyword = keyword).into_owned()
        })
        .collect()
}

/// Checks the material library `name` that the OBJ `obj_path` names at `place`: missing is a
/// warning (the materials are not used), written wrong is an error naming the `.mtl` and its line.
fn check_mtllib(
    obj_path: &Path,
    name: &str,
    place: &str,
    warnings: &mut Vec<String>,
) -> Result<()> {
    let folder = obj_path.parent().unwrap_or(Path::new(""));
    // Exporters on Windows write `.\file.mtl`; a name may hold spaces, or several names may follow.
    let candidates: Vec<String> = std::iter::once(name.to_string())
        .chain(name.split_whitespace().map(str::to_string))
        .map(|n| n.replace('\\', "/"))
        .collect();
    let mut found = HashSet::new();
    for n in &candidates {
        let file = folder.join(n);
        // A name that exists is read, but only inside the OBJ's folder: one that leaves it (an
        // absolute path, `..`, a link out) or is not a regular file is refused, never read.
        let present = Path::new(n).has_root() || (file.exists() && !file.is_dir());
        if present && found.insert(file.clone()) {
            let shown = file.display().to_string();
            let what = t!("obj.mtl_what");
            let bytes = crate::gl::model_refs::read_beside(obj_path, &what, n, MAX_MTL_BYTES)?;
            mtl::check(&decode(&bytes), &shown)?;
        }
    }
    if found.is_empty() {
        warnings.push(t!("obj.mtl_missing", place = place, file = name).into_owned());
    }
    Ok(())
}

/// The faces as one indexed triangle mesh (a vertex per distinct position/texcoord/normal triple),
/// with the faces that have no area counted.
fn triangles(obj: &ObjFile) -> (MeshData, Skipped) {
    let mut out = MeshData::default();
    let mut flat = Skipped::default();
    let mut ids: HashMap<parse::Corner, u32> = HashMap::new();
    let mut all_normals = true;
    for face in &obj.faces {
        let points: Vec<DVec3> = face
            .corners
            .iter()
            .map(|c| Vec3::from(obj.positions[c.v]).as_dvec3())
            .collect();
        let tris = polygon::triangulate(&points);
        if tris.is_empty() || polygon::newell_normal(&points) == DVec3::ZERO {
            flat.count += 1;
            flat.first = if flat.count == 1 {
                face.line
            } else {
                flat.first
            };
            flat.last = face.line;
            continue;
        }
        for t in tris {
            for i in t {
                let c = face.corners[i];
                all_normals &= c.vn.is_some();
                let next = out.vertices.len() as u32;
                let id = *ids.entry(c).or_insert_with(|| {
                    out.vertices.push(Vertex {
                        position: obj.positions[c.v],
                        texcoord: c.vt.map(|i| obj.texcoords[i]).unwrap_or_default(),
                        normal: c.vn.map(|i| obj.normals[i]).unwrap_or_default(),
                    });
                    next
                });
                out.indices.push(id);
            }
        }
    }
    if !all_normals {
        out.compute_normals(0);
    }
    (out, flat)
}
