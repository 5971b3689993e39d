//! Every program the engine builds declares exactly the uniforms, locations and texture units that
//! `opengl3d::shader_interface` lists (the one place Rust writes them).

use crate::common;

use opengl3d::gl::ProgramObject;
use opengl3d::res::ResDirs;
use opengl3d::shader_interface::{
    build_defines, check_program, ProgramInterface, Uniform, PROGRAMS,
};

#[test]
fn every_program_matches_the_interface_table() {
    let ctx = common::context();
    let res = ResDirs::default();
    let defines = build_defines();
    let mut problems = Vec::new();
    for iface in PROGRAMS {
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
