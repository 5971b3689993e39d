//! What the charts show, apart from drawing: the panels (one per scene and radius), the Pareto
//! front of a panel, and the colour of each method (the same on every chart).

use super::super::report::Row;
use plotters::style::RGBColor;

/// The scene a row was measured on (its cameras carry the name).
pub fn scene_of(row: &Row) -> &str {
    row.cameras.first().map_or("", |c| c.scene.as_str())
}

/// One chart panel: the rows of one scene at one radius (each radius has its own truth, so a
/// panel never mixes radii).
pub struct Panel<'a> {
    pub scene: String,
    pub radius: f32,
    pub rows: Vec<&'a Row>,
}

/// The panels of `rows`: scenes in the order of `scenes`, radii ascending; no empty panel.
pub fn panels<'a>(scenes: &[String], rows: &'a [Row]) -> Vec<Panel<'a>> {
    let mut out = Vec::new();
    for scene in scenes {
        let mut radii: Vec<f32> = rows
            .iter()
            .filter(|r| scene_of(r) == scene)
            .map(|r| r.radius)
            .collect();
        radii.sort_by(|a, b| a.total_cmp(b));
        radii.dedup();
        for radius in radii {
            out.push(Panel {
                scene: scene.clone(),
                radius,
                rows: rows
                    .iter()
                    .filter(|r| scene_of(r) == scene && r.radius == radius)
                    .collect(),
            });
        }
    }
    out
}

/// Indices of the Pareto front of `(cost, quality)` points, cheapest first: the points that no
/// other point beats on both (costs no more and scores at least as high, better on one). Points
/// with a non-finite coordinate are never on it.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    // By cost, and at equal cost the best first: it alone can be on the front.
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[b].1.total_cmp(&points[a].1))
    });
    let mut front = Vec::new();
    let mut best = f64::NEG_INFINITY;
    for i in order {
        if points[i].1 > best {
            front.push(i);
            best = points[i].1;
        }
    }
    front
}

/// Colours of the methods the engine has (Tableau 10), fixed so that a method looks the same on
/// every chart whatever else is on it.
const METHOD_COLOURS: [(&str, RGBColor); 9] = [
    ("sao-lesson", RGBColor(31, 119, 180)),
    ("sao", RGBColor(255, 127, 14)),
    ("crytek", RGBColor(44, 160, 44)),
    ("hemisphere", RGBColor(214, 39, 40)),
    ("hbao", RGBColor(148, 103, 189)),
    ("angle-based", RGBColor(140, 86, 75)),
    ("gtao", RGBColor(227, 119, 194)),
    ("vbao", RGBColor(23, 190, 207)),
    ("rtao", RGBColor(188, 189, 34)),
];

/// For a method the table does not name: picked by a hash of the name, so still the same on
/// every chart.
const OTHER_COLOURS: [RGBColor; 4] = [
    RGBColor(255, 187, 120),
    RGBColor(127, 127, 127),
    RGBColor(0, 0, 128),
    RGBColor(128, 0, 64),
];

pub fn method_colour(method: &str) -> RGBColor {
    if let Some((_, c)) = METHOD_COLOURS.iter().find(|(m, _)| *m == method) {
        return *c;
    }
    let hash = method.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
    });
    OTHER_COLOURS[(hash % OTHER_COLOURS.len() as u64) as usize]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ao::AoMethod;

    #[test]
    fn pareto_front_of_a_known_set() {
        // (cost, PSNR): 0 cheap and poor, 1 dominated by 0 (dearer, worse), 2 better, 3 the
        // same cost as 2 but worse, 4 dearest and best, 5 dearer than 4 and worse, 6 NaN.
        let points = [
            (1.0, 10.0),
            (2.0, 9.0),
            (3.0, 15.0),
            (3.0, 12.0),
            (5.0, 20.0),
            (6.0, 19.0),
            (f64::NAN, 30.0),
        ];
        assert_eq!(pareto_front(&points), vec![0, 2, 4]);
        assert!(pareto_front(&[]).is_empty());
        // A point that is cheapest and best is the whole front.
        assert_eq!(pareto_front(&[(2.0, 1.0), (1.0, 5.0), (3.0, 4.0)]), vec![1]);
    }

    #[test]
    fn every_method_has_its_own_fixed_colour() {
        let colours: Vec<RGBColor> = AoMethod::ALL
            .iter()
            .map(|m| method_colour(m.name()))
            .collect();
        for (i, c) in colours.iter().enumerate() {
            assert!(
                !colours[..i].contains(c),
                "{:?} shares a colour",
                AoMethod::ALL[i]
            );
            assert!(!OTHER_COLOURS.contains(c));
        }
        assert_eq!(
            method_colour("some-new-method"),
            method_colour("some-new-method")
        );
    }
}
