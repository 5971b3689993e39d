//! What the SAO step asks at `--level lesson` beyond the course's listing, each taught by a page:
//! the open floor seen at a grazing angle stays open (lesson 7's texel-centre snap where every tap
//! reads level 0, lesson 8's mip bias where the taps read levels 1–3), and no derivative is taken
//! inside a branch (lesson 9; the course's own listing does, erratum 22: checked at both levels,
//! from the source, since llvmpipe gives the expected value there and only other GPUs do not).

use crate::ao::AoSettings;
use crate::math::Camera;
use crate::tools::grade::measure::as_r8;
use crate::tools::grade::rig::Rig;
use crate::tools::grade::scene::{floor, SynthScene};
use anyhow::Result;
use glam::Vec3;

/// A floor seen from 0.4 m above it, nothing else: open everywhere.
fn low_floor_scene((width, height): (u32, u32)) -> SynthScene {
    SynthScene {
        name: "low floor",
        camera: Camera {
            eye: Vec3::new(0.0, 0.4, 0.0),
            target: Vec3::new(0.0, 0.0, -8.0),
            ..Camera::default()
        },
        boxes: vec![floor()],
        width,
        height,
        probes: vec![],
    }
}

/// Mean occlusion of the open floor seen at a grazing angle: (far band, where every tap reads level
/// 0 (10–40 m); near band, where the outer taps read levels 1–3 (1–5 m)), each as (the student's,
/// the reference's).
pub(super) fn low_floor(
    rig: &Rig,
    params: &AoSettings,
    size: (u32, u32),
) -> Result<((f64, f64), (f64, f64))> {
    let scene = low_floor_scene(size);
    let depth = scene.depth();
    let (r, s) = rig.sao_pair(&scene.camera, &depth, params)?;
    let band = |lo: f32, hi: f32| {
        let (mut ss, mut rr, mut n) = (0.0f64, 0.0f64, 0usize);
        for i in (0..depth.len()).filter(|&i| (lo..hi).contains(&depth[i])) {
            ss += as_r8(s[i]) as f64;
            rr += as_r8(r[i]) as f64;
            n += 1;
        }
        let n = n.max(1) as f64;
        (ss / n, rr / n)
    };
    Ok((band(10.0, 40.0), band(1.0, 5.0)))
}

/// Where `source` first calls a derivative (`dFdx`, `dFdy`, `fwidth` and their fine and coarse
/// forms) inside the body of an `if` or an `else`: (its line, from 1; whether it comes after the
/// first `for` loop, i.e. in the smoothing rather than the normal). The condition of an `if` is
/// evaluated before the branch, so a derivative there is not inside it.
pub(super) fn derivative_in_branch(source: &str) -> Option<(usize, bool)> {
    let text = crate::gl::shader_storage::strip_comments(source);
    let bytes = text.as_bytes();
    let word_at = |i: usize, w: &str| {
        text[i..].starts_with(w)
            && (i == 0 || !is_ident(bytes[i - 1]))
            && bytes.get(i + w.len()).is_none_or(|b| !is_ident(*b))
    };
    // Each open brace: whether it opens the body of an `if` or an `else`.
    let mut braces: Vec<bool> = Vec::new();
    // Parentheses of an `if` condition still open, and whether a branch's body is about to start
    // (after `if (…)` or `else`), with the nesting it starts at when it is one statement.
    let mut condition_depth: Option<usize> = None;
    let mut parens = 0usize;
    let mut branch_next = false;
    let mut single: Vec<usize> = Vec::new();
    let (mut line, mut seen_for) = (1usize, false);
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        if c == b'\n' {
            line += 1;
        } else if c.is_ascii_whitespace() {
        } else if word_at(i, "if") {
            condition_depth = Some(parens);
            branch_next = false;
            i += 2;
            continue;
        } else if word_at(i, "else") {
            branch_next = true;
            i += 4;
            continue;
        } else if word_at(i, "for") {
            seen_for = true;
        } else if c == b'(' {
            parens += 1;
        } else if c == b')' {
            parens = parens.saturating_sub(1);
            if condition_depth == Some(parens) {
                condition_depth = None;
                branch_next = true;
                i += 1;
                continue;
            }
        } else if c == b'{' {
            braces.push(branch_next);
            branch_next = false;
        } else if c == b'}' {
            braces.pop();
        } else {
            if branch_next {
                // A branch of one statement, up to its ';'.
                single.push(parens);
                branch_next = false;
            }
            if c == b';' && parens == 0 {
                single.clear();
            }
            let inside = braces.iter().any(|b| *b) || !single.is_empty();
            if inside
                && condition_depth.is_none()
                && ["dFdx", "dFdy", "fwidth"]
                    .iter()
                    .any(|d| text[i..].starts_with(d) && (i == 0 || !is_ident(bytes[i - 1])))
            {
                return Some((line, seen_for));
            }
        }
        i += 1;
    }
    None
}

fn is_ident(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

#[cfg(test)]
mod tests {
    use super::derivative_in_branch;

    #[test]
    fn derivatives_inside_a_branch_are_found_and_those_in_conditions_are_not() {
        let course = "void main() {\n  for (int i = 0; i < 3; ++i) {}\n  if (abs(dFdx(p.z)) < 0.02) {\n    o -= dFdx(o) * 0.5;\n  }\n}\n";
        assert_eq!(derivative_in_branch(course), Some((4, true)));
        let port = "void main() {\n  for (int i = 0; i < 3; ++i) {}\n  float d = dFdx(o);\n  if (abs(dpdx.z) < 0.02) {\n    o -= d * 0.5; // dFdx(o) in a comment\n  }\n}\n";
        assert_eq!(derivative_in_branch(port), None);
        let one_statement = "void main() {\n  if (x > 0)\n    n = normalize(cross(dFdx(p), dFdy(p)));\n  y = dFdy(o);\n}\n";
        assert_eq!(derivative_in_branch(one_statement), Some((3, false)));
        let in_else = "void main() {\n  if (x) { y = 1; } else { y = fwidth(o); }\n}\n";
        assert_eq!(derivative_in_branch(in_else), Some((2, false)));
        let ternary_free = "float f(vec3 p) { return dFdx(p).z; }\nvoid main() { o = f(p); }\n";
        assert_eq!(derivative_in_branch(ternary_free), None);
    }
}
