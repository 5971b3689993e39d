//! `bench --skips`: each case must really run the skipped passes in one configuration and not in
//! the other (checked by pass names and draw calls, never by timings).

use opengl3d::res::ResDirs;
use opengl3d::tools::bench::skips::{run, SkipsConfig};

#[test]
fn each_skip_drops_its_passes_and_the_report_is_written() {
    let out = std::env::temp_dir().join(format!("opengl3d-skips-{}", std::process::id()));
    let cfg = SkipsConfig {
        scene: None,
        width: 160,
        height: 90,
        out: out.clone(),
        warmup: 0,
        frames: 1,
        progress: false,
    };
    let r = run(&ResDirs::with_override(None), &cfg).expect("skips run");
    let case = |n: &str| {
        r.cases
            .iter()
            .find(|c| c.name.starts_with(n))
            .unwrap_or_else(|| panic!("case {n}"))
    };
    let ao_off = case("AO off");
    for p in ["sao restore depth", "sao down sampling", "sao composite"] {
        assert!(
            ao_off.passes_not_run.iter().any(|q| q == p),
            "{p} should not run with AO off: {:?}",
            ao_off.passes_not_run
        );
    }
    assert!(ao_off.skipped.passes.iter().all(|p| !p.starts_with("sao")));
    let depth_view = case("linear-depth view");
    assert!(depth_view
        .skipped
        .passes
        .iter()
        .any(|p| p == "sao down sampling"));
    assert!(
        !depth_view.passes_not_run.is_empty(),
        "the AO method and blur"
    );
    assert_eq!(case("no shadow").passes_not_run, ["shadow map"]);
    assert_eq!(case("bloom off").passes_not_run, ["bloom"]);
    let cull = case("frustum culling");
    assert!(
        cull.skipped.draw_calls < cull.needed.draw_calls,
        "culling must drop draw calls when facing away: {} → {}",
        cull.needed.draw_calls,
        cull.skipped.draw_calls
    );
    assert!(r.ao_target_bytes_on > 0);
    assert_eq!(r.ao_target_bytes_off, 0, "AO off allocates no AO target");
    for c in &r.cases {
        assert!(
            c.needed.frame_ms.is_finite() && c.ratio.is_finite(),
            "{}",
            c.name
        );
    }
    let md = std::fs::read_to_string(out.join("skips.md")).unwrap();
    assert!(md.contains("| AO off |"), "{md}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("skips.json")).unwrap()).unwrap();
    assert_eq!(json["cases"].as_array().unwrap().len(), r.cases.len());
    std::fs::remove_dir_all(out).unwrap();
}
