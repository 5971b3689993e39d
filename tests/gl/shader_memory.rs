//! A shader that declares more array storage than the driver can compile in bounded memory is
//! refused by file and line before the driver sees it: `render` exits with an error (not an abort
//! after gigabytes), and a rebuild, as the window does on save, keeps the last working program.

use crate::common::{self, stderr, temp_dir};
use opengl3d::gl::{ProgramError, ProgramObject};
use opengl3d::res::{project_res_dir, ResDirs};

/// The project's `sao.frag` with `float big[100000000]` declared (and used) in `main`.
fn huge_array_shader() -> String {
    let good = std::fs::read_to_string(project_res_dir().join("sao.frag")).unwrap();
    let at = good.find("void main()\n{\n").expect("sao.frag's main") + "void main()\n{\n".len();
    format!(
        "{}  float big[100000000];\n  big[7] = 1.0;\n{}",
        &good[..at],
        &good[at..]
    )
}

#[test]
fn render_refuses_a_huge_array_by_file_and_line_in_bounded_memory() {
    let dir = temp_dir("shader-memory");
    let shader = huge_array_shader();
    let line = shader
        .lines()
        .position(|l| l.contains("big[100000000]"))
        .unwrap()
        + 1;
    std::fs::write(dir.join("sao.frag"), &shader).unwrap();
    let out = dir.join("x.png");
    // 4 GiB of address space: enough for llvmpipe, far below the ~9 GB the driver would allocate.
    let command = format!(
        "ulimit -v 4194304; exec '{}' render --res '{}' --width 64 --height 48 --out '{}'",
        env!("CARGO_BIN_EXE_opengl3d"),
        dir.display(),
        out.display()
    );
    let o = std::process::Command::new("bash")
        .args(["-c", &command])
        .output()
        .unwrap();
    let e = stderr(&o);
    assert_eq!(
        o.status.code(),
        Some(1),
        "an error exit, not a signal:\n{e}"
    );
    let place = format!("{}:{line}:", dir.join("sao.frag").display());
    assert!(e.contains(&place), "should name {place}:\n{e}");
    assert!(e.contains("`big`") && e.contains("at most 4096"), "{e}");
    assert!(!e.contains("panicked"), "{e}");
    assert!(!out.exists());

    // Japanese messages say the same.
    let o = common::run(&[
        "render",
        "--lang",
        "ja",
        "--res",
        dir.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains(&place) && e.contains("4096成分"),
        "{e}"
    );
}

#[test]
fn a_rebuild_with_a_huge_array_keeps_the_last_working_program() {
    let ctx = common::context();
    let dir = temp_dir("shader-memory-reload");
    let good = std::fs::read_to_string(project_res_dir().join("simple.frag")).unwrap();
    std::fs::write(dir.join("simple.frag"), &good).unwrap();
    let res = ResDirs::with_override(Some(&dir));
    let mut program =
        ProgramObject::from_res(&ctx.gl, &res, "simple.vert", "simple.frag", &[]).unwrap();
    let old = program.id();
    // A macro makes the size: the check sees the source as the compiler would.
    let bad = good.replacen(
        "void main()",
        "#define SIZE (1 << 20)\nvec4 table[SIZE];\nvoid main()",
        1,
    );
    std::fs::write(dir.join("simple.frag"), bad).unwrap();
    let err = program.reload().expect_err("must be refused");
    assert!(matches!(err, ProgramError::Storage { .. }), "{err}");
    assert!(err.to_string().contains("simple.frag"), "{err}");
    assert_eq!(program.id(), old, "the last working program stays in use");
}
