//! Unit vectors stored as two numbers (the octahedral mapping): the sphere folded onto the square
//! [-1, 1]², as `Res/ao/octahedral.glsl` writes the surface normals. The CPU side reads them back
//! for tests and tools.

use glam::Vec3;

/// The unit vector of an octahedral code (the inverse of `encode_octahedral`).
pub fn decode_octahedral([x, y]: [f32; 2]) -> [f32; 3] {
    let mut n = Vec3::new(x, y, 1.0 - x.abs() - y.abs());
    let fold = (-n.z).clamp(0.0, 1.0);
    n.x += if n.x >= 0.0 { -fold } else { fold };
    n.y += if n.y >= 0.0 { -fold } else { fold };
    n.try_normalize().unwrap_or(Vec3::Z).to_array()
}

/// The octahedral code of a direction (need not be unit length; zero gives +z's code).
pub fn encode_octahedral(v: [f32; 3]) -> [f32; 2] {
    let v = Vec3::from(v);
    let l1 = v.x.abs() + v.y.abs() + v.z.abs();
    if l1 <= 0.0 || !l1.is_finite() {
        return [0.0, 0.0];
    }
    let n = v / l1;
    if n.z >= 0.0 {
        return [n.x, n.y];
    }
    let sign = |a: f32| if a >= 0.0 { 1.0 } else { -1.0 };
    [(1.0 - n.y.abs()) * sign(n.x), (1.0 - n.x.abs()) * sign(n.y)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip_over_the_sphere_and_stay_in_the_square() {
        let mut worst = 0.0f32;
        for i in 0..64 {
            for j in 0..128 {
                let theta = std::f32::consts::PI * (i as f32 + 0.5) / 64.0;
                let phi = 2.0 * std::f32::consts::PI * j as f32 / 128.0;
                let v = [
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ];
                let code = encode_octahedral(v);
                assert!(code[0].abs() <= 1.0 && code[1].abs() <= 1.0, "{code:?}");
                let back = decode_octahedral(code);
                let dot: f32 = (0..3).map(|k| v[k] * back[k]).sum();
                worst = worst.max(dot.clamp(-1.0, 1.0).acos());
            }
        }
        assert!(worst < 1e-3, "largest round-trip error {worst} rad");
        // The poles and the folded edge.
        for v in [
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ] {
            let back = decode_octahedral(encode_octahedral(v));
            for k in 0..3 {
                assert!((back[k] - v[k]).abs() < 1e-6, "{v:?} -> {back:?}");
            }
        }
    }
}
