//! OBJ files as exporters write them, through the loader `render` and `reference` use: polylines and
//! points skipped with a warning naming file and line, concave polygons triangulated inside their
//! outline, UTF-16 and Latin-1 text, material libraries checked by file and line.

use crate::common::{fails_with, run, stderr, temp_dir};
use glam::Vec3;
use opengl3d::gl::obj::read_obj;
use std::path::{Path, PathBuf};

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn error_of(path: &Path) -> String {
    let e = read_obj(path).expect_err("should not load");
    format!("{e:#}")
}

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn polylines_points_and_two_vertex_faces_are_skipped_with_their_line() {
    let dir = temp_dir("obj-lines");
    let mixed = write(
        &dir,
        "mixed.obj",
        format!("{SQUARE}l 1 2 3\np 1 2\nf 1 2\nf 1 2 3 4\nl 3 4\n"),
    );
    let loaded = read_obj(&mixed).unwrap();
    assert_eq!(loaded.mesh.indices.len(), 6, "only the square is a surface");
    let w = loaded.warnings.join("\n");
    for needle in [
        "mixed.obj:5: `l`",
        "2 such lines, the last at line 9",
        "mixed.obj:6: `p`",
        "mixed.obj:7: a face of fewer than 3",
    ] {
        assert!(w.contains(needle), "warnings should say {needle:?}:\n{w}");
    }

    // Nothing but lines: an error naming the file, not a blank picture.
    let lines = write(&dir, "lines.obj", format!("{SQUARE}l 1 2 3 4 1\nf 1 2\n"));
    let e = error_of(&lines);
    assert!(e.contains("lines.obj") && e.contains("no faces"), "{e}");
    assert!(e.contains("1 polylines"), "{e}");
    let out = dir.join("x.png");
    let msg = fails_with(
        &[
            "render",
            "--obj",
            lines.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        &["lines.obj", "no faces"],
    );
    assert!(!out.exists(), "no picture for a file without faces:\n{msg}");
}

/// Twice the area of triangle (a, b, c) along `n`: negative when it faces away.
fn area_along(a: Vec3, b: Vec3, c: Vec3, n: Vec3) -> f32 {
    (b - a).cross(c - a).dot(n)
}

#[test]
fn concave_polygons_are_triangulated_inside_their_outline() {
    let dir = temp_dir("obj-concave");
    // A "U" of area 7 (3×3 less the 1×2 notch from the top middle), counter-clockwise seen from
    // +z, starting at a reflex corner: a fan from there covers the notch. Then the same outline
    // standing in the plane x = 2 (facing +x), to check the projection onto its own plane.
    let u = [
        (1.0, 1.0),
        (1.0, 3.0),
        (0.0, 3.0),
        (0.0, 0.0),
        (3.0, 0.0),
        (3.0, 3.0),
        (2.0, 3.0),
        (2.0, 1.0),
    ];
    for (name, to3d, normal) in [
        (
            "flat",
            (|x: f32, y: f32| Vec3::new(x, y, 0.0)) as fn(f32, f32) -> Vec3,
            Vec3::Z,
        ),
        ("standing", |x, y| Vec3::new(2.0, y, -x), Vec3::X),
    ] {
        let mut text = String::new();
        for &(x, y) in &u {
            let p = to3d(x, y);
            text.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
        }
        text.push_str("f 1 2 3 4 5 6 7 8\n");
        let path = write(&dir, &format!("{name}.obj"), text);
        let mesh = read_obj(&path).unwrap().mesh;
        assert_eq!(
            mesh.indices.len(),
            3 * 6,
            "{name}: 8 corners make 6 triangles"
        );
        let mut area = 0.0;
        for [a, b, c] in mesh.triangles() {
            let twice = area_along(a, b, c, normal);
            assert!(
                twice > 0.0,
                "{name}: a triangle faces away or is flat: {a} {b} {c}"
            );
            area += twice / 2.0;
            // The notch (1..2, 1..3) holds no triangle's centre.
            let centre = (a + b + c) / 3.0;
            let (x, y) = if name == "flat" {
                (centre.x, centre.y)
            } else {
                (-centre.z, centre.y)
            };
            assert!(
                !((1.0..2.0).contains(&x) && (1.0..3.0).contains(&y)),
                "{name}: a triangle covers the notch: {a} {b} {c}"
            );
        }
        assert!(
            (area - 7.0).abs() < 1e-4,
            "{name}: area {area}, the U's is 7"
        );
    }
}

#[test]
fn utf16_and_latin1_files_load() {
    let dir = temp_dir("obj-encodings");
    let text = format!("# caf\u{e9}\nmtllib mats.mtl\n{SQUARE}usemtl Terraind\u{e6}k\nf 1 2 3 4\n");
    let utf16 = |le: bool| -> Vec<u8> {
        let bom: [u8; 2] = if le { [0xFF, 0xFE] } else { [0xFE, 0xFF] };
        let units = text
            .replace('\n', "\r\n")
            .encode_utf16()
            .collect::<Vec<_>>();
        let body = units
            .iter()
            .flat_map(|u| if le { u.to_le_bytes() } else { u.to_be_bytes() });
        bom.into_iter().chain(body).collect()
    };
    let (latin1, _, _) = encoding_rs::WINDOWS_1252.encode(&text);
    write(&dir, "mats.mtl", b"newmtl Terraind\xe6k\nKd 0.5 0.5 0.5\n");
    for (name, bytes) in [
        ("le.obj", utf16(true)),
        ("be.obj", utf16(false)),
        ("latin1.obj", latin1.into_owned()),
    ] {
        let path = write(&dir, name, bytes);
        let loaded = read_obj(&path).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        assert_eq!(loaded.mesh.indices.len(), 6, "{name}");
        assert!(loaded.warnings.is_empty(), "{name}: {:?}", loaded.warnings);
    }
}

#[test]
fn a_bad_material_library_is_named_with_its_line() {
    let dir = temp_dir("obj-mtl");
    let obj = write(
        &dir,
        "model.obj",
        format!("mtllib model.mtl\n{SQUARE}f 1 2 3 4\n"),
    );
    for (mtl, line, needle) in [
        (
            "newmtl a\nKd 0.5 0.5 0.5\n\nKs 0.1 oops 0.1\n",
            4,
            "'oops' is not a number",
        ),
        ("# header\nKd 1 1 1\nnewmtl a\n", 2, "before any `newmtl`"),
        (
            "newmtl a\nKd 0.5 0.5\n",
            2,
            "`Kd` takes 1 or 3 numbers, found 2",
        ),
        ("newmtl a\nmap_Kd\n", 2, "names no texture file"),
    ] {
        write(&dir, "model.mtl", mtl);
        let e = error_of(&obj);
        assert!(e.contains(&format!("model.mtl:{line}: ")), "{mtl:?}: {e}");
        assert!(e.contains(needle), "{mtl:?}: {e}");
    }
    // A good one, with what exporters add (unknown keys, options, spaces in names), loads.
    write(
        &dir,
        "model.mtl",
        "newmtl Hard Shiny Plastic\nKa 0 0 0\nKd 0.1 0.2 0.3\nKm 0.05\nd -halo 0.5\nmap_Kd -s 1 1 1 .\\tex.jpg\nillum 2\n",
    );
    assert!(read_obj(&obj).unwrap().warnings.is_empty());
    // A missing one is a warning naming the OBJ's line: its materials are not used.
    std::fs::remove_file(dir.join("model.mtl")).unwrap();
    let w = read_obj(&obj).unwrap().warnings.join("\n");
    assert!(
        w.contains("model.obj:1: material library model.mtl not found"),
        "{w}"
    );
}

#[test]
fn bad_faces_and_numbers_name_the_line() {
    let dir = temp_dir("obj-bad");
    for (text, needle) in [
        (
            format!("{SQUARE}f 1 2 9\n"),
            "bad.obj:5: v index 9 does not exist",
        ),
        (
            format!("{SQUARE}f 0 1 2\n"),
            "bad.obj:5: v index 0 does not exist",
        ),
        (
            format!("{SQUARE}f 1/1 2/1 3/1\n"),
            "bad.obj:5: vt index 1 does not exist",
        ),
        (
            format!("{SQUARE}f 1 2 x\n"),
            "bad.obj:5: 'x' is not a face vertex",
        ),
        (
            "v 1 2 3.1+e2\n".to_string(),
            "bad.obj:1: '3.1+e2' is not a number",
        ),
        (
            "v 1 2 nan\n".to_string(),
            "bad.obj:1: 'nan' is not a number",
        ),
        (
            "v 1 2\n".to_string(),
            "bad.obj:1: `v` takes 3 to 7 numbers, found 2",
        ),
    ] {
        let path = write(&dir, "bad.obj", text);
        let e = error_of(&path);
        assert!(e.contains(needle), "expected {needle:?}, got: {e}");
    }
    // Negative indices count back from the last vertex so far; `\` continues a line.
    let path = write(&dir, "rel.obj", format!("{SQUARE}f -4 -3 \\\n -2 -1\n"));
    assert_eq!(read_obj(&path).unwrap().mesh.indices.len(), 6);
}

#[test]
fn render_draws_an_obj_with_lines_in_it_and_warns_once() {
    let dir = temp_dir("obj-render-warn");
    let obj = write(&dir, "part.obj", format!("{SQUARE}l 1 3\nf 1 2 3 4\n"));
    let out = dir.join("part.png");
    let o = run(&[
        "render",
        "--obj",
        obj.to_str().unwrap(),
        "--width",
        "32",
        "--height",
        "24",
        "--out",
        out.to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert_eq!(e.matches("part.obj:5: `l`").count(), 1, "one warning:\n{e}");
}
