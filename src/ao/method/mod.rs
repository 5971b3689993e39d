//! One file per AO method, each owning its shader name, programs, uniform counts and presets.

pub mod angle_based;
pub mod crytek;
pub mod gtao;
pub mod hbao;
pub mod hemisphere;
pub mod rtao;
pub mod sao;
pub mod sao_lesson;
pub mod vbao;

#[cfg(test)]
mod tests {
    use crate::ao::AoSettings;

    /// Depth taps per pixel each method spends for `--samples n`.
    fn taps(n: u32) -> Vec<(&'static str, u32, u32)> {
        let s = AoSettings {
            samples: n,
            ..Default::default()
        };
        let slices = |c: [i32; 2]| (c[0] * 2 * c[1]) as u32;
        vec![
            ("sao", super::sao::counts(&s)[0] as u32, 1),
            ("crytek", super::crytek::counts(&s)[0] as u32, 1),
            ("hemisphere", super::hemisphere::counts(&s)[0] as u32, 1),
            (
                "angle-based",
                super::angle_based::counts(&s)[0] as u32 * 2,
                2,
            ),
            (
                "hbao",
                {
                    let c = super::hbao::counts(&s);
                    (c[0] * c[1]) as u32
                },
                super::hbao::DIRECTIONS as u32,
            ),
            ("gtao", slices(super::gtao::counts(&s)), 4),
            ("vbao", slices(super::vbao::counts(&s)), 4),
        ]
    }

    #[test]
    fn samples_buy_every_method_the_same_taps_within_half_a_unit() {
        for n in 1..=256 {
            for (name, taps, unit) in taps(n) {
                // Below half a unit, the one unit every method needs at least.
                assert!(
                    taps.abs_diff(n) <= unit / 2 || (n <= unit / 2 && taps == unit),
                    "{name}: {taps} taps for --samples {n} (unit {unit})"
                );
            }
        }
        let eleven: Vec<u32> = taps(11).iter().map(|t| t.1).collect();
        assert_eq!(eleven, [11, 11, 11, 12, 12, 12, 12]);
    }
}
