//! Every program the engine builds declares exactly the uniforms, locations and texture units that
//! `opengl3d::shader_interface` lists (the one place Rust writes them).

use crate::common;

use opengl3d::ao::AoMethod;
use opengl3d::gl::ProgramObject;
use opengl3d::res::ResDirs;
use opengl3d::shader_interface::{check_program, ProgramInterface, Uniform, PROGRAMS};

/// Every define the engine injects, with the default camera and settings.
fn build_defines() -> Vec<(&'static str, String)> {
    use opengl3d::ao::method::every_define;
    every_define(&opengl3d::math::Camera::default(), &Default::default())
}

#[test]
fn every_program_matches_the_interface_table() {
    let ctx = common::context();
    let res = ResDirs::default();
    let defines = build_defines();
    let mut problems = Vec::new();
    // The methods' rows hold their occlusion shaders' interfaces (the lesson's `sao.frag` is in
    // `PROGRAMS` too, for the grader).
    let methods = AoMethod::ALL.map(opengl3d::ao::method::interface);
    for iface in PROGRAMS.iter().chain(&methods) {
        let p = ProgramObject::from_res(&ctx.gl, &res, iface.vert, iface.frag, &defines)
            .unwrap_or_else(|e| panic!("{} + {}: {e}", iface.vert, iface.frag));
        problems.extend(check_program(&ctx.gl, p.id(), iface));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_wrong_location_or_an_unknown_uniform_is_reported() {
    let ctx = common::context();
    let res = ResDirs::default();
    let iface = PROGRAMS
        .iter()
        .find(|p| p.frag == "sao.frag")
        .expect("the lesson's sao.frag is in the table");
    let p =
        ProgramObject::from_res(&ctx.gl, &res, iface.vert, iface.frag, &build_defines()).unwrap();
    // A location typo in the table.
    let shifted: Vec<Uniform> = iface
        .uniforms
        .iter()
        .map(|u| Uniform {
            location: u.location + 1,
            ..*u
        })
        .collect();
    let wrong = ProgramInterface {
        uniforms: Box::leak(shifted.into_boxed_slice()),
        ..*iface
    };
    let problems = check_program(&ctx.gl, p.id(), &wrong);
    assert!(
        problems
            .iter()
            .any(|m| m.contains("saoInfo is at location 200")),
        "{problems:?}"
    );
    // A uniform the table lacks, and one it lists that the program does not have.
    let missing = ProgramInterface {
        uniforms: &[Uniform {
            name: "saoInfoTypo",
            location: 200,
        }],
        ..*iface
    };
    let problems = check_program(&ctx.gl, p.id(), &missing);
    assert!(
        problems.iter().any(|m| m.contains("ndcToView"))
            && problems.iter().any(|m| m.contains("saoInfoTypo")),
        "{problems:?}"
    );
}

/// The compile-time choices Rust sets are the names the shaders test: a misspelt one would leave
/// every path compiled (slower, with the same image) without any error.
#[test]
fn every_define_rust_sets_is_tested_by_its_shader() {
    use opengl3d::ao::method::vbao::feature_defines;
    use opengl3d::ao::method_pass::normal_source_define;
    use opengl3d::ao::upsample::POWER_ONE_DEFINE;
    use opengl3d::ao::AoSettings;
    let settings = AoSettings::default();
    let vbao = include_str!("../../Res/ao/vbao.frag");
    for (name, _) in feature_defines(&settings) {
        assert!(
            vbao.contains(&format!("#if {name}")),
            "vbao.frag never tests {name}"
        );
    }
    let (normals, _) = normal_source_define(&settings);
    let common = include_str!("../../Res/ao/common.glsl");
    assert!(common.contains(&format!("defined({normals})")), "{normals}");
    let composite = include_str!("../../Res/ao/composite_bilateral.frag");
    assert!(composite.contains(&format!("#ifdef {POWER_ONE_DEFINE}")));
}
