//! Deterministic random numbers and hemisphere sampling for the reference renderer.
//!
//! Everything here is written out by hand (no `rand` crate) so that a given seed gives the same
//! image on every platform and every version of the dependencies, which is what makes the file
//! cache and the analytic tests reproducible.

use glam::DVec3;

/// SplitMix64 finaliser: a good 64-bit mixer, used to turn (seed, pixel index) into
/// well-separated generator states.
#[inline]
pub(crate) fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// PCG-XSH-RR 32-bit generator (O'Neill 2014), one per pixel.
#[derive(Clone, Debug)]
pub(crate) struct Pcg32 {
    state: u64,
    inc: u64,
}

impl Pcg32 {
    const MUL: u64 = 6_364_136_223_846_793_005;

    /// Generator for one pixel. The pixel index goes through its own mixing round so that
    /// neighbouring pixels (and neighbouring seeds) get unrelated streams.
    pub(crate) fn for_pixel(seed: u64, pixel: u64) -> Self {
        let a = splitmix64(seed ^ splitmix64(pixel));
        let b = splitmix64(a ^ 0xD1B5_4A32_D192_ED03);
        let mut rng = Pcg32 {
            state: 0,
            inc: (b << 1) | 1, // stream selector must be odd
        };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(a);
        rng.next_u32();
        rng
    }

    #[inline]
    pub(crate) fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(Self::MUL).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in [0, 1) with 53 random bits.
    #[inline]
    pub(crate) fn next_f64(&mut self) -> f64 {
        let hi = (self.next_u32() as u64) << 21;
        let lo = (self.next_u32() as u64) >> 11;
        ((hi | lo) as f64) * (1.0 / (1u64 << 53) as f64)
    }
}

/// 1/golden ratio: increment of the Kronecker (golden-ratio) sequence used for the second
/// sample dimension.
const INV_PHI: f64 = 0.618_033_988_749_894_9;

/// The `i`-th of `n` stratified points in the unit square, randomly shifted by `shift`.
///
/// The first coordinate is a stratified grid `(i + 0.5) / n`, the second a golden-ratio
/// sequence; together this is a Fibonacci-like rank-1 lattice. Adding one random shift per pixel
/// (Cranley–Patterson rotation, modulo 1) makes every single point uniformly distributed, so the
/// estimator stays unbiased while its variance is far below that of independent samples.
#[inline]
pub(crate) fn lattice_point(i: u32, n: u32, shift: (f64, f64)) -> (f64, f64) {
    let u = ((i as f64 + 0.5) / n as f64 + shift.0).fract();
    let v = (i as f64 * INV_PHI + shift.1).fract();
    (u, v)
}

/// Orthonormal tangent frame for a unit normal (Duff et al. 2017, "Building an Orthonormal
/// Basis, Revisited"); branch-free and without the singularity of cross-with-fixed-axis methods.
#[inline]
pub(crate) fn tangent_frame(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bt = DVec3::new(b, sign + n.y * n.y * a, -n.y);
    (t, bt)
}

/// Maps a point of the unit square to a cosine-weighted direction about `n` (Malley's method:
/// uniform on the unit disk, projected up onto the hemisphere). `u` = squared disk radius, so
/// `cos(theta) = sqrt(1 - u)`.
#[inline]
pub(crate) fn cosine_direction(n: DVec3, t: DVec3, b: DVec3, u: f64, v: f64) -> DVec3 {
    let r = u.sqrt();
    let phi = std::f64::consts::TAU * v;
    let (s, c) = phi.sin_cos();
    let z = (1.0 - u).max(0.0).sqrt();
    t * (r * c) + b * (r * s) + n * z
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcg_is_deterministic_and_uniform_ish() {
        let mut a = Pcg32::for_pixel(7, 3);
        let mut b = Pcg32::for_pixel(7, 3);
        let mut c = Pcg32::for_pixel(7, 4);
        let mut same = true;
        let mut sum = 0.0;
        for _ in 0..10_000 {
            let x = a.next_f64();
            assert_eq!(x, b.next_f64());
            assert!((0.0..1.0).contains(&x));
            if x != c.next_f64() {
                same = false;
            }
            sum += x;
        }
        assert!(!same);
        assert!((sum / 10_000.0 - 0.5).abs() < 0.02);
    }

    #[test]
    fn frame_is_orthonormal() {
        for n in [
            DVec3::Z,
            -DVec3::Z,
            DVec3::X,
            DVec3::new(0.3, -0.5, 0.8).normalize(),
            DVec3::new(1e-9, 0.0, -1.0).normalize(),
        ] {
            let (t, b) = tangent_frame(n);
            assert!((t.length() - 1.0).abs() < 1e-12);
            assert!((b.length() - 1.0).abs() < 1e-12);
            assert!(t.dot(b).abs() < 1e-12 && t.dot(n).abs() < 1e-12 && b.dot(n).abs() < 1e-12);
        }
    }

    #[test]
    fn cosine_directions_have_mean_cos_two_thirds() {
        // E[cos theta] under the cosine-weighted density is 2/3.
        let n = DVec3::new(0.2, 0.9, -0.1).normalize();
        let (t, b) = tangent_frame(n);
        let count = 4096;
        let mut sum = 0.0;
        for i in 0..count {
            let (u, v) = lattice_point(i, count, (0.37, 0.71));
            let d = cosine_direction(n, t, b, u, v);
            assert!((d.length() - 1.0).abs() < 1e-9);
            assert!(d.dot(n) > 0.0);
            sum += d.dot(n);
        }
        assert!((sum / count as f64 - 2.0 / 3.0).abs() < 1e-3);
    }
}
