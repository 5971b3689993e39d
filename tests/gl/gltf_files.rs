//! glTF 2.0 models (`.gltf` with base64 or separate buffers, binary `.glb`) through the loader that
//! `render`, scene files and `reference` use: each renders and ray-traces the same picture as its
//! OBJ twin, node transforms place the mesh, and a malformed file is an error naming it.

use crate::common::{fails_with, run, stderr, temp_dir};
use base64::Engine as _;
use glam::{Mat4, Quat, Vec3};
use opengl3d::gl::gltf_file::read_gltf;
use opengl3d::gl::mesh::MeshData;
use opengl3d::scene::shapes;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// A ground quad and a box standing on it: creases for AO, all triangles facing outwards.
pub(super) fn ground_and_box() -> MeshData {
    let mut m = shapes::ground(1.2, 1);
    shapes::add_box(&mut m, Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 1.0, 0.5));
    m
}

/// The buffer of `meshes` (per mesh: positions, normals, u32 indices) and their accessors, views
/// and glTF meshes, in the order written.
fn buffer_of(meshes: &[&MeshData]) -> (Vec<u8>, Value, Value, Value) {
    let (mut bin, mut accessors, mut views, mut gltf_meshes) = (vec![], vec![], vec![], vec![]);
    for m in meshes {
        let mut add = |bytes: Vec<u8>, accessor: Value| {
            views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len()}));
            let mut accessor = accessor;
            accessor["bufferView"] = json!(views.len() - 1);
            accessors.push(accessor);
            bin.extend(bytes);
        };
        let n = m.vertices.len();
        let (lo, hi) = m.bounds().unwrap();
        let floats = |f: &dyn Fn(&opengl3d::gl::Vertex) -> [f32; 3]| -> Vec<u8> {
            m.vertices
                .iter()
                .flat_map(f)
                .flat_map(f32::to_le_bytes)
                .collect()
        };
        add(
            floats(&|v| v.position),
            json!({"componentType": 5126, "count": n, "type": "VEC3",
                   "min": lo.to_array(), "max": hi.to_array()}),
        );
        add(
            floats(&|v| v.normal),
            json!({"componentType": 5126, "count": n, "type": "VEC3"}),
        );
        let indices: Vec<u8> = m.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        add(
            indices,
            json!({"componentType": 5125, "count": m.indices.len(), "type": "SCALAR"}),
        );
        let first = accessors.len() - 3;
        gltf_meshes.push(json!({"primitives": [{
            "attributes": {"POSITION": first, "NORMAL": first + 1}, "indices": first + 2}]}));
    }
    (bin, json!(accessors), json!(views), json!(gltf_meshes))
}

/// A glTF document over `meshes` with `nodes` (the scene holds `roots`); the buffer's `uri` (None:
/// the `.glb`'s binary chunk). Returns the document and the buffer's bytes.
pub(super) fn document(
    meshes: &[&MeshData],
    nodes: Value,
    roots: Value,
    uri: Option<&str>,
) -> (Value, Vec<u8>) {
    let (bin, accessors, views, gltf_meshes) = buffer_of(meshes);
    let mut buffer = json!({"byteLength": bin.len()});
    if let Some(uri) = uri {
        buffer["uri"] = json!(uri);
    }
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": roots}],
        "nodes": nodes,
        "meshes": gltf_meshes,
        "buffers": [buffer],
        "bufferViews": views,
        "accessors": accessors,
    });
    (doc, bin)
}

/// A binary glTF: header, JSON chunk (padded with spaces), BIN chunk (padded with zeros).
pub(super) fn glb(doc: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json_bytes = serde_json::to_vec(doc).unwrap();
    while !json_bytes.len().is_multiple_of(4) {
        json_bytes.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json_bytes.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    for word in [2, total as u32, json_bytes.len() as u32, 0x4E4F_534A] {
        out.extend(word.to_le_bytes());
    }
    out.extend(json_bytes);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(0x004E_4942u32.to_le_bytes());
    out.extend(bin);
    out
}

pub(super) fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// `mesh` as one node: a `.gltf` with a base64 buffer, one with a `.bin` beside it, and a `.glb`.
fn three_forms(dir: &Path, mesh: &MeshData) -> Vec<PathBuf> {
    let nodes = json!([{"mesh": 0}]);
    let (_, bin) = document(&[mesh], nodes.clone(), json!([0]), None);
    let b64 = base64::engine::general_purpose::STANDARD.encode(&bin);
    let uri = format!("data:application/octet-stream;base64,{b64}");
    let (embedded, _) = document(&[mesh], nodes.clone(), json!([0]), Some(&uri));
    let (separate, _) = document(&[mesh], nodes.clone(), json!([0]), Some("twin%20data.bin"));
    let (binary, _) = document(&[mesh], nodes, json!([0]), None);
    write(dir, "twin data.bin", &bin);
    vec![
        write(dir, "embedded.gltf", serde_json::to_vec(&embedded).unwrap()),
        write(dir, "separate.gltf", serde_json::to_vec(&separate).unwrap()),
        write(dir, "binary.glb", glb(&binary, &bin)),
    ]
}

/// Renders `model` with `--obj` and returns the blurred AO view (visibility per pixel).
fn render_ao(model: &Path, out: &Path) -> Vec<f32> {
    render_ao_said(model, out).0
}

/// `render_ao`, with what the command said on stderr.
pub(crate) fn render_ao_said(model: &Path, out: &Path) -> (Vec<f32>, String) {
    let o = run(&[
        "render",
        "--obj",
        model.to_str().unwrap(),
        "--width",
        "96",
        "--height",
        "64",
        "--view",
        "ao",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}: {}", model.display(), stderr(&o));
    (opengl3d::io::read_pfm(out).unwrap().3, stderr(&o))
}

/// Ray-traces the reference AO of `model` (no cache, so each file is really traced).
fn reference_ao(model: &Path, out: &Path, cache: &Path) -> Vec<f32> {
    let o = run(&[
        "reference",
        "--obj",
        model.to_str().unwrap(),
        "--width",
        "48",
        "--height",
        "32",
        "--rays",
        "32",
        "--cache",
        cache.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}: {}", model.display(), stderr(&o));
    opengl3d::io::read_pfm(out).unwrap().3
}

/// The largest difference between two pictures; a pixel that is a number in one and not in the
/// other (sky in the reference) counts as infinite.
fn max_difference(a: &[f32], b: &[f32]) -> f32 {
    assert_eq!(a.len(), b.len());
    let diff = |(x, y): (&f32, &f32)| match (x.is_finite(), y.is_finite()) {
        (true, true) => (x - y).abs(),
        (false, false) => 0.0,
        _ => f32::INFINITY,
    };
    a.iter().zip(b).map(diff).fold(0.0, f32::max)
}

/// The picture holds occlusion (some pixels clearly below 1) and open ground (some at 1): it is
/// not blank, so equal pictures say something.
fn assert_has_occlusion(label: &str, ao: &[f32]) {
    let dark = ao.iter().filter(|v| **v < 0.9).count();
    let open = ao.iter().filter(|v| **v > 0.98).count();
    assert!(dark > 20 && open > 20, "{label}: {dark} dark, {open} open");
}

#[test]
fn gltf_and_glb_render_and_ray_trace_like_their_obj_twin() {
    let dir = temp_dir("gltf-twin");
    let mesh = ground_and_box();
    let obj = write(&dir, "twin.obj", shapes::to_obj(&mesh, "twin"));
    let twin = render_ao(&obj, &dir.join("obj.pfm"));
    assert_has_occlusion("obj", &twin);
    let forms = three_forms(&dir, &mesh);
    for model in &forms {
        let loaded = read_gltf(model).unwrap_or_else(|e| panic!("{}: {e:#}", model.display()));
        assert_eq!(
            loaded.mesh.indices.len(),
            mesh.indices.len(),
            "{}",
            model.display()
        );
        assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
        let name = model.file_name().unwrap().to_string_lossy();
        let ao = render_ao(model, &dir.join(format!("{name}.pfm")));
        let d = max_difference(&ao, &twin);
        assert!(d < 1e-4, "{name} differs from its OBJ twin by {d}");
    }
    let cache = dir.join("cache");
    let traced_obj = reference_ao(&obj, &dir.join("ref-obj.pfm"), &cache);
    let traced_glb = reference_ao(&forms[2], &dir.join("ref-glb.pfm"), &cache);
    let ao: Vec<f32> = traced_obj
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    assert_has_occlusion("reference of the OBJ", &ao);
    let d = max_difference(&traced_glb, &traced_obj);
    assert!(
        d < 1e-4,
        "the .glb's reference differs from the OBJ's by {d}"
    );

    // A scene file's `mesh` takes a glTF file as it takes an OBJ.
    let scene =
        "[camera]\neye = [2.5, 2.0, 3.0]\ntarget = [0.0, 0.4, 0.0]\n\n[[object]]\nmesh = \"M\"\n";
    let mut views = Vec::new();
    for model in ["twin.obj", "binary.glb"] {
        let file = write(&dir, &format!("{model}.toml"), scene.replace('M', model));
        let out = dir.join(format!("{model}.scene.pfm"));
        let o = run(&[
            "render",
            "--scene",
            file.to_str().unwrap(),
            "--width",
            "64",
            "--height",
            "48",
            "--view",
            "ao",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{model}: {}", stderr(&o));
        views.push(opengl3d::io::read_pfm(&out).unwrap().3);
    }
    assert_has_occlusion("scene with the OBJ", &views[0]);
    let d = max_difference(&views[0], &views[1]);
    assert!(d < 1e-4, "scene with the .glb differs by {d}");
}

#[test]
fn node_transforms_place_the_mesh_where_its_obj_twin_is() {
    let dir = temp_dir("gltf-nodes");
    let ground = shapes::ground(3.0, 1);
    let mut cube = MeshData::default();
    shapes::add_box(&mut cube, Vec3::splat(-0.5), Vec3::splat(0.5));
    // Node 0 (root) moves its child by (0.8, 0.5, -0.3); node 1 turns the cube 30° about Y and
    // stretches it to 1.6 along its own X. The ground hangs off the root untouched.
    let rotation = Quat::from_rotation_y(30f32.to_radians());
    let nodes = json!([
        {"children": [1], "translation": [0.8, 0.5, -0.3]},
        {"mesh": 1, "rotation": rotation.to_array(), "scale": [1.6, 1.0, 1.0]},
        {"mesh": 0}
    ]);
    let (doc, bin) = document(&[&ground, &cube], nodes, json!([0, 2]), None);
    let model = write(&dir, "nodes.glb", glb(&doc, &bin));

    let placed = Mat4::from_translation(Vec3::new(0.8, 0.5, -0.3))
        * Mat4::from_scale_rotation_translation(Vec3::new(1.6, 1.0, 1.0), rotation, Vec3::ZERO);
    let mut twin = cube.clone();
    for v in &mut twin.vertices {
        v.position = placed.transform_point3(Vec3::from(v.position)).into();
        let n = (rotation * (Vec3::from(v.normal) / Vec3::new(1.6, 1.0, 1.0))).normalize();
        v.normal = n.into();
    }
    let mut scene = twin;
    let base = scene.vertices.len() as u32;
    scene.vertices.extend(&ground.vertices);
    scene
        .indices
        .extend(ground.indices.iter().map(|i| i + base));

    let loaded = read_gltf(&model).unwrap().mesh;
    let (lo, hi) = loaded.bounds().unwrap();
    let (want_lo, want_hi) = scene.bounds().unwrap();
    assert!(
        lo.abs_diff_eq(want_lo, 1e-5) && hi.abs_diff_eq(want_hi, 1e-5),
        "{lo} {hi}"
    );
    // The cube's top face, turned by 30°, lies at y = 1.0 with its corners where the twin's are.
    let top: Vec<Vec3> = loaded
        .vertices
        .iter()
        .map(|v| Vec3::from(v.position))
        .filter(|p| (p.y - 1.0).abs() < 1e-5)
        .collect();
    let corner = placed.transform_point3(Vec3::new(0.5, 0.5, 0.5));
    assert!(
        top.iter().any(|p| p.abs_diff_eq(corner, 1e-5)),
        "{corner} not in {top:?}"
    );

    let obj = write(&dir, "twin.obj", shapes::to_obj(&scene, "twin"));
    let a = render_ao(&obj, &dir.join("obj.pfm"));
    let b = render_ao(&model, &dir.join("glb.pfm"));
    assert_has_occlusion("transformed twin", &a);
    let d = max_difference(&a, &b);
    assert!(
        d < 1e-3,
        "the transformed .glb differs from its OBJ twin by {d}"
    );
}

#[test]
fn a_mirroring_node_keeps_triangles_facing_out() {
    let dir = temp_dir("gltf-mirror");
    let mut cube = MeshData::default();
    shapes::add_box(&mut cube, Vec3::splat(-0.5), Vec3::splat(0.5));
    let nodes = json!([{"mesh": 0, "scale": [-1.0, 1.0, 1.0]}]);
    let (doc, bin) = document(&[&cube], nodes, json!([0]), None);
    let model = write(&dir, "mirror.glb", glb(&doc, &bin));
    let m = read_gltf(&model).unwrap().mesh;
    for t in m.indices.chunks_exact(3) {
        let p: [Vec3; 3] = std::array::from_fn(|k| Vec3::from(m.vertices[t[k] as usize].position));
        let face = (p[1] - p[0]).cross(p[2] - p[0]);
        let centre = (p[0] + p[1] + p[2]) / 3.0;
        assert!(face.dot(centre) > 0.0, "triangle {p:?} faces into the cube");
        let n = Vec3::from(m.vertices[t[0] as usize].normal);
        assert!(
            n.dot(face) > 0.0,
            "normal {n} disagrees with the winding of {p:?}"
        );
    }
}

/// A one-triangle document whose parts the malformed cases break.
pub(super) fn triangle_doc() -> (Value, Vec<u8>) {
    let mut tri = MeshData::default();
    shapes::add_quad(
        &mut tri,
        [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        Vec3::Z,
    );
    document(&[&tri], json!([{"mesh": 0}]), json!([0]), Some("tri.bin"))
}

#[test]
fn malformed_gltf_files_are_errors_naming_the_file_and_the_problem() {
    let dir = temp_dir("gltf-bad");
    let (doc, bin) = triangle_doc();
    let bad = |name: &str, doc: &Value, bin: &[u8]| {
        write(&dir, "tri.bin", bin);
        write(&dir, name, serde_json::to_vec(doc).unwrap())
    };
    let error_of = |path: &Path| {
        let e = read_gltf(path).expect_err("should not load");
        format!("{e:#}")
    };
    // The document is sound as written: the cases below each break one thing.
    assert!(read_gltf(&bad("good.gltf", &doc, &bin)).is_ok());

    let text = write(&dir, "text.gltf", "this is not JSON");
    let e = error_of(&text);
    assert!(
        e.contains("text.gltf") && e.contains("not a glTF 2.0 file"),
        "{e}"
    );
    let cut = write(&dir, "cut.glb", &glb(&doc, &bin)[..30]);
    assert!(error_of(&cut).contains("cut.glb: not a glTF 2.0 file"));

    let mut missing = doc.clone();
    missing["buffers"][0]["uri"] = json!("gone.bin");
    let e = error_of(&bad("missing.gltf", &missing, &bin));
    assert!(e.contains("missing.gltf") && e.contains("gone.bin"), "{e}");
    assert!(e.contains("no such file"), "{e}");

    let e = error_of(&bad("short.gltf", &doc, &bin[..bin.len() / 2]));
    assert!(e.contains("short.gltf: buffer 0 holds"), "{e}");

    let mut overrun = doc.clone();
    overrun["accessors"][0]["count"] = json!(1_000_000);
    let e = error_of(&bad("overrun.gltf", &overrun, &bin));
    assert!(e.contains("overrun.gltf: accessor 0 (POSITION)"), "{e}");
    assert!(e.contains("past the end"), "{e}");

    let mut index = doc.clone();
    let last = bin.len() - 4;
    let mut wrong = bin.clone();
    wrong[last..].copy_from_slice(&77u32.to_le_bytes());
    let e = error_of(&bad("index.gltf", &index, &wrong));
    assert!(
        e.contains("index.gltf: vertex index 77 does not exist"),
        "{e}"
    );

    index["accessors"][2]["type"] = json!("VEC2");
    index["accessors"][2]["count"] = json!(3);
    let e = error_of(&bad("kind.gltf", &index, &bin));
    assert!(e.contains("kind.gltf") && e.contains("accessor 2"), "{e}");

    let mut cycle = doc.clone();
    cycle["nodes"] = json!([{"mesh": 0, "children": [1]}, {"children": [0]}]);
    let e = error_of(&bad("cycle.gltf", &cycle, &bin));
    assert!(e.contains("cycle.gltf") && e.contains("node 0"), "{e}");

    let mut lines = doc.clone();
    lines["meshes"][0]["primitives"][0]["mode"] = json!(1);
    let e = error_of(&bad("lines.gltf", &lines, &bin));
    assert!(
        e.contains("lines.gltf") && e.contains("no triangles"),
        "{e}"
    );
    assert!(e.contains("1 of them points or lines"), "{e}");

    // Through the command line: exit status 1, the file named, no panic, no picture.
    let out = dir.join("x.png");
    let path = dir.join("overrun.gltf");
    write(&dir, "overrun.gltf", serde_json::to_vec(&overrun).unwrap());
    fails_with(
        &[
            "render",
            "--model",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        &["overrun.gltf", "accessor 0"],
    );
    assert!(!out.exists());
}
