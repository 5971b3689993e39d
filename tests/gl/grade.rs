//! The grader (`opengl3d grade`) run as a student would run it, against tests/mutants/: each folder
//! holds one lesson shader. `listing-*` are the lesson's listings typed as printed (errata fixed) and
//! `rewrite-*` correct shaders written differently: they must pass. The others are typical mistakes:
//! they must fail, with a message that names the problem.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn mutant(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/mutants")
        .join(name)
}

fn temp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    match std::fs::remove_dir_all(&d) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => panic!("{}: {e}", d.display()),
        _ => {}
    }
    std::fs::create_dir_all(&d).unwrap();
    d
}

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

impl Run {
    fn json(&self) -> Value {
        serde_json::from_str(self.stdout.trim()).unwrap_or_else(|e| {
            panic!(
                "grade --json printed no JSON ({e}):\n{}\n{}",
                self.stdout, self.stderr
            )
        })
    }
}

/// Runs `opengl3d grade ARGS`, at `--level course` unless ARGS name a level: the tests of the
/// lessons' mechanics use the course's listings, which pass there.
fn grade(res: Option<&Path>, args: &[&str]) -> Run {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_opengl3d"));
    if let Some(r) = res {
        cmd.arg("--res").arg(r);
    }
    cmd.arg("grade").args(args);
    if !args.contains(&"--level") {
        cmd.args(["--level", "course"]);
    }
    let o = cmd.output().expect("run opengl3d");
    Run {
        code: o.status.code(),
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
    }
}

/// The report must have exactly {"passed", "level", "steps": [{"step", "file", "passed",
/// "submitted", "message", "parts"?}]}; each part {"part", "passed", "message", "erratum"?}, and a
/// step with parts passes exactly when all of them do.
fn check_shape(v: &Value) {
    let top = v.as_object().expect("a JSON object");
    let mut keys: Vec<&str> = top.keys().map(String::as_str).collect();
    keys.sort();
    assert_eq!(keys, ["level", "passed", "steps"], "{v}");
    assert!(top["passed"].is_boolean());
    assert!(
        ["course", "lesson"].contains(&top["level"].as_str().unwrap()),
        "{v}"
    );
    for s in top["steps"].as_array().expect("steps is an array") {
        let o = s.as_object().expect("each step is an object");
        let mut keys: Vec<&str> = o
            .keys()
            .map(String::as_str)
            .filter(|k| *k != "parts")
            .collect();
        keys.sort();
        assert_eq!(
            keys,
            ["file", "message", "passed", "step", "submitted"],
            "{s}"
        );
        assert!(o["passed"].is_boolean() && o["message"].is_string());
        assert!(o["submitted"].is_boolean());
        if let Some(parts) = o.get("parts") {
            let parts = parts.as_array().expect("parts is an array");
            assert!(!parts.is_empty(), "{s}");
            for p in parts {
                let p = p.as_object().expect("each part is an object");
                let mut keys: Vec<&str> = p.keys().map(String::as_str).collect();
                keys.retain(|k| *k != "erratum");
                keys.sort();
                assert_eq!(keys, ["message", "part", "passed"], "{s}");
            }
            let all = parts.iter().all(|p| p["passed"].as_bool().unwrap());
            assert_eq!(o["passed"].as_bool(), Some(all), "{s}");
        }
    }
}

/// The step a mutant folder's only lesson shader belongs to (other files are its includes).
fn step_of(dir: &Path) -> &'static str {
    let file = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .find(|f| f.ends_with(".frag"))
        .expect("a mutant folder holds one shader");
    match file.as_str() {
        "sao_restore_depth.frag" => "restore",
        "sao_down_sampling.frag" => "down-sampling",
        "simple.frag" => "simple",
        "sao.frag" => "sao",
        "sao_blur.frag" => "blur",
        f => panic!("{f} is not a lesson shader"),
    }
}

/// Grades mutant `name` on its own step; checks the verdict and that the message holds `needles`.
fn expect(name: &str, pass: bool, needles: &[&str]) {
    expect_at(name, "lesson", pass, needles)
}

/// `expect` at `--level level`.
fn expect_at(name: &str, level: &str, pass: bool, needles: &[&str]) {
    let dir = mutant(name);
    let step = step_of(&dir);
    let run = grade(Some(&dir), &["--json", "--level", level, "--step", step]);
    let v = run.json();
    check_shape(&v);
    let s = &v["steps"][0];
    let message = s["message"].as_str().unwrap();
    eprintln!("{name}: {message}");
    assert_eq!(v["steps"].as_array().unwrap().len(), 1);
    assert_eq!(s["step"], step);
    assert_eq!(
        s["passed"].as_bool(),
        Some(pass),
        "{name} should {}: {message}",
        if pass { "pass" } else { "fail" }
    );
    assert_eq!(v["passed"].as_bool(), Some(pass));
    assert_eq!(run.code, Some(if pass { 0 } else { 1 }), "exit code");
    for n in needles {
        assert!(
            message.contains(n),
            "{name}: '{message}' should mention '{n}'"
        );
    }
}

macro_rules! passes {
    ($($test:ident: $dir:literal),* $(,)?) => {$(
        #[test]
        fn $test() {
            expect_at($dir, "course", true, &[]);
        }
    )*};
}

/// Mistakes that only `--level lesson` (what the pages teach beyond the listings) rejects.
macro_rules! fails_at_lesson {
    ($($test:ident: $dir:literal => [$($needle:literal),*]),* $(,)?) => {$(
        #[test]
        fn $test() {
            expect_at($dir, "lesson", false, &[$($needle),*]);
            expect_at($dir, "course", true, &[]);
        }
    )*};
}

macro_rules! fails {
    ($($test:ident: $dir:literal => [$($needle:literal),*]),* $(,)?) => {$(
        #[test]
        fn $test() {
            expect($dir, false, &[$($needle),*]);
        }
    )*};
}

passes! {
    listing_restore_passes: "listing-restore",
    listing_restore_saved_as_shift_jis_passes: "listing-restore-shift-jis",
    listing_down_sampling_passes: "listing-down-sampling",
    listing_sao_passes: "listing-sao",
    listing_sao_with_normal_guard_passes: "listing-sao-guarded",
    listing_blur_passes: "listing-blur",
    listing_simple_passes: "listing-simple",
    rewritten_simple_passes: "rewrite-simple",
    rewritten_restore_passes: "rewrite-restore",
    rewritten_down_sampling_passes: "rewrite-down-sampling",
    rewritten_sao_passes: "rewrite-sao",
    rewritten_sao_with_an_include_passes: "rewrite-sao-include",
    rewritten_blur_passes: "rewrite-blur",
}

/// The lesson's `sao.frag` written differently (the hash bracketed the other way, the loop from 1 to N
/// with (i − 0.5) / N, the spiral turned the other way, `normalize`): every measure of what the pages
/// fix must leave it its noise.
#[test]
fn a_rewritten_lesson_sao_passes_at_both_levels() {
    expect_at("rewrite-sao-lesson", "lesson", true, &[]);
    expect_at("rewrite-sao-lesson", "course", true, &[]);
}

fails! {
    restore_with_the_wrong_sign_fails: "restore-wrong-sign" => ["wrong sign at z=10 m: got -10.0"],
    restore_with_max_fails: "restore-max" => ["max instead of min"],
    restore_without_times_two_fails: "restore-no-x2" => ["gl_FragCoord.xy) * 2"],
    restore_with_the_debug_scale_left_fails: "restore-debug-scale" => ["0.01", "got 0.100"],
    restore_with_2d_plus_1_fails: "restore-2d-plus-1" => ["D′ = 2D - 1, not 2D + 1", "a typo in the course's printed text", "depth = 2 * depth - 1;"],
    restore_not_text_is_rejected_by_name: "restore-not-text" => ["restore-not-text/sao_restore_depth.frag", "neither UTF-8, UTF-16 nor Shift-JIS"],
    down_sampling_with_max_fails: "down-sampling-max" => ["max instead of min"],
    down_sampling_without_times_two_fails: "down-sampling-no-x2" => ["gl_FragCoord.xy) * 2"],
    down_sampling_reading_level_0_fails: "down-sampling-level-0" => ["pass mipLevel"],
    down_sampling_with_a_float_mip_level_names_the_declaration: "down-sampling-float-mip-level" => ["location 200 (mipLevel) is declared as float", "type int", "`layout(location=200) uniform int mipLevel`"],
    down_sampling_without_the_layout_names_it: "down-sampling-no-layout" => ["mipLevel is at location", "not 200", "`layout(location=200) uniform int mipLevel`"],
    simple_broadcasting_red_fails: "simple-wrong-channel" => ["(r, r, r, r)", "reads the occlusion from alpha", "outColor = texture(texColor, inTexcoord)"],
    simple_with_alpha_one_fails: "simple-alpha-one" => ["(r, g, b, 1)", "alpha must be copied too"],
    simple_with_swapped_channels_fails: "simple-swapped" => ["(b, g, r, a)", "swapped"],
    simple_upside_down_fails: "simple-flipped" => ["upside down"],
    simple_reading_single_texels_fails: "simple-texel-fetch" => ["reads single texels instead of filtering"],
    simple_on_the_wrong_unit_names_the_binding: "simple-binding-1" => ["texColor reads texture unit 1", "`layout(binding=0) uniform sampler2D texColor`"],
    sao_writing_inside_the_loop_fails: "sao-output-in-loop" => ["not normalised", "expected about 0."],
    sao_with_a_flipped_normal_fails: "sao-flipped-normal" => ["cross product's order is reversed", "cross(dpdx, dpdy)"],
    sao_with_a_flipped_view_z_names_get_view_space_position: "sao-view-z-flipped" => ["GetViewSpacePosition must return z = -linearDepth"],
    sao_with_the_bias_added_names_its_sign: "sao-bias-plus" => ["vn + BIAS", "wrong sign", "max((vn - BIAS) / (vv + 0.001), 0)"],
    sao_with_a_derivative_in_a_branch_names_the_line_and_erratum_22: "sao-derivative-in-branch" => ["derivative is called inside a branch", "sao.frag:114", "appendix A #22"],
    sao_without_the_clamp_fails: "sao-no-clamp" => ["max(…, 0)"],
    sao_reading_only_level_0_fails: "sao-level-0" => ["never reads the mip levels 1–3", "textureLod(texDepth, uv, float(mipLevel))", "findMSB(int(ratio * pixelsSS))"],
    sao_with_a_squared_falloff_fails: "sao-falloff-squared" => ["f * f * f", "fades too slowly"],
    sao_with_a_compile_error_names_file_and_line: "sao-compile-error" => ["does not compile", "sao-compile-error/sao.frag:83:"],
    sao_including_an_absolute_path_is_refused_unread: "sao-include-absolute" => ["sao-include-absolute/sao.frag:3: #include \"/etc/passwd\" is an absolute path"],
    sao_including_from_above_its_folder_is_refused_unread: "sao-include-parent" => ["sao-include-parent/sao.frag:3: #include \"../rewrite-sao-include/sao_helpers.glsl\" goes up with '..'"],
    blur_without_normalisation_fails: "blur-no-normalise" => ["not normalised", "running total of the weights"],
    blur_without_the_edge_weight_fails: "blur-no-edge-weight" => ["across a depth edge"],
    blur_ignoring_blur_scale_fails: "blur-no-blur-scale" => ["reads the wrong texels", "ivec2(gl_FragCoord.xy) + ivec2(x, y) * 2"],
    blur_with_an_edge_distance_ten_times_too_large_fails: "blur-edge-distance-x10" => ["across a depth edge"],
    sao_without_the_2x2_smoothing_fails: "sao-no-smoothing" => ["2×2 smoothing"],
    sao_with_the_2x2_smoothing_of_the_wrong_sign_fails: "sao-smoothing-wrong-sign" => ["2×2 smoothing"],
    sao_with_the_mip_level_inverted_fails: "sao-mip-level-inverted" => ["flat and open but occluded"],
    blur_without_its_sky_test_blurs_the_sky: "blur-no-sky-test" => ["sky texels are blurred", "if (depth >= CAMERA_FAR) { return; }"],
    blur_with_a_strict_sky_test_blurs_the_sky: "blur-sky-test-strict" => ["sky texels are blurred", "with >=", "if (depth >= CAMERA_FAR) { return; }"],
    blur_without_its_clamp_fails_at_the_border: "blur-no-clamp" => ["reads past the texture's border", "clamp(ivec2(gl_FragCoord.xy) + ivec2(x, y) * 2, ivec2(0), textureSize(texColor, 0) - 1)"],
    blur_clamped_to_the_transposed_size_fails: "blur-clamp-swapped" => ["reads past the texture's border"],
    sao_with_ndc_to_view_swapped_fails: "sao-ndc-swapped" => ["stretched along x or y", "x by ndcToView.x"],
    sao_without_the_aspect_fix_fails: "sao-no-aspect-fix" => ["stretched along x or y", "aspectFix = (height / width, 1)"],
    sao_never_divided_by_the_sample_count_is_too_strong: "sao-no-divide" => ["too strong", "about the sample count (11)", "not divided by samplingCount"],
    sao_writing_inf_is_told_so: "sao-writes-inf" => ["writes Inf or NaN", "Inf at 100.0%"],
    sao_including_itself_is_an_include_cycle: "sao-include-self" => ["sao-include-self/sao.frag:3: #include \"sao.frag\"", "#include cycle"],
    blur_with_an_edge_distance_twice_too_large_fails: "blur-edge-distance-x2" => ["depth step of 0.05 m weigh 0.83", "gives 0.67"],
    sao_clamped_at_half_fails: "sao-clamped-at-half" => ["fully occluded pixels stay at 0.5", "min(1.0,"],
    sao_with_a_falloff_below_zero_fails: "sao-falloff-below-zero" => ["post 1.5 m in front of the wall", "must count 0", "f = max(RADIUS2 - vv, 0)"],
}

/// The SAO step of `res` (the project's files when `None`) at `--level level` with `--points`:
/// (points, max points, [(part, passed, points, erratum, message)]).
type Part = (String, bool, u64, Option<String>, String);
fn sao_parts(res: Option<&Path>, level: &str) -> (u64, u64, Vec<Part>) {
    let run = grade(
        res,
        &["--json", "--points", "--level", level, "--step", "sao"],
    );
    let v = run.json();
    assert_eq!(v["level"], level, "{v}");
    let s = &v["steps"][0];
    let parts = s["parts"]
        .as_array()
        .unwrap_or_else(|| panic!("sao has parts: {v}"))
        .iter()
        .map(|p| {
            (
                p["part"].as_str().unwrap().to_string(),
                p["passed"].as_bool().unwrap(),
                p["points"].as_u64().unwrap(),
                p["erratum"].as_str().map(str::to_string),
                p["message"].as_str().unwrap().to_string(),
            )
        })
        .collect::<Vec<_>>();
    let earned: u64 = parts.iter().map(|p| p.2).sum();
    assert_eq!(
        s["points"].as_u64(),
        Some(earned),
        "a step's points are its parts': {v}"
    );
    assert_eq!(v["points"].as_u64(), Some(earned), "{v}");
    (earned, s["max_points"].as_u64().unwrap(), parts)
}

/// The parts of `parts` that failed.
fn failing(parts: &[Part]) -> Vec<&str> {
    parts
        .iter()
        .filter(|p| !p.1)
        .map(|p| p.0.as_str())
        .collect()
}

fails_at_lesson! {
    sao_without_the_edge_guard_draws_outlines: "sao-no-edge-guard" => ["dark outlines around every object", "bool onEdge = max(abs(dpdx.z), abs(dpdy.z)) > 0.1 * depth;"],
    sao_without_the_mip_bias_mottles_the_floor: "sao-no-mip-bias" => ["mottled grey", "float mipBias = float((1 << mipLevel) - 1)"],
    sao_without_the_texel_snap_occludes_itself: "sao-no-texel-snap" => ["occludes itself", "uv = (floor(clamp(uv, vec2(0), vec2(1)) * size) + 0.5) / size;"],
    sao_without_the_2cm_test_smears: "sao-no-2cm-test" => ["grey smears across silhouettes", "|Δz| < 0.02"],
    sao_with_the_thresholds_swapped_smears: "sao-thresholds-swapped" => ["grey smears across silhouettes", "wrong axis"],
    sao_with_both_derivatives_first_halves: "sao-derivatives-before" => ["instead of the mean of the quad", "float dOccY = dFdy(occlusion);"],
    sao_with_the_edge_guard_at_20_percent_draws_outlines: "sao-guard-20-percent" => ["silhouettes 12–18 % deep", "> 0.1 * depth"],
    sao_with_weighted_smoothing_misses_the_mean: "sao-smoothing-weighted" => ["does not leave the pair's mean", "(float(iuv.x & 1) - 0.5)"],
    sao_with_a_4cm_test_smears: "sao-threshold-4cm" => ["2.4–3.6 cm per pixel are evened out", "abs(dpdy.z) < 0.02"],
    sao_without_the_uv_clamp_occludes_the_border: "sao-no-uv-clamp" => ["border occludes itself", "clamp(uv, vec2(0), vec2(1))"],
    sao_with_another_epsilon_fails_on_a_small_disc: "sao-epsilon-0-01" => ["5 cm sampling radius", "(vv + 0.001), 0)"],
    sao_with_the_loop_from_1_loses_its_first_tap: "sao-loop-from-1" => ["right beside small raised squares", "float ratio = (float(i) + 0.5) * (1.0 / samplingCount);"],
    sao_with_one_tap_more_fails_on_a_small_disc: "sao-one-tap-more" => ["5 cm sampling radius", "ratio = (i + 0.5) / N"],
    restore_leaving_the_sky_at_1000_014_fails: "restore-sky-not-far" => ["instead of exactly 1000 (far)", "if (depth >= 1.0) { outColor = far; return; }"],
}

#[test]
fn a_blur_with_the_courses_gaussian_table_is_the_reference_behaviour() {
    // McGuire and Mara's SAO_blur.pix adds 0.3 to every tap's weight but the centre's; the course
    // folded that into its table. The listing keeps the table, the project's blur does not: both
    // are the reference to within float precision, not 0.032 apart.
    for (name, table) in [("listing-blur", "0.444893"), ("rewrite-blur", "0.144893")] {
        let source = std::fs::read_to_string(mutant(name).join("sao_blur.frag")).unwrap();
        assert!(source.contains(table), "{name} has the table {table}");
        expect_at(name, "lesson", true, &["RMSE 0.000 against the reference"]);
    }
}

#[test]
fn a_correct_sao_gets_every_part() {
    // The project's at the lesson level, a rewrite of the listing at the course's.
    for (res, level) in [(None, "lesson"), (Some(mutant("rewrite-sao")), "course")] {
        let (earned, max, parts) = sao_parts(res.as_deref(), level);
        assert_eq!((earned, max), (50, 50), "{parts:?}");
        let ids: Vec<&str> = parts.iter().map(|p| p.0.as_str()).collect();
        assert_eq!(
            ids,
            [
                "sao.normal",
                "sao.sampling",
                "sao.occlusion",
                "sao.smoothing",
                "sao.view"
            ]
        );
    }
}

#[test]
fn a_smoothing_of_the_wrong_sign_loses_only_the_smoothing() {
    // The lesson's code with the sign flipped, at the lesson level; the listing with it, at the
    // course's.
    for (name, level) in [
        ("sao-smoothing-sign-flipped", "lesson"),
        ("sao-smoothing-wrong-sign", "course"),
    ] {
        let (earned, max, parts) = sao_parts(Some(&mutant(name)), level);
        assert_eq!(failing(&parts), ["sao.smoothing"], "{name}: {parts:?}");
        assert_eq!((earned, max), (40, 50), "{name}");
    }
}

#[test]
fn the_courses_text_gets_the_parts_its_erratum_does_not_touch_and_the_erratum_is_named() {
    let (earned, _, parts) = sao_parts(Some(&mutant("course-sao")), "course");
    assert_eq!(
        failing(&parts),
        ["sao.sampling", "sao.smoothing"],
        "{parts:?}"
    );
    assert_eq!(earned, 30);
    let (sampling, smoothing) = (&parts[1], &parts[3]);
    assert_eq!(
        sampling.3.as_deref(),
        Some("appendix A #20: the sampling disc in texture coordinates, stretched by the aspect ratio")
    );
    assert!(
        sampling.4.contains("appendix A #20") && sampling.4.contains("aspectFix"),
        "{sampling:?}"
    );
    assert_eq!(
        smoothing.3.as_deref(),
        Some("appendix A #22: dFdx(occlusion) inside a branch")
    );
    assert!(smoothing.4.contains("appendix A #22"), "{smoothing:?}");
}

#[test]
fn a_mistake_that_leaves_nothing_to_measure_fails_the_rest_saying_so() {
    let (earned, _, parts) = sao_parts(Some(&mutant("sao-view-z-flipped")), "lesson");
    assert_eq!(earned, 0);
    assert!(parts[0].4.contains("-linearDepth"), "{parts:?}");
    for p in &parts[1..] {
        assert!(
            p.4.contains("not measured") && p.4.contains("view position and normal (lesson 6)"),
            "{p:?}"
        );
    }
}

#[test]
fn sub_step_points_are_taken_from_the_command_line() {
    let run = grade(
        Some(&mutant("sao-smoothing-wrong-sign")),
        &[
            "--json",
            "--points",
            "sao.smoothing=20,sao.view=5",
            "--step",
            "sao",
        ],
    );
    let v = run.json();
    assert_eq!(
        (v["points"].as_u64(), v["max_points"].as_u64()),
        (Some(35), Some(55)),
        "{v}"
    );
}

#[test]
fn the_projects_own_shaders_pass() {
    let run = grade(None, &["--json", "--level", "lesson"]);
    let v = run.json();
    check_shape(&v);
    let steps: Vec<&str> = v["steps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["step"].as_str().unwrap())
        .collect();
    assert_eq!(steps, ["restore", "down-sampling", "simple", "sao", "blur"]);
    assert_eq!(v["passed"], true, "{v}");
    assert_eq!(run.code, Some(0));
}

#[test]
fn a_student_with_every_listing_passes_and_gets_pictures() {
    let dir = temp_dir("grade-listings");
    for (m, f) in [
        ("listing-restore", "sao_restore_depth.frag"),
        ("listing-down-sampling", "sao_down_sampling.frag"),
        ("listing-simple", "simple.frag"),
        ("listing-sao", "sao.frag"),
        ("listing-blur", "sao_blur.frag"),
    ] {
        std::fs::copy(mutant(m).join(f), dir.join(f)).unwrap();
    }
    let out = dir.join("pictures");
    let run = grade(Some(&dir), &["--json", "--out", out.to_str().unwrap()]);
    let v = run.json();
    check_shape(&v);
    assert_eq!(v["passed"], true, "{v}");
    assert_eq!(v["steps"].as_array().unwrap().len(), 5);
    for s in v["steps"].as_array().unwrap() {
        assert!(
            !s["message"].as_str().unwrap().contains("project's file"),
            "{s}"
        );
    }
    for step in ["restore", "down-sampling", "simple", "sao", "blur"] {
        for kind in ["expected", "actual", "difference"] {
            let p = out.join(format!("{step}-{kind}.png"));
            let img = image::open(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert!(img.width() > 8 && img.height() > 4);
        }
    }
}

#[test]
fn an_empty_folder_passes_nothing() {
    let dir = temp_dir("grade-empty");
    let run = grade(Some(&dir), &["--json"]);
    let v = run.json();
    check_shape(&v);
    assert_eq!(run.code, Some(1), "{v}");
    assert_eq!(v["passed"], false);
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 5);
    for s in steps {
        let file = s["file"].as_str().unwrap();
        assert_eq!(s["passed"], false, "{s}");
        assert_eq!(s["submitted"], false, "{s}");
        let message = s["message"].as_str().unwrap();
        assert_eq!(
            message,
            format!("not submitted: no {file} in {}", dir.display())
        );
    }
    // The text report too: no PASS line.
    let run = grade(Some(&dir), &[]);
    assert_eq!(run.code, Some(1));
    assert!(!run.stdout.contains("PASS"), "{}", run.stdout);
    assert_eq!(run.stdout.matches("FAIL").count(), 5, "{}", run.stdout);
}

#[test]
fn a_folder_named_like_the_shader_is_not_a_submission() {
    let dir = temp_dir("grade-folder-named-sao");
    std::fs::create_dir_all(dir.join("sao.frag")).unwrap();
    let run = grade(Some(&dir), &["--json", "--step", "sao"]);
    let v = run.json();
    check_shape(&v);
    assert_eq!(run.code, Some(1));
    let s = &v["steps"][0];
    assert_eq!(
        (&s["passed"], &s["submitted"]),
        (&false.into(), &false.into())
    );
    let message = s["message"].as_str().unwrap();
    assert!(message.starts_with("not submitted: "), "{message}");
    assert!(message.contains("sao.frag is a folder"), "{message}");
}

#[test]
fn a_misnamed_file_is_not_submitted_and_named() {
    let dir = temp_dir("grade-misnamed");
    std::fs::copy(
        mutant("listing-sao").join("sao.frag"),
        dir.join("Sao.frag.txt"),
    )
    .unwrap();
    let run = grade(Some(&dir), &["--json", "--step", "sao"]);
    let v = run.json();
    assert_eq!(run.code, Some(1));
    assert_eq!(v["steps"][0]["submitted"], false);
    let message = v["steps"][0]["message"].as_str().unwrap();
    assert!(
        message.contains("found Sao.frag.txt: rename it to sao.frag"),
        "{message}"
    );
}

#[test]
fn a_partial_folder_grades_only_what_was_submitted() {
    // Lesson step 4 needs the restore and down-sampling shaders; the student has only the first.
    let dir = temp_dir("grade-partial");
    std::fs::copy(
        mutant("listing-restore").join("sao_restore_depth.frag"),
        dir.join("sao_restore_depth.frag"),
    )
    .unwrap();
    let run = grade(Some(&dir), &["--json", "--lesson", "4"]);
    let v = run.json();
    check_shape(&v);
    assert_eq!(run.code, Some(1), "{v}");
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 2);
    assert_eq!(steps[0]["step"], "restore");
    assert_eq!(steps[0]["passed"], true, "{v}");
    assert_eq!(steps[0]["submitted"], true, "{v}");
    assert_eq!(steps[1]["step"], "down-sampling");
    assert_eq!(steps[1]["passed"], false, "{v}");
    assert_eq!(steps[1]["submitted"], false, "{v}");
}

#[test]
fn a_shader_over_one_mib_is_refused_by_name_and_size() {
    let dir = temp_dir("grade-huge-file");
    let mut text = std::fs::read(mutant("listing-sao").join("sao.frag")).unwrap();
    text.resize(1 << 21, b'\n');
    std::fs::write(dir.join("sao.frag"), &text).unwrap();
    let run = grade(Some(&dir), &["--json", "--step", "sao"]);
    let v = run.json();
    assert_eq!(run.code, Some(1));
    let message = v["steps"][0]["message"].as_str().unwrap();
    assert!(message.contains("grade-huge-file"), "{message}");
    assert!(message.contains("sao.frag"), "{message}");
    assert!(message.contains("2097152 bytes"), "{message}");
}

#[test]
fn an_endless_loop_times_out_and_grading_goes_on() {
    // Lesson step 8: the restore, down-sampling and simple listings, and an SAO that never ends.
    let dir = temp_dir("grade-endless");
    for (m, f) in [
        ("listing-restore", "sao_restore_depth.frag"),
        ("listing-down-sampling", "sao_down_sampling.frag"),
        ("listing-simple", "simple.frag"),
        ("sao-endless-loop", "sao.frag"),
    ] {
        std::fs::copy(mutant(m).join(f), dir.join(f)).unwrap();
    }
    let run = grade(Some(&dir), &["--json", "--lesson", "8", "--timeout", "6"]);
    let v = run.json();
    check_shape(&v);
    assert_eq!(v["passed"], false);
    assert_eq!(run.code, Some(1));
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 4);
    for s in &steps[..3] {
        assert_eq!(s["passed"], true, "{v}");
    }
    assert_eq!(steps[3]["step"], "sao");
    let message = steps[3]["message"].as_str().unwrap();
    assert!(message.contains("timed out after 6 s"), "{message}");
}

/// The step names `--lesson N` grades (on an empty folder: all "not submitted").
fn lesson_steps(n: &str) -> Vec<String> {
    let dir = temp_dir(&format!("grade-lesson-{n}-steps"));
    let v = grade(Some(&dir), &["--json", "--lesson", n]).json();
    v["steps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["step"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn simple_frag_is_graded_from_lesson_step_5_on() {
    assert_eq!(lesson_steps("4"), ["restore", "down-sampling"]);
    assert_eq!(lesson_steps("5"), ["restore", "down-sampling", "simple"]);
    assert_eq!(lesson_steps("12").len(), 5);
    // Missing, it is not submitted (not graded on the project's file).
    let dir = temp_dir("grade-no-simple");
    std::fs::copy(mutant("listing-sao").join("sao.frag"), dir.join("sao.frag")).unwrap();
    let run = grade(Some(&dir), &["--json", "--step", "simple"]);
    let v = run.json();
    check_shape(&v);
    assert_eq!(run.code, Some(1));
    let s = &v["steps"][0];
    assert_eq!(
        (&s["passed"], &s["submitted"]),
        (&false.into(), &false.into())
    );
    assert_eq!(
        s["message"],
        format!("not submitted: no simple.frag in {}", dir.display())
    );
}

/// A student at lesson 6 or 7: restore, down-sampling and simple written, and the start of sao.frag
/// with lesson 6's debug output.
fn lesson_6_folder(name: &str, sao: &str) -> PathBuf {
    let dir = temp_dir(name);
    for (m, f) in [
        ("listing-restore", "sao_restore_depth.frag"),
        ("listing-down-sampling", "sao_down_sampling.frag"),
        ("listing-simple", "simple.frag"),
        (sao, "sao.frag"),
    ] {
        std::fs::copy(mutant(m).join(f), dir.join(f)).unwrap();
    }
    dir
}

#[test]
fn lessons_6_and_7_check_the_start_of_sao_and_say_when_it_is_graded() {
    for (n, sao) in [
        ("6", "sao-lesson-6"),
        ("6", "rewrite-sao-lesson-6"),
        ("7", "sao-lesson-7"),
    ] {
        let dir = lesson_6_folder(&format!("grade-lesson-{n}-{sao}"), sao);
        let run = grade(Some(&dir), &["--json", "--lesson", n]);
        let v = run.json();
        check_shape(&v);
        assert_eq!(run.code, Some(0), "lesson {n}, {sao}: {v}");
        let steps = v["steps"].as_array().unwrap();
        assert_eq!(steps.len(), 4, "{v}");
        assert_eq!(steps[3]["step"], "sao");
        let message = steps[3]["message"].as_str().unwrap();
        assert!(
            message.contains(&format!("lesson {n}'s checkpoint matches"))
                && message.contains("graded from lesson 8 on"),
            "{message}"
        );
    }
    // The lessons' typical mistakes in their debug views are named.
    for (n, sao, needles) in [
        (
            "6",
            "sao-lesson-6-flipped-normal",
            ["points away from the camera", "cross(dpdx, dpdy)"],
        ),
        (
            "7",
            "sao-lesson-7-log-mip-offset-4",
            ["one mip level finer", "logMipOffset is 3"],
        ),
        (
            "6",
            "sao-lesson-6-no-debug-line",
            [
                "writes 0 at every pixel",
                "put the checkpoint's outColor line back",
            ],
        ),
        (
            "6",
            "sao-lesson-7",
            ["lesson 6's checkpoint differs", "expected"],
        ),
    ] {
        let dir = lesson_6_folder(&format!("grade-lesson-{n}-{sao}"), sao);
        let run = grade(Some(&dir), &["--json", "--lesson", n]);
        let v = run.json();
        assert_eq!(run.code, Some(1), "lesson {n}, {sao}: {v}");
        let message = v["steps"][3]["message"].as_str().unwrap();
        for needle in needles {
            assert!(
                message.contains(needle),
                "{sao}: '{message}' should mention '{needle}'"
            );
        }
    }
    // What each lesson asks is still checked: the interface it declares...
    let broken = lesson_6_folder("grade-lesson-6-no-layout", "sao-lesson-6-no-layout");
    let run = grade(Some(&broken), &["--json", "--lesson", "6"]);
    let v = run.json();
    assert_eq!(run.code, Some(1), "{v}");
    let message = v["steps"][3]["message"].as_str().unwrap();
    assert!(
        message.contains("ndcToView is at location")
            && message.contains("`layout(location=201) uniform vec2 ndcToView`"),
        "{message}"
    );
    // ...and what it reads: lesson 7 sizes the disc with saoInfo, which lesson 6's start never reads;
    // the untouched stub writes 0.
    let dir = lesson_6_folder("grade-lesson-7-with-6", "sao-lesson-6");
    let run = grade(Some(&dir), &["--json", "--lesson", "7"]);
    let v = run.json();
    assert_eq!(run.code, Some(1), "{v}");
    let message = v["steps"][3]["message"].as_str().unwrap();
    assert!(
        message.contains("never reads the uniform at location 200") && message.contains("saoInfo"),
        "{message}"
    );
    let stub = lesson_6_folder("grade-lesson-6-stub", "sao-lesson-6");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("Res/lesson-stubs/sao.frag"),
        stub.join("sao.frag"),
    )
    .unwrap();
    let run = grade(Some(&stub), &["--json", "--lesson", "6"]);
    let v = run.json();
    assert_eq!(run.code, Some(1), "{v}");
    let message = v["steps"][3]["message"].as_str().unwrap();
    assert!(message.contains("still the stub"), "{message}");
    // From lesson 8 on, the debug view is graded as SAO, and fails.
    let run = grade(Some(&dir), &["--json", "--lesson", "8"]);
    let v = run.json();
    assert_eq!(run.code, Some(1), "{v}");
    assert_eq!(v["steps"][3]["passed"], false, "{v}");
    // --step grades a file in full, which --lesson does not: the two cannot go together.
    let run = grade(Some(&dir), &["--json", "--lesson", "7", "--step", "sao"]);
    assert_eq!(run.code, Some(2), "{}", run.stdout);
    assert!(run.stdout.is_empty(), "{}", run.stdout);
    assert!(
        run.stderr.contains("cannot be used with")
            && run.stderr.contains("--step")
            && run.stderr.contains("--lesson"),
        "{}",
        run.stderr
    );
}

/// A student at lesson 8 or 9: the other files are the listings, `sao.frag` is `sao`'s.
fn lesson_8_folder(name: &str, sao: &str) -> PathBuf {
    let dir = lesson_6_folder(name, sao);
    std::fs::remove_file(dir.join("sao_restore_depth.frag")).unwrap();
    std::fs::remove_file(dir.join("sao_down_sampling.frag")).unwrap();
    std::fs::remove_file(dir.join("simple.frag")).unwrap();
    dir
}

/// The SAO verdict of `grade --lesson N` on `dir` (whose other steps are not submitted).
fn sao_at_lesson(dir: &Path, n: &str) -> (bool, String) {
    let v = grade(Some(dir), &["--json", "--lesson", n]).json();
    check_shape(&v);
    let steps = v["steps"].as_array().unwrap();
    let s = steps
        .iter()
        .find(|s| s["step"] == "sao")
        .expect("an sao step");
    (
        s["passed"].as_bool().unwrap(),
        s["message"].as_str().unwrap().to_string(),
    )
}

#[test]
fn lesson_8_grades_the_occlusion_without_the_smoothing_of_lesson_9() {
    // sao.frag as lesson 8 has it: occlusion clamped, no 2×2 smoothing yet.
    let dir = lesson_8_folder("grade-lesson-8", "sao-lesson-8");
    let (passed, message) = sao_at_lesson(&dir, "8");
    assert!(passed, "{message}");
    assert!(
        message.contains("the 2×2 smoothing is graded from lesson 9 on"),
        "{message}"
    );
    // Lesson 9's answer is not given away.
    assert!(
        !message.contains("dFdx") && !message.contains("iuv"),
        "{message}"
    );
    // At lesson 9 the smoothing is due.
    let (passed, message) = sao_at_lesson(&dir, "9");
    assert!(!passed, "{message}");
    assert!(message.contains("2×2 smoothing is missing"), "{message}");
    // A finished shader passes at lesson 8 too.
    let dir = lesson_8_folder("grade-lesson-8-finished", "listing-sao");
    let (passed, message) = sao_at_lesson(&dir, "8");
    assert!(passed, "{message}");
}

/// A student who has done lessons 1 to `n` and nothing more passes `grade --lesson n`, for every n:
/// each file as that lesson leaves it (`sao.frag` with lesson 6's or 7's debug output, then without
/// the smoothing at 8), the others not written yet.
#[test]
fn every_lesson_passes_a_student_who_did_just_that_lesson() {
    for n in 2..=12u32 {
        let dir = temp_dir(&format!("grade-through-lesson-{n}"));
        let sao = match n {
            ..=5 => None,
            6 => Some("sao-lesson-6"),
            7 => Some("sao-lesson-7"),
            8 => Some("sao-lesson-8"),
            _ => Some("listing-sao"),
        };
        let written = [
            (2, Some("listing-restore"), "sao_restore_depth.frag"),
            (4, Some("listing-down-sampling"), "sao_down_sampling.frag"),
            (5, Some("listing-simple"), "simple.frag"),
            (6, sao, "sao.frag"),
            (11, Some("listing-blur"), "sao_blur.frag"),
        ];
        for (from, m, f) in written {
            if let (true, Some(m)) = (n >= from, m) {
                std::fs::copy(mutant(m).join(f), dir.join(f)).unwrap();
            }
        }
        let n = n.to_string();
        let v = grade(Some(&dir), &["--json", "--lesson", &n]).json();
        check_shape(&v);
        assert_eq!(v["passed"], true, "lesson {n}: {v}");
    }
}

#[test]
fn lesson_1_writes_no_shader_and_grades_nothing() {
    let dir = temp_dir("grade-lesson-1");
    let run = grade(Some(&dir), &["--lesson", "1"]);
    assert_eq!(run.code, Some(0), "{}{}", run.stdout, run.stderr);
    assert!(
        run.stdout
            .contains("lesson 1 writes no shader yet: nothing to grade"),
        "{}",
        run.stdout
    );
    assert!(!run.stdout.contains("FAIL"), "{}", run.stdout);
    let v = grade(Some(&dir), &["--json", "--lesson", "1"]).json();
    check_shape(&v);
    assert_eq!(v["passed"], true);
    assert_eq!(v["steps"].as_array().unwrap().len(), 0);
    assert_eq!(lesson_steps("2"), ["restore"]);
}

#[test]
fn bad_arguments_are_errors() {
    let run = grade(None, &["--lesson", "13"]);
    assert_ne!(run.code, Some(0));
    assert!(run.stderr.contains("no lesson step 13"), "{}", run.stderr);
    let missing = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-such-student-folder");
    let run = grade(Some(&missing), &[]);
    assert_ne!(run.code, Some(0));
    assert!(run.stderr.contains("not a folder"), "{}", run.stderr);
    assert!(!run.stdout.contains("PASS"), "{}", run.stdout);
    let file = mutant("listing-sao").join("sao.frag");
    let run = grade(Some(&file), &[]);
    assert_ne!(run.code, Some(0));
    assert!(run.stderr.contains("not a folder"), "{}", run.stderr);
}

#[test]
fn pictures_that_cannot_be_written_are_said_with_the_verdict() {
    // A folder where the restore step's first picture should go: the PNG cannot be written.
    let out = temp_dir("grade-blocked-pictures");
    std::fs::create_dir_all(out.join("restore-expected.png")).unwrap();
    let run = grade(
        Some(&mutant("listing-restore")),
        &[
            "--json",
            "--step",
            "restore",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    let v = run.json();
    check_shape(&v);
    let s = &v["steps"][0];
    assert_eq!(s["passed"], true, "{v}");
    let message = s["message"].as_str().unwrap();
    assert!(
        message.contains("pictures not written") && message.contains("restore-expected.png"),
        "{message}"
    );
}

#[test]
fn verdicts_write_code_a_student_can_paste_with_the_pages_names() {
    // ASCII operators in both languages, and no name that only the folded answers define.
    for lang in ["en", "ja"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("locales/{lang}.yml"));
        let text = std::fs::read_to_string(path).unwrap();
        for line in text.lines().filter(|l| l.starts_with("grade.verdict.")) {
            assert!(!line.contains('−') && !line.contains('·'), "{lang}: {line}");
            for name in [
                "ssR",
                "edgeSharpness",
                "totalWeight",
                "blurScale",
                "blurRadius",
                "farPlaneZ",
            ] {
                assert!(!line.contains(name), "{lang}: {name} in {line}");
            }
        }
    }
}
