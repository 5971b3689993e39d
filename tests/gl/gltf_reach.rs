//! What a model file may reach and what it may ask of the loader: buffers and material libraries
//! only inside the model's folder (no absolute paths, `..`, links out, devices or URL schemes);
//! `EXT_mesh_gpu_instancing` drawn; node chains of any depth; glTF that is valid but uses what
//! the engine does not (extras of any type, 3-component texture coordinates, a BOM) accepted, and
//! what is not glTF 2.0 UTF-8 named as such.

use super::gltf_files::{document, ground_and_box, triangle_doc, write};
use crate::common::temp_dir;
use glam::Vec3;
use opengl3d::gl::gltf_file::read_gltf;
use opengl3d::gl::mesh::MeshData;
use opengl3d::gl::obj::read_obj;
use opengl3d::scene::shapes;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// `doc` with its buffer's uri set to `uri`, written as `name` in `dir`.
fn with_uri(dir: &Path, name: &str, doc: &Value, uri: &str) -> PathBuf {
    let mut d = doc.clone();
    d["buffers"][0]["uri"] = json!(uri);
    write(dir, name, serde_json::to_vec(&d).unwrap())
}

fn error_of(path: &Path) -> String {
    let e = read_gltf(path).expect_err("should not load");
    format!("{e:#}")
}

#[test]
fn gltf_buffers_stay_inside_the_models_folder() {
    let root = temp_dir("gltf-reach");
    let dir = root.join("model");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let (doc, bin) = triangle_doc();
    write(&dir, "tri.bin", &bin);
    write(&dir.join("sub"), "tri.bin", &bin);
    // A good buffer beside the model's folder: readable, but not the model's to read.
    write(&root, "outside.bin", &bin);
    assert!(read_gltf(&with_uri(&dir, "good.gltf", &doc, "tri.bin")).is_ok());
    assert!(read_gltf(&with_uri(&dir, "below.gltf", &doc, "sub/tri.bin")).is_ok());
    assert!(read_gltf(&with_uri(&dir, "round.gltf", &doc, "sub/../tri.bin")).is_ok());
    assert!(read_gltf(&with_uri(&dir, "encoded.gltf", &doc, "sub%2Ftri.bin")).is_ok());

    let outside = |name: &str, uri: &str| {
        let e = error_of(&with_uri(&dir, name, &doc, uri));
        assert!(
            e.contains(name) && e.contains("buffer 0") && e.contains("outside the model's folder"),
            "{uri}: {e}"
        );
        // Nothing of the file was read: no message about its contents.
        assert!(
            !e.contains("vertex index") && !e.contains("holds"),
            "{uri}: {e}"
        );
    };
    outside("absolute.gltf", "/etc/passwd");
    outside("up.gltf", "../../../../etc/passwd");
    outside("sibling.gltf", "../outside.bin");
    outside("encoded_up.gltf", "%2E%2E/outside.bin");
    outside("zero.gltf", "/dev/zero");
    std::os::unix::fs::symlink(root.join("outside.bin"), dir.join("link.bin")).unwrap();
    outside("link.gltf", "link.bin");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.bin")).unwrap();
    outside("link_zero.gltf", "zero.bin");
    // A link that stays inside is followed.
    std::os::unix::fs::symlink(dir.join("sub/tri.bin"), dir.join("inner.bin")).unwrap();
    assert!(read_gltf(&with_uri(&dir, "inner.gltf", &doc, "inner.bin")).is_ok());

    for (name, uri, scheme) in [
        ("http.gltf", "http://example.com/tri.bin", "http:"),
        ("file.gltf", "file:///etc/passwd", "file:"),
    ] {
        let e = error_of(&with_uri(&dir, name, &doc, uri));
        assert!(
            e.contains(name) && e.contains("buffer 0") && e.contains(uri) && e.contains(scheme),
            "{e}"
        );
    }
    // A FIFO inside the folder is not a file: refused without waiting for a writer.
    let fifo = dir.join("fifo.bin");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: mkfifo on a path this test owns.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let e = error_of(&with_uri(&dir, "fifo.gltf", &doc, "fifo.bin"));
    assert!(
        e.contains("fifo.gltf") && e.contains("not a regular file"),
        "{e}"
    );
    // A file far longer than the buffer's byteLength is not read to its end.
    let mut long = bin.clone();
    long.resize(bin.len() + (1 << 20), 0);
    write(&dir, "long.bin", &long);
    let e = error_of(&with_uri(&dir, "long.gltf", &doc, "long.bin"));
    assert!(e.contains("long.gltf") && e.contains("larger than"), "{e}");
}

#[test]
fn obj_material_libraries_stay_inside_the_models_folder() {
    let root = temp_dir("obj-reach");
    let dir = root.join("model");
    std::fs::create_dir_all(&dir).unwrap();
    let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    write(&root, "outside.mtl", "newmtl a\nKd 1 0 0\n");
    write(&dir, "inside.mtl", "newmtl a\nKd 1 0 0\n");
    let obj =
        |name: &str, lib: &str| write(&dir, name, format!("mtllib {lib}\n{square}f 1 2 3 4\n"));
    assert!(read_obj(&obj("good.obj", "inside.mtl")).is_ok());
    std::os::unix::fs::symlink(root.join("outside.mtl"), dir.join("link.mtl")).unwrap();
    for (name, lib) in [
        ("absolute.obj", "/etc/passwd"),
        ("up.obj", "../outside.mtl"),
        ("link.obj", "link.mtl"),
        ("zero.obj", "/dev/zero"),
    ] {
        let e = format!("{:#}", read_obj(&obj(name, lib)).expect_err(lib));
        assert!(
            e.contains(name) && e.contains("material library") && e.contains("outside"),
            "{lib}: {e}"
        );
    }
    // Missing inside the folder stays a warning (the materials are not used).
    let m = read_obj(&obj("missing.obj", "gone.mtl")).unwrap();
    assert!(m.warnings.iter().any(|w| w.contains("gone.mtl")));
}

/// A unit box as a one-mesh document whose node 0 carries `extension` (and `required` lists the
/// instancing extension in extensionsRequired too), with the instance accessors appended.
fn instanced(
    translations: &[[f32; 3]],
    rotations: &[[f32; 4]],
    required: bool,
) -> (Value, Vec<u8>) {
    let mut cube = MeshData::default();
    shapes::add_box(&mut cube, Vec3::ZERO, Vec3::ONE);
    let (mut doc, mut bin) = document(&[&cube], json!([{"mesh": 0}]), json!([0]), Some("i.bin"));
    let mut attributes = serde_json::Map::new();
    let mut add = |name: &str, kind: &str, floats: Vec<f32>, count: usize| {
        let offset = bin.len();
        bin.extend(floats.iter().flat_map(|f| f.to_le_bytes()));
        let views = doc["bufferViews"].as_array_mut().unwrap();
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": floats.len() * 4}));
        let view = views.len() - 1;
        let accessors = doc["accessors"].as_array_mut().unwrap();
        accessors
            .push(json!({"bufferView": view, "componentType": 5126, "count": count, "type": kind}));
        attributes.insert(name.into(), json!(accessors.len() - 1));
    };
    add(
        "TRANSLATION",
        "VEC3",
        translations.concat(),
        translations.len(),
    );
    if !rotations.is_empty() {
        add("ROTATION", "VEC4", rotations.concat(), rotations.len());
    }
    doc["buffers"][0]["byteLength"] = json!(bin.len());
    doc["nodes"][0]["extensions"] = json!({"EXT_mesh_gpu_instancing": {"attributes": attributes}});
    doc["extensionsUsed"] = json!(["EXT_mesh_gpu_instancing"]);
    if required {
        doc["extensionsRequired"] = json!(["EXT_mesh_gpu_instancing"]);
    }
    (doc, bin)
}

#[test]
fn gltf_gpu_instancing_draws_every_instance() {
    let dir = temp_dir("gltf-instancing");
    let places = [[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.0, 0.0, -4.0]];
    for required in [false, true] {
        let (doc, bin) = instanced(&places, &[], required);
        write(&dir, "i.bin", &bin);
        let path = write(&dir, "i.gltf", serde_json::to_vec(&doc).unwrap());
        let m = read_gltf(&path).unwrap().mesh;
        assert_eq!(m.indices.len(), 3 * 36, "three boxes of 12 triangles");
        let (lo, hi) = m.bounds().unwrap();
        assert_eq!(
            (lo, hi),
            (Vec3::new(0.0, 0.0, -4.0), Vec3::new(4.0, 1.0, 1.0))
        );
    }
    // A rotation: a quarter turn about y takes the box's +x corner to -z.
    let quarter = [
        0.0,
        std::f32::consts::FRAC_1_SQRT_2,
        0.0,
        std::f32::consts::FRAC_1_SQRT_2,
    ];
    let (doc, bin) = instanced(&[[10.0, 0.0, 0.0]], &[quarter], false);
    write(&dir, "i.bin", &bin);
    let path = write(&dir, "r.gltf", serde_json::to_vec(&doc).unwrap());
    let (lo, hi) = read_gltf(&path).unwrap().mesh.bounds().unwrap();
    assert!(lo.distance(Vec3::new(10.0, 0.0, -1.0)) < 1e-5, "{lo}");
    assert!(hi.distance(Vec3::new(11.0, 1.0, 0.0)) < 1e-5, "{hi}");
    // Attributes of different lengths are an error naming the node.
    let (mut doc, bin) = instanced(&places, &[quarter], false);
    write(&dir, "i.bin", &bin);
    doc["extensionsRequired"] = json!([]);
    let path = write(&dir, "mixed.gltf", serde_json::to_vec(&doc).unwrap());
    let e = format!("{:#}", read_gltf(&path).unwrap_err());
    assert!(
        e.contains("mixed.gltf: node 0") && e.contains("different counts"),
        "{e}"
    );
}

#[test]
fn a_deep_node_chain_loads_without_exhausting_the_stack() {
    let dir = temp_dir("gltf-deep");
    let depth = 30_000;
    let mut nodes: Vec<Value> = (0..depth)
        .map(|i| json!({"children": [i + 1], "translation": [0.001, 0.0, 0.0]}))
        .collect();
    nodes.push(json!({"mesh": 0}));
    let (doc, bin) = document(
        &[&ground_and_box()],
        json!(nodes),
        json!([0]),
        Some("d.bin"),
    );
    write(&dir, "d.bin", &bin);
    let path = write(&dir, "deep.gltf", serde_json::to_vec(&doc).unwrap());
    // In a thread with a small stack, as a recursion over the chain would overflow any.
    let m = std::thread::Builder::new()
        .stack_size(256 << 10)
        .spawn(move || read_gltf(&path).map(|g| g.mesh))
        .unwrap()
        .join()
        .expect("no stack overflow")
        .unwrap();
    let (lo, _) = m.bounds().unwrap();
    assert!(
        (lo.x - (-1.2 + 30.0)).abs() < 0.05,
        "30 000 steps of 1 mm: {lo}"
    );
}

#[test]
fn gltf_data_the_engine_does_not_use_is_accepted_and_other_formats_named() {
    let dir = temp_dir("gltf-unused");
    let (doc, bin) = triangle_doc();
    write(&dir, "tri.bin", &bin);
    let save = |name: &str, d: &Value| write(&dir, name, serde_json::to_vec(d).unwrap());
    // `extras` of any JSON type, anywhere.
    let mut extras = doc.clone();
    extras["extras"] = json!(["free", "form"]);
    extras["nodes"][0]["extras"] = json!("a string");
    extras["accessors"][0]["extras"] = json!(3);
    assert!(read_gltf(&save("extras.gltf", &extras)).is_ok());
    // Texture coordinates of three components (not drawn with) are ignored.
    let mut uvw = doc.clone();
    uvw["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = json!(1);
    assert!(read_gltf(&save("uvw.gltf", &uvw)).is_ok());
    // Morph targets: drawn in the base shape, with a warning saying so.
    let mut morph = doc.clone();
    morph["meshes"][0]["primitives"][0]["targets"] = json!([{"POSITION": 1}]);
    let g = read_gltf(&save("morph.gltf", &morph)).unwrap();
    assert!(
        g.warnings.iter().any(|w| w.contains("morph targets")),
        "{:?}",
        g.warnings
    );
    // A byte-order mark before the JSON.
    let mut bom = b"\xEF\xBB\xBF".to_vec();
    bom.extend(serde_json::to_vec(&doc).unwrap());
    assert!(read_gltf(&write(&dir, "bom.gltf", bom)).is_ok());
    // UTF-16 and glTF 1.0 are named.
    let text = serde_json::to_string(&doc).unwrap();
    let mut utf16 = vec![0xFF, 0xFE];
    utf16.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
    let e = error_of(&write(&dir, "utf16.gltf", utf16));
    assert!(e.contains("utf16.gltf") && e.contains("UTF-16"), "{e}");
    let v1 = json!({"asset": {"version": "1.0"}, "meshes": {"m": {"primitives": []}}});
    let e = error_of(&save("v1.gltf", &v1));
    assert!(
        e.contains("v1.gltf") && e.contains("glTF 1.0") && e.contains("2.0"),
        "{e}"
    );
}

#[test]
fn odd_geometry_is_named_for_what_it_is() {
    let dir = temp_dir("model-odd");
    // NaN corners are not "on one line".
    let (doc, mut bin) = triangle_doc();
    bin[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
    write(&dir, "tri.bin", &bin);
    // (The corner is shared by both triangles of the quad: nothing is left to draw.)
    let e = error_of(&write(&dir, "nan.gltf", serde_json::to_vec(&doc).unwrap()));
    assert!(
        e.contains("nan.gltf")
            && e.contains("2 triangles have a corner that is not a finite number"),
        "{e}"
    );
    assert!(!e.contains("one line"), "{e}");
    // A triangle whose corners lie on one line is not a face "of 1-2 vertices".
    let flat = write(&dir, "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    let e = format!("{:#}", read_obj(&flat).unwrap_err());
    assert!(e.contains("flat.obj:4") && e.contains("one line"), "{e}");
    assert!(!e.contains("1-2 vertices"), "{e}");
    // A sparse accessor the engine never reads (here one nothing refers to) refuses nothing.
    let (mut sparse, bin) = triangle_doc();
    write(&dir, "tri.bin", &bin);
    sparse["accessors"].as_array_mut().unwrap().push(json!({
        "componentType": 5126, "count": 4, "type": "VEC3",
        "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5125},
                   "values": {"bufferView": 0}}
    }));
    assert!(read_gltf(&write(
        &dir,
        "sparse.gltf",
        serde_json::to_vec(&sparse).unwrap()
    ))
    .is_ok());
}
