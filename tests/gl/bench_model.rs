//! `bench --obj`: a model runs as a scene of its own, its cameras framed from its bounds as
//! `render --obj` frames them, with the scene files' train/test variants, and its radii scaled to
//! its size.

use opengl3d::ao::AoMethod;
use opengl3d::res::ResDirs;
use opengl3d::tools::bench::perf;

/// A 200-unit floor with a 40-unit box on it (a model in centimetres, say): bounds
/// (-100, 0, -100)..(100, 40, 100).
fn floor_and_box() -> String {
    let mut s = String::from("o floor\nv -100 0 -100\nv 100 0 -100\nv 100 0 100\nv -100 0 100\n");
    s.push_str("f 1 4 3\nf 1 3 2\no box\n");
    for (x, y, z) in [
        (-20, 0, -20),
        (20, 0, -20),
        (20, 0, 20),
        (-20, 0, 20),
        (-20, 40, -20),
        (20, 40, -20),
        (20, 40, 20),
        (-20, 40, 20),
    ] {
        s.push_str(&format!("v {x} {y} {z}\n"));
    }
    for f in [
        "5 8 7", "5 7 6", "5 6 2", "5 2 1", "6 7 3", "6 3 2", "7 8 4", "7 4 3", "8 5 1", "8 1 4",
    ] {
        let idx: Vec<u32> = f
            .split(' ')
            .map(|i| i.parse::<u32>().unwrap() + 4)
            .collect();
        s.push_str(&format!("f {} {} {}\n", idx[0], idx[1], idx[2]));
    }
    s
}

#[test]
fn a_model_is_framed_from_its_bounds_with_the_scene_variants_and_radii_to_scale() {
    let dir = crate::common::temp_dir("bench-model");
    let obj = dir.join("floor-box.obj");
    std::fs::write(&obj, floor_and_box()).unwrap();
    let cfg = perf::PerfConfig {
        scenes: Vec::new(),
        models: vec![obj],
        width: 64,
        height: 36,
        out: dir.join("out"),
        methods: vec![AoMethod::Sao],
        samples: vec![8],
        radii: Vec::new(),
        qualities: Vec::new(),
        ref_rays: 16,
        screen_rays: 8,
        ref_scale: 2,
        cache: dir.join("cache"),
        warmup: 0,
        frames: 1,
        flip: false,
        charts: true,
        progress: false,
        ceilings: false,
        grid: perf::Grid::Quick,
        scaled: Vec::new(),
    };
    let report = perf::run(&ResDirs::default(), &cfg).expect("bench --obj");
    // Only the model: no demo scene when models are given alone.
    assert_eq!(report.scenes, ["floor-box"]);
    // Its bounding sphere: centre (0, 20, 0), radius half the diagonal of 200 × 40 × 200.
    let half = (200f32 * 200.0 + 40.0 * 40.0 + 200.0 * 200.0).sqrt() * 0.5;
    let cams: Vec<_> = report.cameras.iter().map(|(_, c)| c).collect();
    assert_eq!(cams.len(), 4, "the scene's camera and three variants");
    let train: Vec<bool> = cams.iter().map(|c| c.train).collect();
    assert_eq!(train, [true, false, true, false]);
    for c in &cams {
        assert_eq!(c.target, [0.0, 20.0, 0.0], "{c:?}");
    }
    // The scene's own camera sees the whole sphere: distance r / sin(fov/2) × 1.1.
    let eye = glam::Vec3::from(cams[0].eye);
    let want = half / (cams[0].fov_y.to_radians() * 0.5).sin() * 1.1;
    let got = eye.distance(glam::Vec3::new(0.0, 20.0, 0.0));
    assert!((got - want).abs() < 1e-3 * want, "{got} vs {want}");
    // Radii follow the model: 8 samples at 1 m is 0.2 × half the diagonal here.
    let r0 = ((0.2 * half) * 1e4).round() / 1e4;
    let radii: Vec<f32> = report.rows.iter().map(|r| r.radius).collect();
    assert_eq!(report.rows.len(), 1);
    assert!((radii[0] - r0).abs() < 1e-3 * r0, "{radii:?} vs {r0}");
    // The model is occluded where the box meets the floor: the truth is not all open, and the
    // method is compared on real pixels.
    let row = &report.rows[0];
    assert!(
        row.psnr.is_finite() && row.rmse > 0.0 && row.rmse < 0.5,
        "{row:?}"
    );
    crate::bench_html::check(&cfg.out, 1);
}
