//! Every OBJ file of Debian's `assimp-testmodels` (exporters' output and files that once broke a
//! loader) through the OBJ loader, each with its expected outcome: triangles, or an error naming the
//! file and the problem. A file the table does not list fails the test, so a new package version is
//! looked at rather than passed.

use opengl3d::gl::obj::read_obj;
use std::path::Path;

/// Where the package puts its models.
const CORPUS: &str = "/usr/share/assimp/models";

enum Expect {
    /// Loads with this many triangles (`None`: any number above 0).
    Triangles(Option<usize>),
    /// Fails with a message holding each of these (the file's name is checked too).
    Error(&'static [&'static str]),
}
use Expect::{Error, Triangles};

const TABLE: &[(&str, Expect)] = &[
    ("OBJ/WusonOBJ.obj", Triangles(None)),
    ("OBJ/box.obj", Triangles(Some(12))),
    ("OBJ/box_UTF16BE.obj", Triangles(Some(12))),
    // One face repeats the square 1 2 3 4 hundreds of times.
    ("OBJ/box_longline.obj", Triangles(None)),
    // Its material library has a Latin-1 name.
    ("OBJ/box_mat_with_spaces.obj", Triangles(Some(12))),
    ("OBJ/box_without_lineending.obj", Triangles(Some(12))),
    ("OBJ/concave_polygon.obj", Triangles(None)),
    ("OBJ/cube_mtllib_after_g.obj", Triangles(Some(12))),
    ("OBJ/cube_usemtl.obj", Triangles(Some(12))),
    ("OBJ/cube_with_vertexcolors.obj", Triangles(Some(12))),
    ("OBJ/cube_with_vertexcolors_uni.obj", Triangles(Some(12))),
    ("OBJ/empty_mat.obj", Triangles(None)),
    ("OBJ/multiple_spaces.obj", Triangles(Some(1))),
    // `3.1+e2` is no number in any notation.
    (
        "OBJ/number_formats.obj",
        Error(&["number_formats.obj:11: '3.1+e2' is not a number"]),
    ),
    ("OBJ/point_cloud.obj", Error(&["no faces", "3 vertices"])),
    ("OBJ/regr01.obj", Triangles(None)),
    ("OBJ/regr_3429812.obj", Triangles(Some(4))),
    ("OBJ/space_in_material_name.obj", Triangles(None)),
    ("OBJ/spider.obj", Triangles(None)),
    ("OBJ/testline.obj", Error(&["no faces", "6 polylines"])),
    ("OBJ/testmixed.obj", Triangles(Some(12))),
    ("OBJ/testpoints.obj", Error(&["no faces"])),
    ("invalid/empty.obj", Error(&["is empty"])),
    (
        "invalid/malformed.obj",
        Error(&["malformed.obj:23: v index 12 does not exist"]),
    ),
    // An empty `f` (skipped with a warning) and a material no library defines.
    ("invalid/malformed2.obj", Triangles(Some(10))),
];

/// Every `.obj` under `dir`, as paths relative to `root`.
fn obj_files(root: &Path, dir: &Path, out: &mut Vec<String>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir).unwrap().flatten().collect();
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let p = e.path();
        if p.is_dir() {
            obj_files(root, &p, out);
        } else if p.extension().is_some_and(|x| x.eq_ignore_ascii_case("obj")) {
            out.push(p.strip_prefix(root).unwrap().display().to_string());
        }
    }
}

#[test]
fn every_obj_of_assimp_testmodels_loads_or_fails_as_expected() {
    let root = Path::new(CORPUS);
    assert!(
        root.is_dir(),
        "{CORPUS} is missing: install Debian's test models (apt-get install assimp-testmodels; \
         .ci/run installs them)"
    );
    let mut files = Vec::new();
    obj_files(root, root, &mut files);
    let mut problems = Vec::new();
    for file in &files {
        let Some((_, expect)) = TABLE.iter().find(|(name, _)| name == file) else {
            problems.push(format!(
                "{file}: not in the table: look at it and add its outcome"
            ));
            continue;
        };
        let name = Path::new(file).file_name().unwrap().to_str().unwrap();
        match (read_obj(&root.join(file)), expect) {
            (Ok(m), Triangles(want)) => {
                let n = m.mesh.indices.len() / 3;
                if n == 0 || want.is_some_and(|w| w != n) {
                    problems.push(format!("{file}: {n} triangles, expected {want:?}"));
                }
                if m.mesh
                    .vertices
                    .iter()
                    .any(|v| !v.normal.iter().all(|c| c.is_finite()))
                {
                    problems.push(format!("{file}: a normal is not finite"));
                }
            }
            (Err(e), Error(needles)) => {
                let e = format!("{e:#}");
                for n in needles.iter().chain([&name]) {
                    if !e.contains(n) {
                        problems.push(format!("{file}: error should say {n:?}: {e}"));
                    }
                }
            }
            (Ok(m), Error(_)) => problems.push(format!(
                "{file}: loaded ({} triangles) but should fail",
                m.mesh.indices.len() / 3
            )),
            (Err(e), Triangles(_)) => problems.push(format!("{file}: {e:#}")),
        }
    }
    // A ring drawn as one polygon (outer circle, bridge, inner circle back): ear clipping keeps
    // the hole, a fan from the first corner fills it (area 1.7 m² instead of 0.25).
    if let Ok(m) = read_obj(&root.join("OBJ/concave_polygon.obj")) {
        let area: f32 = m
            .mesh
            .triangles()
            .map(|[a, b, c]| (b - a).cross(c - a).length() / 2.0)
            .sum();
        if (area - 0.2455).abs() > 0.01 {
            problems.push(format!(
                "concave_polygon.obj: area {area} m², the ring's is 0.2455"
            ));
        }
    }
    for (name, _) in TABLE {
        if !files.iter().any(|f| f == name) {
            problems.push(format!("{name}: in the table but not in {CORPUS}"));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
