//! The GL layer on real Mesa: context creation, every shader in Res/ builds, shader errors are clear.

use crate::common;

use glow::HasContext;
use opengl3d::gl::preprocess::{decode_shader_bytes, TextEncoding};
use opengl3d::gl::ProgramError;
use opengl3d::gl::ProgramObject;
use opengl3d::res::{project_res_dir, ResDirs};

#[test]
fn headless_context_is_gl_4_5_core() {
    let ctx = common::context();
    let (major, minor) = unsafe {
        (
            ctx.gl.get_parameter_i32(glow::MAJOR_VERSION),
            ctx.gl.get_parameter_i32(glow::MINOR_VERSION),
        )
    };
    assert!(
        (major, minor) >= (4, 5),
        "got OpenGL {major}.{minor} ({})",
        ctx.renderer
    );
}

/// The vertex shader each fragment shader is drawn with.
fn vertex_for(frag: &str) -> &'static str {
    if frag == "ao/surface_normal.frag" {
        return "ao/surface_normal.vert";
    }
    match frag.rsplit('/').next().unwrap() {
        "standard.frag" => "standard.vert",
        "shadow.frag" => "shadow.vert",
        "sky.frag" => "sky.vert",
        _ => "simple.vert",
    }
}

#[test]
fn every_shader_in_res_compiles_and_links() {
    let ctx = common::context();
    let res = ResDirs::default();
    // Top level, the AO methods' folder, the lesson stubs and the grader's lesson checkpoints.
    let mut frags: Vec<String> = Vec::new();
    for sub in [
        "",
        "ao",
        "lesson-stubs",
        "lesson-stubs/ja",
        "lesson-checkpoints/6",
        "lesson-checkpoints/7",
    ] {
        for e in std::fs::read_dir(project_res_dir().join(sub)).unwrap() {
            let name = e.unwrap().file_name().into_string().unwrap();
            if name.ends_with(".frag") {
                frags.push(if sub.is_empty() {
                    name
                } else {
                    format!("{sub}/{name}")
                });
            }
        }
    }
    frags.sort();
    // The lesson's four shaders and the composite must be among them.
    for needed in [
        "sao_restore_depth.frag",
        "sao_down_sampling.frag",
        "sao.frag",
        "sao_blur.frag",
        "simple.frag",
        "lesson-stubs/simple.frag",
        "lesson-stubs/ja/simple.frag",
        "lesson-checkpoints/6/sao.frag",
        "lesson-checkpoints/7/sao.frag",
    ] {
        assert!(frags.iter().any(|f| f == needed), "Res/{needed} is missing");
    }
    for f in &frags {
        // With the defines the engine injects (the engine's shaders have no fallbacks).
        let defines = opengl3d::ao::method::every_define(
            &opengl3d::math::Camera::default(),
            &Default::default(),
        );
        if let Err(e) = ProgramObject::from_res(&ctx.gl, &res, vertex_for(f), f, &defines) {
            panic!("{f} failed to build:\n{e}");
        }
    }
}

fn student_dir(name: &str, files: &[(&str, &[u8])]) -> std::path::PathBuf {
    let d = common::temp_dir(name);
    for (n, bytes) in files {
        std::fs::write(d.join(n), bytes).unwrap();
    }
    d
}

#[test]
fn compile_error_names_file_and_line_and_keeps_last_program() {
    let ctx = common::context();
    let good = std::fs::read(project_res_dir().join("simple.frag")).unwrap();
    let dir = student_dir("compile-error", &[("simple.frag", &good)]);
    let res = ResDirs::with_override(Some(&dir));
    let mut prog =
        ProgramObject::from_res(&ctx.gl, &res, "simple.vert", "simple.frag", &[]).unwrap();
    let old_id = prog.id();
    // Line 11 gets an undeclared identifier.
    let broken = String::from_utf8(good).unwrap().replace(
        "outColor = texture(texColor, inTexcoord);",
        "outColor = texture(texColr, inTexcoord);",
    );
    std::fs::write(dir.join("simple.frag"), broken).unwrap();
    let err = prog.reload().expect_err("a broken shader must not build");
    let msg = err.to_string();
    assert!(matches!(err, ProgramError::Compile { .. }), "{msg}");
    let expected = format!("{}:11:", dir.join("simple.frag").display());
    assert!(
        msg.contains(&expected),
        "message should point at {expected}, got:\n{msg}"
    );
    assert!(
        msg.contains("texColr"),
        "message should quote the driver's complaint:\n{msg}"
    );
    assert_eq!(
        prog.id(),
        old_id,
        "the last working program must stay in use"
    );
    assert!(unsafe { ctx.gl.is_program(prog.id()) });
}

#[test]
fn shift_jis_shader_with_japanese_comments_is_decoded() {
    let ctx = common::context();
    let text = std::fs::read_to_string(project_res_dir().join("simple.frag"))
        .unwrap()
        .replace(
            "void main()",
            "// テクスチャを描画するだけのシェーダ\nvoid main()",
        );
    let (sjis, _, bad) = encoding_rs::SHIFT_JIS.encode(&text);
    assert!(!bad);
    assert!(
        std::str::from_utf8(&sjis).is_err(),
        "the test file must really not be UTF-8"
    );
    let dir = student_dir("sjis", &[("simple.frag", &sjis)]);
    let res = ResDirs::with_override(Some(&dir));
    ProgramObject::from_res(&ctx.gl, &res, "simple.vert", "simple.frag", &[])
        .expect("Shift-JIS shader should build");
    let (decoded, encoding) = decode_shader_bytes(&sjis).unwrap();
    assert!(encoding == TextEncoding::ShiftJis && decoded.contains("テクスチャ"));
}

#[test]
fn undecodable_shader_file_is_rejected_by_name() {
    let ctx = common::context();
    let dir = student_dir(
        "binary",
        &[("simple.frag", &[0x23, 0x76, 0xFF, 0xFF, 0x00, 0x81, 0xFF])],
    );
    let res = ResDirs::with_override(Some(&dir));
    let err = ProgramObject::from_res(&ctx.gl, &res, "simple.vert", "simple.frag", &[])
        .err()
        .expect("must fail");
    let msg = err.to_string();
    assert!(matches!(err, ProgramError::Encoding { .. }), "{msg}");
    assert!(
        msg.contains("simple.frag") && msg.contains("UTF-8"),
        "{msg}"
    );
}

#[test]
fn missing_version_line_is_explained() {
    let ctx = common::context();
    let dir = student_dir("noversion", &[("simple.frag", b"void main() {}\n")]);
    let res = ResDirs::with_override(Some(&dir));
    let msg = ProgramObject::from_res(&ctx.gl, &res, "simple.vert", "simple.frag", &[])
        .err()
        .unwrap()
        .to_string();
    assert!(
        msg.contains("simple.frag") && msg.contains("#version"),
        "{msg}"
    );
}
