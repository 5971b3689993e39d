//! `reference` takes the scene's values through the engine's ranges, as `render` does: the truth
//! traces the radius the methods are given.

use crate::common::{run, stderr, temp_dir};

#[test]
fn reference_clamps_the_radius_as_render_does() {
    let dir = temp_dir("reference-inputs");
    let demo =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/Res/scenes/demo.toml"))
            .unwrap();
    assert!(demo.contains("radius = 1.0"));
    let meshes = concat!(env!("CARGO_MANIFEST_DIR"), "/Res/meshes/");
    let text = demo
        .replace("radius = 1.0", "radius = 1e30")
        .replace("\"meshes/", &format!("\"{meshes}"));
    let scene = dir.join("huge.toml");
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("r.pfm");
    let o = run(&[
        "reference",
        "--scene",
        scene.to_str().unwrap(),
        "--width",
        "16",
        "--height",
        "12",
        "--rays",
        "2",
        "--cache",
        dir.join("cache").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let said = format!("{}{}", stderr(&o), String::from_utf8_lossy(&o.stdout));
    assert!(o.status.success(), "{said}");
    assert!(said.contains("out of range, using 100"), "{said}");
    assert!(said.contains("R = 100 m"), "{said}");
}
