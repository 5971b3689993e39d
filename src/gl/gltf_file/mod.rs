//! Loading glTF 2.0 models (Khronos Group, "glTF 2.0 Specification", 2021): a `.gltf` with its
//! buffers embedded as base64 or in `.bin` files beside it, or a binary `.glb`. The document is
//! parsed and validated by the `gltf` crate; the default scene (else the first) is walked node by
//! node with each node's transform applied, so the mesh comes out in the scene's space. Triangles,
//! strips and fans are read; points and lines are not surfaces and are skipped with a warning, as
//! the OBJ loader does. Normals missing from a primitive are computed flat, as the specification
//! asks. Every error names the file and the accessor, buffer or node at fault.

mod buffers;
mod document;
mod instances;

use super::mesh::{MeshData, Vertex};
use anyhow::{bail, Result};
use glam::{Mat3, Mat4, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use rust_i18n::t;
use std::path::Path;

/// The largest `.gltf`/`.glb` file, and the largest `.bin` file it names.
pub const MAX_GLTF_BYTES: u64 = 512 << 20;

/// A loaded glTF scene: its triangles in scene space and what was skipped, as warnings.
#[derive(Debug)]
pub struct GltfMesh {
    pub mesh: MeshData,
    pub warnings: Vec<String>,
}

/// True for a path that names a glTF file (`.gltf` or `.glb`, any case).
pub fn is_gltf_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// Reads `path` as glTF 2.0 (the default scene's meshes merged into one, transforms applied, each
/// `EXT_mesh_gpu_instancing` instance drawn).
pub fn read_gltf(path: &Path) -> Result<GltfMesh> {
    let shown = path.display().to_string();
    let bytes = crate::io::read_capped(path, MAX_GLTF_BYTES)?;
    if bytes.is_empty() {
        bail!("{}", t!("obj.empty", path = shown));
    }
    let document::Parsed {
        document,
        blob,
        instancing,
    } = document::parse(&bytes, &shown)?;
    drop(bytes);
    let buffers = buffers::load(&document, blob, path, MAX_GLTF_BYTES)?;
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or_else(|| anyhow::anyhow!("{}", t!("gltf.no_scene", path = shown)))?;
    let mut out = Builder {
        shown: &shown,
        buffers: &buffers,
        mesh: MeshData::default(),
        skipped_modes: 0,
        flat: 0,
        primitives: 0,
        morphed: 0,
        non_finite: 0,
    };
    out.walk(&document, &scene, &instancing)?;
    let mut warnings = Vec::new();
    if out.skipped_modes > 0 {
        let count = out.skipped_modes;
        warnings.push(t!("gltf.skipped_lines", path = shown, count = count).into_owned());
    }
    if out.flat > 0 {
        let count = out.flat;
        warnings.push(t!("gltf.no_area", path = shown, count = count).into_owned());
    }
    if out.non_finite > 0 {
        let count = out.non_finite;
        warnings.push(t!("gltf.non_finite", path = shown, count = count).into_owned());
    }
    if out.morphed > 0 {
        let count = out.morphed;
        warnings.push(t!("gltf.morph_targets", path = shown, count = count).into_owned());
    }
    if out.mesh.indices.is_empty() {
        let (primitives, skipped) = (out.primitives, out.skipped_modes);
        let message = t!(
            "gltf.no_triangles",
            path = shown,
            primitives = primitives,
            skipped = skipped
        );
        // What was skipped says why: every triangle without area, or with a corner not a number.
        let why: Vec<String> = warnings.iter().map(|w| format!("\n  {w}")).collect();
        bail!("{message}{}", why.concat());
    }
    Ok(GltfMesh {
        mesh: out.mesh,
        warnings,
    })
}

/// Walks the scene's node trees, appending each primitive's triangles in scene space.
struct Builder<'a> {
    shown: &'a str,
    buffers: &'a [Vec<u8>],
    mesh: MeshData,
    skipped_modes: usize,
    flat: usize,
    primitives: usize,
    /// Primitives with morph targets, drawn in their base shape.
    morphed: usize,
    /// Triangles with a corner that is not a finite number.
    non_finite: usize,
}

impl Builder<'_> {
    /// Visits the scene's nodes depth first with a stack of its own (a chain of nodes can be as deep
    /// as the file is long; the call stack is not). A node reached twice is an error: glTF's node
    /// hierarchy is a set of disjoint trees, and a cycle or a shared child would draw twice or
    /// forever.
    fn walk(
        &mut self,
        document: &gltf::Document,
        scene: &gltf::Scene,
        instancing: &[Option<document::Instancing>],
    ) -> Result<()> {
        let nodes: Vec<gltf::Node> = document.nodes().collect();
        let mut visited = vec![false; nodes.len()];
        let mut pending: Vec<(usize, Mat4)> =
            scene.nodes().map(|n| (n.index(), Mat4::IDENTITY)).collect();
        pending.reverse();
        while let Some((index, parent)) = pending.pop() {
            if std::mem::replace(&mut visited[index], true) {
                bail!(
                    "{}",
                    t!("gltf.node_twice", path = self.shown, index = index)
                );
            }
            let node = &nodes[index];
            let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            if !world.is_finite() {
                bail!(
                    "{}",
                    t!("gltf.bad_transform", path = self.shown, index = index)
                );
            }
            if let Some(mesh) = node.mesh() {
                let instances = match instancing.get(index).copied().flatten() {
                    Some(i) => instances::read(document, self.buffers, &i, index, self.shown)?,
                    None => vec![Mat4::IDENTITY],
                };
                for instance in instances {
                    let placed = world * instance;
                    if !placed.is_finite() {
                        bail!(
                            "{}",
                            t!("gltf.bad_transform", path = self.shown, index = index)
                        );
                    }
                    for primitive in mesh.primitives() {
                        self.primitive(&primitive, placed)?;
                    }
                }
            }
            let first_child = pending.len();
            pending.extend(node.children().map(|c| (c.index(), world)));
            pending[first_child..].reverse();
        }
        Ok(())
    }

    fn primitive(&mut self, primitive: &gltf::Primitive, world: Mat4) -> Result<()> {
        self.primitives += 1;
        if primitive.morph_targets().next().is_some() {
            self.morphed += 1;
        }
        if matches!(
            primitive.mode(),
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
        ) {
            self.skipped_modes += 1;
            return Ok(());
        }
        let (shown, buffers) = (self.shown, self.buffers);
        let f32_only = [DataType::F32];
        let Some(positions_acc) = primitive.get(&gltf::Semantic::Positions) else {
            let mesh = primitive.index();
            bail!("{}", t!("gltf.no_positions", path = shown, index = mesh));
        };
        buffers::check_accessor(
            &positions_acc,
            buffers,
            &f32_only,
            Dimensions::Vec3,
            "POSITION",
            shown,
        )?;
        let normals_acc = primitive.get(&gltf::Semantic::Normals);
        if let Some(acc) = &normals_acc {
            buffers::check_accessor(acc, buffers, &f32_only, Dimensions::Vec3, "NORMAL", shown)?;
        }
        let texcoord_types = [DataType::F32, DataType::U8, DataType::U16];
        // Texture coordinates of another shape or type are not drawn with: ignored, not refused.
        let texcoords_acc = primitive
            .get(&gltf::Semantic::TexCoords(0))
            .filter(|acc| acc.dimensions() == Dimensions::Vec2 && acc.sparse().is_none())
            .filter(|acc| texcoord_types.contains(&acc.data_type()));
        if let Some(acc) = &texcoords_acc {
            let dims = Dimensions::Vec2;
            buffers::check_accessor(acc, buffers, &texcoord_types, dims, "TEXCOORD_0", shown)?;
        }
        let index_types = [DataType::U8, DataType::U16, DataType::U32];
        if let Some(acc) = primitive.indices() {
            let dims = Dimensions::Scalar;
            buffers::check_accessor(&acc, buffers, &index_types, dims, "indices", shown)?;
        }
        let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
        let positions: Vec<Vec3> = match reader.read_positions() {
            Some(it) => it.map(Vec3::from).collect(),
            None => Vec::new(),
        };
        let normals: Option<Vec<Vec3>> = normals_acc
            .and_then(|_| reader.read_normals())
            .map(|it| it.map(Vec3::from).collect());
        let texcoords: Option<Vec<[f32; 2]>> = texcoords_acc
            .and_then(|_| reader.read_tex_coords(0))
            .map(|it| it.into_f32().collect());
        let indices: Vec<u32> = match reader.read_indices() {
            Some(it) => it.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        let n = positions.len();
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
            let message = t!("gltf.bad_index", path = shown, index = bad, count = n);
            bail!("{message}");
        }
        let normals = normals.filter(|v| v.len() == n);
        let texcoords = texcoords.filter(|v| v.len() == n);
        let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
        // A mirroring transform turns the triangles inside out: keep them counter-clockwise.
        let mirrored = Mat3::from_mat4(world).determinant() < 0.0;
        for [a, b, c] in triangle_list(primitive.mode(), &indices) {
            let [a, b, c] = if mirrored { [a, c, b] } else { [a, b, c] };
            let corners = [a, b, c].map(|i| i as usize);
            let p = corners.map(|i| world.transform_point3(positions[i]));
            if !p.iter().all(|v| v.is_finite()) {
                self.non_finite += 1;
                continue;
            }
            let face = (p[1] - p[0]).cross(p[2] - p[0]);
            let Some(face_normal) = face.try_normalize() else {
                self.flat += 1;
                continue;
            };
            for (k, &i) in corners.iter().enumerate() {
                let normal = normals
                    .as_ref()
                    .and_then(|v| (normal_matrix * v[i]).try_normalize())
                    .unwrap_or(face_normal);
                self.mesh.indices.push(self.mesh.vertices.len() as u32);
                self.mesh.vertices.push(Vertex {
                    position: p[k].into(),
                    texcoord: texcoords.as_ref().map_or([0.0; 2], |t| t[i]),
                    normal: normal.into(),
                });
            }
        }
        Ok(())
    }
}

/// The triangles of a primitive drawn with `mode` over `indices` (strips and fans unrolled, the
/// strip's odd triangles turned back to counter-clockwise).
fn triangle_list(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (2..indices.len())
            .map(|i| {
                let (a, b, c) = (indices[i - 2], indices[i - 1], indices[i]);
                if i % 2 == 0 {
                    [a, b, c]
                } else {
                    [b, a, c]
                }
            })
            .collect(),
        Mode::TriangleFan => (2..indices.len())
            .map(|i| [indices[0], indices[i - 1], indices[i]])
            .collect(),
        _ => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_unroll_counter_clockwise() {
        let strip = triangle_list(Mode::TriangleStrip, &[0, 1, 2, 3]);
        assert_eq!(strip, vec![[0, 1, 2], [2, 1, 3]]);
        let fan = triangle_list(Mode::TriangleFan, &[0, 1, 2, 3]);
        assert_eq!(fan, vec![[0, 1, 2], [0, 2, 3]]);
        let list = triangle_list(Mode::Triangles, &[0, 1, 2, 3, 4]);
        assert_eq!(list, vec![[0, 1, 2]]);
    }
}
