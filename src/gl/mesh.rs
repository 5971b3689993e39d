//! `MeshBuffer` and `StaticMesh`: one vertex/index buffer pair holding every mesh, as in the course,
//! with each mesh remembering where its indices start (the course's `drawParamsList`).

use super::Gl;
use anyhow::{bail, Context as _, Result};
use glam::Vec3;
use glow::HasContext;
use std::collections::HashMap;
use std::path::Path;

/// Vertex layout: location 0 position, 1 texcoord, 2 normal (the course's attribute numbers).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vertex {
    pub position: [f32; 3],
    pub texcoord: [f32; 2],
    pub normal: [f32; 3],
}

/// CPU-side triangle mesh (also what the ray-traced reference consumes).
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
}

impl MeshData {
    /// Triangles as position triples.
    pub fn triangles(&self) -> impl Iterator<Item = [Vec3; 3]> + '_ {
        self.indices.chunks_exact(3).map(|t| {
            let p = |i: u32| Vec3::from(self.vertices[i as usize].position);
            [p(t[0]), p(t[1]), p(t[2])]
        })
    }

    /// Loads an OBJ file (all models merged, triangulated). Errors name the file.
    pub fn load_obj(path: &Path) -> Result<MeshData> {
        let shown = path.display();
        if !path.is_file() {
            bail!("{shown}: OBJ file not found");
        }
        let opts = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..Default::default()
        };
        let (models, _materials) =
            tobj::load_obj(path, &opts).with_context(|| format!("{shown}: malformed OBJ file"))?;
        let mut out = MeshData::default();
        for m in &models {
            let mesh = &m.mesh;
            let n = mesh.positions.len() / 3;
            let base = out.vertices.len() as u32;
            for i in 0..n {
                let position = [
                    mesh.positions[3 * i],
                    mesh.positions[3 * i + 1],
                    mesh.positions[3 * i + 2],
                ];
                if position.iter().any(|v| !v.is_finite()) {
                    bail!(
                        "{shown}: vertex {} of '{}' is not a finite number",
                        i + 1,
                        m.name
                    );
                }
                let texcoord = if mesh.texcoords.len() >= 2 * n {
                    [mesh.texcoords[2 * i], mesh.texcoords[2 * i + 1]]
                } else {
                    [0.0; 2]
                };
                let normal = if mesh.normals.len() >= 3 * n {
                    [
                        mesh.normals[3 * i],
                        mesh.normals[3 * i + 1],
                        mesh.normals[3 * i + 2],
                    ]
                } else {
                    [0.0; 3]
                };
                out.vertices.push(Vertex {
                    position,
                    texcoord,
                    normal,
                });
            }
            for &i in &mesh.indices {
                if i as usize >= n {
                    bail!("{shown}: face index {} out of range in '{}'", i + 1, m.name);
                }
                out.indices.push(base + i);
            }
            if mesh.normals.len() < 3 * n {
                out.compute_normals(base as usize);
            }
        }
        if out.indices.len() < 3 {
            bail!("{shown}: OBJ file contains no triangles");
        }
        Ok(out)
    }

    /// Area-weighted vertex normals for vertices from `first` on (for OBJ files without normals).
    pub fn compute_normals(&mut self, first: usize) {
        let mut acc = vec![Vec3::ZERO; self.vertices.len()];
        for t in self.indices.chunks_exact(3) {
            if (t[0] as usize) < first {
                continue;
            }
            let p = |i: u32| Vec3::from(self.vertices[i as usize].position);
            let n = (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
            for &i in t {
                acc[i as usize] += n;
            }
        }
        for (v, n) in self.vertices.iter_mut().zip(acc).skip(first) {
            // Guard normalize(0): isolated or degenerate vertices get an arbitrary up normal.
            v.normal = n.try_normalize().unwrap_or(Vec3::Y).into();
        }
    }

    /// Axis-aligned bounds (min, max); `None` for an empty mesh.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut it = self.vertices.iter().map(|v| Vec3::from(v.position));
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }
}

/// Where one mesh's indices live in the shared buffers.
#[derive(Clone, Copy, Debug)]
pub struct StaticMesh {
    pub mode: u32,
    pub count: i32,
    /// Byte offset into the index buffer.
    pub index_offset: i32,
    pub base_vertex: i32,
}

pub struct MeshBuffer {
    gl: Gl,
    vao: glow::VertexArray,
    vbo: glow::Buffer,
    ibo: glow::Buffer,
    meshes: HashMap<String, (StaticMesh, MeshData)>,
    /// Draw calls issued so far (pass statistics read differences of it).
    pub draw_calls: std::cell::Cell<u64>,
}

impl MeshBuffer {
    /// Creates the buffers and the full-screen `plane_xy` mesh every post pass draws.
    pub fn new(gl: &Gl) -> Result<MeshBuffer> {
        unsafe {
            let vao = gl
                .create_named_vertex_array()
                .map_err(|e| anyhow::anyhow!(e))?;
            let vbo = gl.create_named_buffer().map_err(|e| anyhow::anyhow!(e))?;
            let ibo = gl.create_named_buffer().map_err(|e| anyhow::anyhow!(e))?;
            let stride = std::mem::size_of::<Vertex>() as i32;
            gl.vertex_array_vertex_buffer(vao, 0, Some(vbo), 0, stride);
            gl.vertex_array_element_buffer(vao, Some(ibo));
            for (loc, size, offset) in [(0u32, 3, 0u32), (1, 2, 12), (2, 3, 20)] {
                gl.enable_vertex_array_attrib(vao, loc);
                gl.vertex_array_attrib_format_f32(vao, loc, size, glow::FLOAT, false, offset);
                gl.vertex_array_attrib_binding_f32(vao, loc, 0);
            }
            let mut mb = MeshBuffer {
                gl: gl.clone(),
                vao,
                vbo,
                ibo,
                meshes: HashMap::new(),
                draw_calls: std::cell::Cell::new(0),
            };
            mb.add("plane_xy", plane_xy())?;
            Ok(mb)
        }
    }

    /// Adds (or replaces) a mesh. All data is re-uploaded; meshes are added at load time only.
    pub fn add(&mut self, name: &str, data: MeshData) -> Result<StaticMesh> {
        if data.indices.is_empty() {
            bail!("mesh '{name}' has no triangles");
        }
        self.meshes.insert(
            name.to_string(),
            (
                StaticMesh {
                    mode: glow::TRIANGLES,
                    count: 0,
                    index_offset: 0,
                    base_vertex: 0,
                },
                data,
            ),
        );
        self.upload();
        Ok(self.meshes[name].0)
    }

    pub fn load_obj(&mut self, name: &str, path: &Path) -> Result<StaticMesh> {
        if let Some((m, _)) = self.meshes.get(name) {
            return Ok(*m);
        }
        let data = MeshData::load_obj(path)?;
        self.add(name, data)
    }

    fn upload(&mut self) {
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        let mut names: Vec<String> = self.meshes.keys().cloned().collect();
        names.sort();
        for n in names {
            let (sm, data) = self.meshes.get_mut(&n).unwrap();
            sm.base_vertex = vertices.len() as i32;
            sm.index_offset = (indices.len() * 4) as i32;
            sm.count = data.indices.len() as i32;
            vertices.extend_from_slice(&data.vertices);
            indices.extend_from_slice(&data.indices);
        }
        let vbytes: Vec<u8> = vertices
            .iter()
            .flat_map(|v| {
                v.position
                    .iter()
                    .chain(&v.texcoord)
                    .chain(&v.normal)
                    .flat_map(|f| f.to_ne_bytes())
            })
            .collect();
        let ibytes: Vec<u8> = indices.iter().flat_map(|i| i.to_ne_bytes()).collect();
        unsafe {
            self.gl
                .named_buffer_data_u8_slice(self.vbo, &vbytes, glow::STATIC_DRAW);
            self.gl
                .named_buffer_data_u8_slice(self.ibo, &ibytes, glow::STATIC_DRAW);
        }
    }

    pub fn get(&self, name: &str) -> Option<StaticMesh> {
        self.meshes.get(name).map(|(m, _)| *m)
    }
    pub fn data(&self, name: &str) -> Option<&MeshData> {
        self.meshes.get(name).map(|(_, d)| d)
    }
    pub fn bind(&self) {
        unsafe { self.gl.bind_vertex_array(Some(self.vao)) }
    }
    /// Draws one mesh (the VAO must be bound).
    pub fn draw(&self, mesh: &StaticMesh) {
        self.draw_calls.set(self.draw_calls.get() + 1);
        unsafe {
            self.gl.draw_elements_base_vertex(
                mesh.mode,
                mesh.count,
                glow::UNSIGNED_INT,
                mesh.index_offset,
                mesh.base_vertex,
            )
        }
    }
    /// Binds the VAO and draws the full-screen quad.
    pub fn draw_plane_xy(&self) {
        self.bind();
        let m = self.meshes["plane_xy"].0;
        self.draw(&m);
    }
}

/// The course's `plane_xy`: a quad covering NDC [-1,1]², texcoords [0,1]².
pub fn plane_xy() -> MeshData {
    let v = |x: f32, y: f32| Vertex {
        position: [x, y, 0.0],
        texcoord: [(x + 1.0) * 0.5, (y + 1.0) * 0.5],
        normal: [0.0, 0.0, 1.0],
    };
    MeshData {
        vertices: vec![v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)],
        indices: vec![0, 1, 2, 2, 3, 0],
    }
}

impl Drop for MeshBuffer {
    fn drop(&mut self) {
        unsafe {
            self.gl.delete_vertex_array(self.vao);
            self.gl.delete_buffer(self.vbo);
            self.gl.delete_buffer(self.ibo);
        }
    }
}
