//! A model's units: `render --obj` chooses the AO radius from the model's objects (not from a
//! ground plane many times their size), and draws a model whose radius would leave the radius
//! range (in metres) at a power of 1000 of its size, so the same boxes in metres and in
//! millimetres give the same AO picture.

use crate::common::temp_dir;
use glam::Vec3;
use opengl3d::gl::mesh::MeshData;
use opengl3d::scene::shapes;
use std::path::Path;

/// A ground slab 28 m wide and three boxes about a metre tall, all in `unit`s of a metre.
fn boxes(unit: f32) -> MeshData {
    let mut m = MeshData::default();
    let s = |x: f32, y: f32, z: f32| Vec3::new(x, y, z) * unit;
    shapes::add_box(&mut m, s(-14.0, -0.05, -14.0), s(14.0, 0.0, 14.0));
    shapes::add_box(&mut m, s(-1.0, 0.0, -0.5), s(0.0, 1.0, 0.5));
    shapes::add_box(&mut m, s(0.3, 0.0, -0.4), s(1.0, 0.6, 0.3));
    shapes::add_box(&mut m, s(-0.4, 0.0, 0.8), s(0.4, 1.4, 1.2));
    m
}

/// `render --obj` of `model`: the AO view (visibility per pixel) and what it said on stderr.
fn render(model: &Path, out: &Path) -> (Vec<f32>, String) {
    crate::gltf_files::render_ao_said(model, out)
}

#[test]
fn the_same_boxes_in_metres_and_millimetres_give_the_same_ao() {
    let dir = temp_dir("model-units");
    let m = dir.join("boxes_m.obj");
    let mm = dir.join("boxes_mm.obj");
    std::fs::write(&m, shapes::to_obj(&boxes(1.0), "boxes")).unwrap();
    std::fs::write(&mm, shapes::to_obj(&boxes(1000.0), "boxes")).unwrap();
    let (ao_m, said_m) = render(&m, &dir.join("m.pfm"));
    let (ao_mm, said_mm) = render(&mm, &dir.join("mm.pfm"));
    eprintln!("{said_m}{said_mm}");
    // The boxes span 2 × 1.4 × 1.7 m: a diagonal of 2.97 m, a radius of 0.297 m (the ground's
    // 40 m diagonal would give 4 m).
    assert!(said_m.contains("AO radius 0.297"), "{said_m}");
    assert!(said_mm.contains("0.001"), "{said_mm}");
    let dark = ao_m.iter().filter(|v| **v < 0.9).count();
    let open = ao_m.iter().filter(|v| **v > 0.98).count();
    assert!(dark > 30 && open > 30, "{dark} dark, {open} open");
    // Rounding in millimetres differs a little from rounding in metres; the picture does not.
    let worst = ao_m
        .iter()
        .zip(&ao_mm)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    let mean = ao_m
        .iter()
        .zip(&ao_mm)
        .map(|(a, b)| (a - b).abs())
        .sum::<f32>()
        / ao_m.len() as f32;
    assert!(mean < 0.002 && worst < 0.05, "mean {mean}, worst {worst}");
}
