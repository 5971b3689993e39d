//! `MeshBuffer` and `StaticMesh`: one vertex/index buffer pair holding every mesh, as in the course,
//! with each mesh remembering where its indices start (the course's `drawParamsList`). OBJ files
//! are read by `super::obj`.

use super::Gl;
use anyhow::{bail, Context as _, Result};
use glam::Vec3;
use glow::HasContext;
use std::collections::HashMap;

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

/// One GL buffer that grows by doubling: new data is appended with a sub-data upload, and on growth
/// the old contents are copied GPU-side, so adding a mesh costs O(its size) amortised.
struct GrowingBuffer {
    buffer: glow::Buffer,
    /// Bytes allocated.
    capacity: usize,
    /// Bytes in use (from 0).
    used: usize,
}

/// Bytes moved by a `MeshBuffer` so far (to check that adding N meshes costs O(total size)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UploadCounts {
    /// Bytes sent from the CPU.
    pub uploaded: u64,
    /// Bytes copied GPU-side when a buffer grew.
    pub copied: u64,
    /// Buffer reallocations.
    pub grows: u32,
}

/// Smallest allocation: the full-screen quad and a few small meshes fit without growing.
const MIN_CAPACITY: usize = 64 * 1024;

impl GrowingBuffer {
    fn new(gl: &Gl) -> Result<GrowingBuffer> {
        let buffer = unsafe { gl.create_named_buffer() }.map_err(|e| anyhow::anyhow!(e))?;
        Ok(GrowingBuffer {
            buffer,
            capacity: 0,
            used: 0,
        })
    }

    /// Appends `bytes`, growing (and moving) the buffer if needed; returns the byte offset written.
    /// Returns whether the GL buffer object changed (the VAO must then point at the new one).
    fn append(
        &mut self,
        gl: &Gl,
        bytes: &[u8],
        counts: &mut UploadCounts,
    ) -> Result<(usize, bool)> {
        let needed = self.used + bytes.len();
        if needed > i32::MAX as usize {
            bail!("meshes need {needed} bytes: more than one GL buffer holds (2 GiB)");
        }
        let mut moved = false;
        if needed > self.capacity {
            let capacity = needed
                .max(self.capacity * 2)
                .max(MIN_CAPACITY)
                .min(i32::MAX as usize);
            unsafe {
                let fresh = gl.create_named_buffer().map_err(|e| anyhow::anyhow!(e))?;
                gl.named_buffer_data_size(fresh, capacity as i32, glow::STATIC_DRAW);
                if self.used > 0 {
                    // No DSA copy in glow: bind the two buffers to the copy targets.
                    gl.bind_buffer(glow::COPY_READ_BUFFER, Some(self.buffer));
                    gl.bind_buffer(glow::COPY_WRITE_BUFFER, Some(fresh));
                    gl.copy_buffer_sub_data(
                        glow::COPY_READ_BUFFER,
                        glow::COPY_WRITE_BUFFER,
                        0,
                        0,
                        self.used as i32,
                    );
                    gl.bind_buffer(glow::COPY_READ_BUFFER, None);
                    gl.bind_buffer(glow::COPY_WRITE_BUFFER, None);
                }
                gl.delete_buffer(self.buffer);
                self.buffer = fresh;
            }
            counts.copied += self.used as u64;
            counts.grows += 1;
            self.capacity = capacity;
            moved = true;
        }
        let offset = self.used;
        unsafe {
            gl.named_buffer_sub_data_u8_slice(self.buffer, offset as i32, bytes);
        }
        counts.uploaded += bytes.len() as u64;
        self.used = needed;
        Ok((offset, moved))
    }
}

pub struct MeshBuffer {
    gl: Gl,
    vao: glow::VertexArray,
    vbo: GrowingBuffer,
    ibo: GrowingBuffer,
    meshes: HashMap<String, (StaticMesh, MeshData)>,
    counts: UploadCounts,
    /// Draw calls issued so far (pass statistics read differences of it).
    pub draw_calls: std::cell::Cell<u64>,
}

/// Vertex size in bytes (position, texcoord, normal).
const VERTEX_BYTES: usize = std::mem::size_of::<Vertex>();

impl MeshBuffer {
    /// Creates the buffers and the full-screen `plane_xy` mesh every post pass draws.
    pub fn new(gl: &Gl) -> Result<MeshBuffer> {
        let vao = unsafe { gl.create_named_vertex_array() }.map_err(|e| anyhow::anyhow!(e))?;
        unsafe {
            for (loc, size, offset) in [(0u32, 3, 0u32), (1, 2, 12), (2, 3, 20)] {
                gl.enable_vertex_array_attrib(vao, loc);
                gl.vertex_array_attrib_format_f32(vao, loc, size, glow::FLOAT, false, offset);
                gl.vertex_array_attrib_binding_f32(vao, loc, 0);
            }
        }
        let mut mb = MeshBuffer {
            gl: gl.clone(),
            vao,
            vbo: GrowingBuffer::new(gl)?,
            ibo: GrowingBuffer::new(gl)?,
            meshes: HashMap::new(),
            counts: UploadCounts::default(),
            draw_calls: std::cell::Cell::new(0),
        };
        mb.add("plane_xy", plane_xy())?;
        Ok(mb)
    }

    /// Adds (or replaces) a mesh: its data is appended to the shared buffers (a replaced mesh's old
    /// range stays allocated, unused). Meshes already added keep their offsets.
    pub fn add(&mut self, name: &str, data: MeshData) -> Result<StaticMesh> {
        if data.indices.is_empty() {
            bail!("mesh '{name}' has no triangles");
        }
        let count = i32::try_from(data.indices.len())
            .with_context(|| format!("mesh '{name}' has too many indices"))?;
        let vbytes: Vec<u8> = data
            .vertices
            .iter()
            .flat_map(|v| {
                v.position
                    .iter()
                    .chain(&v.texcoord)
                    .chain(&v.normal)
                    .flat_map(|f| f.to_ne_bytes())
            })
            .collect();
        let ibytes: Vec<u8> = data.indices.iter().flat_map(|i| i.to_ne_bytes()).collect();
        let (voffset, vmoved) = self.vbo.append(&self.gl, &vbytes, &mut self.counts)?;
        let (ioffset, imoved) = self.ibo.append(&self.gl, &ibytes, &mut self.counts)?;
        unsafe {
            if vmoved {
                let stride = VERTEX_BYTES as i32;
                self.gl
                    .vertex_array_vertex_buffer(self.vao, 0, Some(self.vbo.buffer), 0, stride);
            }
            if imoved {
                self.gl
                    .vertex_array_element_buffer(self.vao, Some(self.ibo.buffer));
            }
        }
        let mesh = StaticMesh {
            mode: glow::TRIANGLES,
            count,
            index_offset: ioffset as i32,
            base_vertex: (voffset / VERTEX_BYTES) as i32,
        };
        self.meshes.insert(name.to_string(), (mesh, data));
        Ok(mesh)
    }

    /// Bytes uploaded and copied so far.
    pub fn upload_counts(&self) -> UploadCounts {
        self.counts
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
            self.gl.delete_buffer(self.vbo.buffer);
            self.gl.delete_buffer(self.ibo.buffer);
        }
    }
}
