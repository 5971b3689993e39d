//! The bench's error split against the ceiling with each method's own thickness model, whether it
//! adds up, and runs over several scenes. Speed is never asserted.

use opengl3d::ao::AoMethod;
use opengl3d::res::ResDirs;
use opengl3d::tools::bench::perf;

#[test]
fn vbao_is_split_against_slabs_of_its_thickness_on_every_scene() {
    let out = crate::common::temp_dir("bench-split");
    let res = ResDirs::default();
    // The scenes with the keys a method's recommendation covers written out as the struct's
    // defaults (half size, depth normals, no guard band, one layer, vbao's default thickness): the
    // split of one depth layer against slabs of a fixed thickness is what this test checks.
    let scenes: Vec<_> = ["demo", "room"]
        .into_iter()
        .map(|name| {
            let text = std::fs::read_to_string(res.find(&format!("scenes/{name}.toml")).unwrap());
            let plain = "[ao]\nresolution = \"half\"\nnormals = \"depth\"\nguard_band = 0\nlayers = 1\nthickness = 0.25\n";
            let path = out.join("scenes").join(format!("{name}.toml"));
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, text.unwrap().replace("[ao]\n", plain)).unwrap();
            path
        })
        .collect();
    let cfg = perf::PerfConfig {
        scenes,
        models: Vec::new(),
        width: 64,
        height: 36,
        out: out.clone(),
        methods: vec![AoMethod::Gtao, AoMethod::Vbao],
        samples: vec![8],
        radii: vec![0.5],
        qualities: Vec::new(),
        ref_rays: 8,
        screen_rays: 8,
        ref_scale: 1,
        cache: out.join("cache"),
        warmup: 0,
        frames: 1,
        flip: false,
        charts: true,
        progress: false,
        ceilings: true,
        grid: perf::Grid::Full,
        scaled: Vec::new(),
    };
    let report = perf::run(&res, &cfg).expect("bench run");
    // A chart of every row, and one per scene (errors are not comparable across scenes).
    for stem in ["report", "report-demo", "report-room"] {
        for ext in ["png", "svg"] {
            let path = out.join(format!("{stem}.{ext}"));
            let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
            assert!(size > 1000, "{} missing or empty", path.display());
        }
    }
    // vbao's default thickness at R = 0.5 m, a fraction of the radius, as written above.
    let thickness = opengl3d::ao::settings::DEFAULT_THICKNESS_OF_RADIUS * 0.5;
    assert_eq!(thickness, 0.25);
    // One row per scene and method, in scene order.
    assert_eq!(report.scenes, ["demo", "room"]);
    assert_eq!(report.rows.len(), 4);
    for (k, row) in report.rows.iter().enumerate() {
        let scene = if k < 2 { "demo" } else { "room" };
        assert!(row.cameras.iter().all(|c| c.scene == scene), "row {k}");
    }
    // gtao against the heightfield, vbao against slabs of its default thickness, so
    // their depth-buffer errors differ while the ray-traced truth is the same.
    for pair in report.rows.chunks(2) {
        let (gtao, vbao) = (&pair[0], &pair[1]);
        assert_eq!(
            (gtao.method.as_str(), vbao.method.as_str()),
            ("gtao", "vbao")
        );
        assert_eq!(gtao.ceiling_thickness, None);
        assert_eq!(vbao.ceiling_thickness, Some(thickness));
        assert_ne!(gtao.depth_buffer_error.rmse, vbao.depth_buffer_error.rmse);
        for row in pair {
            // parts PSNR is 10·log10(1 / (RMSE_db² + RMSE_s² − 2σ_own²)) of each test camera,
            // averaged. σ² is the screen-space reference's mean squared standard error (8 rays: at
            // most 1/32 per pixel); at the truth's own rays (8 and 8 here) it shares the truth's
            // noise and σ_own = 0.
            let test: Vec<_> = row.cameras.iter().filter(|c| !c.train).collect();
            assert!(!test.is_empty());
            let mut mean = 0.0;
            for c in &test {
                assert!(c.ceiling_noise_rms > 0.0 && c.ceiling_noise_rms <= (0.25f64 / 8.0).sqrt());
                assert_eq!(
                    c.ceiling_own_noise_rms, 0.0,
                    "the ceiling traced the truth's rays"
                );
                let mse = c.depth_buffer_error.rmse.powi(2) + c.sampling_error.rmse.powi(2);
                assert!(mse > 0.0, "{mse}");
                let want = -10.0 * mse.log10();
                assert!(
                    (c.parts_psnr - want).abs() < 1e-9,
                    "{} vs {want}",
                    c.parts_psnr
                );
                mean += want / test.len() as f64;
            }
            assert!((row.parts_psnr - mean).abs() < 1e-9);
            let gap = test
                .iter()
                .map(|c| (c.raw.psnr - c.parts_psnr).abs())
                .fold(0.0, f64::max);
            assert!((row.split_gap_max_db - gap).abs() < 1e-9);
        }
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let vbao_row = format!("| room | vbao | n8 r0.5 | {thickness} m |");
    assert!(md.contains(&vbao_row), "{vbao_row} not in {md}");
    assert!(md.contains("| demo | gtao | n8 r0.5 | ∞ |"), "{md}");
    assert!(md.contains("adds up") && md.contains("10·log10(1 / (RMSE_db² + RMSE_s² − 2σ_own²))"));
    // The per-camera table is one per scene (their cameras differ).
    assert!(
        md.contains("| demo | setting |") && md.contains("| room | setting |"),
        "{md}"
    );
    let json = std::fs::read_to_string(out.join("report.json")).unwrap();
    assert!(!json.contains("null"), "{json}");
}
