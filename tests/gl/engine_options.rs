//! Engine options: AO targets created only when AO runs, reversed-Z depth, the automatic mip count
//! of the engine's SAO, GTAO quality presets.

use crate::common;

use glam::Vec3;
use opengl3d::render::View;

/// Mean luminance (0–255) of a small window around GL pixel (x, y from the bottom) of a top-down image.
fn lum_around(img: &image::RgbaImage, x: usize, y: usize, r: usize) -> f32 {
    let (w, h) = img.dimensions();
    let mut sum = 0.0;
    let mut n = 0.0;
    for yy in y.saturating_sub(r)..=(y + r).min(h as usize - 1) {
        for xx in x.saturating_sub(r)..=(x + r).min(w as usize - 1) {
            let p = img.get_pixel(xx as u32, h - 1 - yy as u32);
            sum += (p[0] as f32 + p[1] as f32 + p[2] as f32) / 3.0;
            n += 1.0;
        }
    }
    sum / n
}

#[test]
fn ao_off_allocates_no_ao_texture_until_ao_is_turned_on() {
    let ctx = common::context();
    let dir = common::temp_dir("lazy-ao");
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(4.0, 2.0, 4.0),
        Vec3::new(0.0, 1.0, 0.0),
        320,
        240,
    );
    scene.light.shadow = false;
    scene.ao.enabled = false;
    let mut eng = common::engine(&ctx, &scene);
    assert!(eng.ao_textures().is_empty(), "{:?}", eng.ao_textures());
    let img_off = eng.render_image().unwrap();
    assert!(
        eng.ao_textures().is_empty(),
        "AO off, composite view: {:?}",
        eng.ao_textures()
    );

    // Turned on later: render_image does not create them itself, render(&self) does (as after the
    // window's Space key).
    for method in [
        opengl3d::ao::AoMethod::SaoLesson,
        opengl3d::ao::AoMethod::Sao,
    ] {
        eng.ao_settings.enabled = true;
        eng.ao_settings.method = method;
        eng.sync_shader_constants().unwrap();
        let img_on = eng.render_image().unwrap();
        let textures = eng.ao_textures();
        let names: Vec<&str> = textures.iter().map(|t| t.name.as_str()).collect();
        assert!(
            names.contains(&"FBO(sao depth)") && names.contains(&"FBO(sao)"),
            "{names:?}"
        );
        // The half-size depth chain: level 0 is 160×120 R32F.
        let depth = textures
            .iter()
            .find(|t| t.name == "FBO(sao depth)")
            .unwrap();
        assert_eq!((depth.width, depth.height), (160, 120));
        assert!(depth.bytes >= 160 * 120 * 4);
        let (cx, cy) = common::project(&eng, Vec3::new(0.03, 0.03, 0.0), 320, 240);
        let (on, off) = (
            lum_around(&img_on, cx, cy, 1),
            lum_around(&img_off, cx, cy, 1),
        );
        assert!(
            on < off - 10.0,
            "{}: crease {on} with AO vs {off} without",
            method.name()
        );
    }
    let sao_bytes: u64 = eng.ao_textures().iter().map(|t| t.bytes).sum();
    assert!(sao_bytes > 0);

    // A resize while AO is off drops them; a resize while on re-creates them at the new size.
    eng.ao_settings.enabled = false;
    eng.resize(200, 100).unwrap();
    assert!(eng.ao_textures().is_empty(), "{:?}", eng.ao_textures());
    eng.ao_settings.enabled = true;
    eng.render_image().unwrap();
    eng.resize(256, 128).unwrap();
    let depth = eng
        .ao_textures()
        .into_iter()
        .find(|t| t.name == "FBO(sao depth)")
        .expect("kept while AO is on");
    assert_eq!((depth.width, depth.height), (128, 64));

    // The debug views need the chain even with AO off.
    eng.ao_settings.enabled = false;
    eng.resize(320, 240).unwrap();
    assert!(eng.ao_textures().is_empty());
    let v = eng.render_values(View::LinearDepth).unwrap();
    common::assert_finite("linear depth", &v);
    assert!(!eng.ao_textures().is_empty());
}

/// A scene of one wall facing the camera (at the origin, looking down −Z) at distance `d`, big enough
/// to fill the view: every pixel's exact view distance is `d`.
fn facing_wall_scene(dir: &std::path::Path, d: f32, w: u32, h: u32) -> opengl3d::scene::SceneDesc {
    let mut wall = opengl3d::gl::mesh::MeshData::default();
    opengl3d::scene::shapes::add_box(
        &mut wall,
        Vec3::new(-1.0, -1.0, -1.0),
        Vec3::new(1.0, 1.0, 0.0),
    );
    let mut s = opengl3d::scene::SceneDesc::default();
    // Front face at z = −d; 2·d wide in each direction covers a 60° view.
    s.objects.push(common::object(
        dir,
        "wall",
        &wall,
        Vec3::new(0.0, 0.0, -d),
        Vec3::new(2.0 * d, 2.0 * d, 1.0),
    ));
    s.camera.eye = [0.0, 0.0, 0.0];
    s.camera.target = [0.0, 0.0, -1.0];
    s.output.width = w;
    s.output.height = h;
    s.bloom.enabled = false;
    s.light.shadow = false;
    s
}

#[test]
fn reversed_z_restores_far_distances_far_more_precisely_than_d32() {
    use opengl3d::math::DepthMode;
    let ctx = common::context();
    let dir = common::temp_dir("reversed-z");
    let mut worst = [0.0f64; 2];
    for d in [500.0f32, 640.0, 777.7, 900.0, 990.0] {
        for (i, mode) in [DepthMode::D32, DepthMode::D32fReversed]
            .into_iter()
            .enumerate()
        {
            let mut scene = facing_wall_scene(&dir, d, 32, 32);
            scene.output.depth = mode;
            let mut eng = common::engine(&ctx, &scene);
            assert_eq!(eng.depth_mode(), mode);
            let v = eng.render_values(View::LinearDepth).unwrap();
            common::assert_finite("linear depth", &v);
            // Away from the border, every texel sees the wall at exactly d (−z_view).
            for y in 4..28 {
                for x in 4..28 {
                    let got = v[y * 32 + x] as f64;
                    assert!(
                        got < scene.camera.far as f64,
                        "{mode:?} at {d} m: sky at ({x},{y})"
                    );
                    let rel = (got - d as f64).abs() / d as f64;
                    worst[i] = worst[i].max(rel);
                }
            }
        }
    }
    eprintln!(
        "worst relative error 500–990 m: D32 {:e}, D32F reversed {:e}, ratio {:.0}",
        worst[0],
        worst[1],
        worst[0] / worst[1].max(1e-12)
    );
    // f32 arithmetic on both sides of the restore: a few ulps of 1.0 at most.
    assert!(
        worst[1] < 1e-6,
        "reversed-Z worst relative error {:e}",
        worst[1]
    );
    // The course's convention loses ~2^-24 of window depth near 1, i.e. ~1e-4 of the distance here.
    assert!(
        worst[0] > 100.0 * worst[1].max(1e-9),
        "D32 {:e} vs reversed {:e}: reversed-Z should be far more precise",
        worst[0],
        worst[1]
    );
}

#[test]
fn reversed_z_composite_matches_the_standard_picture() {
    use opengl3d::math::DepthMode;
    let ctx = common::context();
    let res = opengl3d::res::ResDirs::default();
    let scene_path = res.find("scenes/demo.toml").unwrap();
    let mut scene = opengl3d::scene::SceneDesc::load(&scene_path).unwrap();
    scene.output.width = 320;
    scene.output.height = 180;
    let mut images = Vec::new();
    for mode in [DepthMode::D32, DepthMode::D32fReversed] {
        scene.output.depth = mode;
        for method in [
            opengl3d::ao::AoMethod::SaoLesson,
            opengl3d::ao::AoMethod::Sao,
        ] {
            scene.ao.method = method;
            for composite in [
                opengl3d::ao::CompositeMode::Blend,
                opengl3d::ao::CompositeMode::AmbientOnly,
            ] {
                scene.ao.composite = composite;
                let mut eng = common::engine(&ctx, &scene);
                images.push(eng.render_image().unwrap());
                let vis = eng.render_values(View::Ao).unwrap();
                common::assert_finite(&format!("{mode:?} {method:?} visibility"), &vis);
            }
        }
    }
    let (standard, reversed) = images.split_at(images.len() / 2);
    for (i, (a, b)) in standard.iter().zip(reversed).enumerate() {
        let diffs: Vec<i32> = a
            .pixels()
            .zip(b.pixels())
            .flat_map(|(p, q)| (0..3).map(move |c| (p[c] as i32 - q[c] as i32).abs()))
            .collect();
        let mean = diffs.iter().sum::<i32>() as f64 / diffs.len() as f64;
        let big = diffs.iter().filter(|d| **d > 24).count() as f64 / diffs.len() as f64;
        eprintln!("case {i}: mean |diff| {mean:.3}, share > 24: {big:.5}");
        // Identical geometry; only depth rounding differs (a few edge pixels may flip).
        assert!(mean < 0.5, "case {i}: mean difference {mean}");
        assert!(
            big < 0.002,
            "case {i}: {big} of the channels differ by more than 24"
        );
    }
    // The sky is drawn (not left black) and objects are in front of it in both conventions.
    let top = reversed[0].get_pixel(160, 2);
    assert!(top[2] > 100, "sky missing with reversed-Z: {top:?}");
}

/// McGuire's rule, computed here independently of the engine: the farthest sample of a disc of
/// `radius` pixels reads level floor(log2(radius)) − 3, so the chain needs that many levels + 1.
fn levels_for_radius(radius_px: f64) -> u32 {
    (radius_px.log2().floor() as i64 - 3).max(0) as u32 + 1
}

#[test]
fn engine_sao_sizes_its_depth_chain_for_the_largest_disc_and_reads_the_top_level() {
    use opengl3d::ao::method_pass::AoMethodPass;
    use opengl3d::ao::{AoMethod, AoTargets};
    use opengl3d::math::Camera;
    let ctx = common::context();
    let (w, h) = (1280u32, 720u32);
    let hw = w / 2;
    // The screen radius is clamped to a quarter of the half-size buffer's larger side.
    let want = levels_for_radius(0.25 * hw as f64);
    assert_eq!(want, 5);

    // The engine: a close-up of a crease (the disc hits the clamp) with the two SAO methods.
    let dir = common::temp_dir("auto-mips");
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(0.6, 0.5, 0.6),
        Vec3::new(0.0, 0.2, 0.0),
        w,
        h,
    );
    scene.ao.method = AoMethod::Sao;
    let mut eng = common::engine(&ctx, &scene);
    let auto = eng.render_values(View::AoRaw).unwrap();
    common::assert_finite("sao, automatic levels", &auto);
    assert_eq!(eng.ao_targets().unwrap().tex_depth.levels(), want);
    eng.depth_levels_override = Some(4);
    let four = eng.render_values(View::AoRaw).unwrap();
    common::assert_finite("sao, 4 levels", &four);
    assert_eq!(eng.ao_targets().unwrap().tex_depth.levels(), 4);
    let changed = auto
        .iter()
        .zip(&four)
        .filter(|(a, b)| (*a - *b).abs() > 1.0 / 255.0)
        .count();
    eprintln!(
        "close-up, {want} levels vs 4: {changed} of {} AO texels differ by more than 1/255",
        auto.len()
    );
    assert!(
        changed > 0,
        "the close-up must read level 4 somewhere (no pixel changed with 4 levels)"
    );
    eng.depth_levels_override = None;
    eng.ao_settings.method = AoMethod::SaoLesson;
    eng.sync_shader_constants().unwrap();
    common::assert_finite("sao-lesson", &eng.render_values(View::Ao).unwrap());
    assert_eq!(
        eng.ao_targets().unwrap().tex_depth.levels(),
        4,
        "the lesson keeps its 4 levels"
    );

    // The shader really reads the top level: levels 0–3 hold a wall facing the camera at 3 m (no
    // occlusion), level 4 claims it 0.5 m closer. Only samples farther than 2^(4+3) = 128 px read it.
    let cam = Camera::default();
    let (params, meshes, sao) = common::sao_pass(&ctx, 2.0, 1000.0, false);
    let mean_occlusion = |levels: u32, top: f32| {
        let targets = AoTargets::new(&ctx.gl, w, h, levels).unwrap();
        assert_eq!(targets.tex_depth.levels(), levels);
        for l in 0..levels {
            let (lw, lh) = targets.tex_depth.size_at(l);
            let v = if l == 4 { top } else { 3.0 };
            targets
                .tex_depth
                .upload_f32(l, 1, &vec![v; (lw * lh) as usize])
                .unwrap();
        }
        let inputs = common::depth_only_inputs(&ctx, &meshes, &targets, &cam, &params, None);
        sao.compute(&inputs).unwrap();
        let occ = targets.sao_texture().read_f32(0, 1);
        common::assert_finite("sao on synthetic levels", &occ);
        occ.iter().sum::<f32>() / occ.len() as f32
    };
    let five = mean_occlusion(5, 2.5);
    let control = mean_occlusion(5, 3.0);
    let capped = mean_occlusion(4, 2.5);
    eprintln!("synthetic levels: mean occlusion {five} (5 levels), {control} (control), {capped} (4 levels)");
    assert!(five > 0.02, "level 4 was not read (mean occlusion {five})");
    assert!(
        control < 0.005,
        "a flat wall must not occlude itself ({control})"
    );
    assert!(
        capped < 0.005,
        "with 4 levels nothing reads the closer level ({capped})"
    );
}

#[test]
fn gtao_quality_presets_set_slices_and_steps_and_samples_still_work() {
    use opengl3d::ao::{AoMethod, SlicePreset};
    let ctx = common::context();
    let dir = common::temp_dir("gtao-quality");
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(3.0, 2.0, 3.0),
        Vec3::new(0.0, 0.5, 0.0),
        256,
        192,
    );
    scene.ao.method = AoMethod::Gtao;
    let mut raw = Vec::new();
    for q in SlicePreset::ALL {
        scene.ao.quality = Some(q);
        let mut eng = common::engine(&ctx, &scene);
        let v = eng.render_values(View::AoRaw).unwrap();
        common::assert_finite(q.name(), &v);
        raw.push(v);
    }
    // medium = 2 slices × 4 steps = what `samples = 16` has always meant (16 / 4 steps per side).
    scene.ao.quality = None;
    scene.ao.samples = 16;
    let mut eng = common::engine(&ctx, &scene);
    assert_eq!(eng.render_values(View::AoRaw).unwrap(), raw[1]);
    // And an explicit count is not overridden by anything: 8 samples = 2 slices × 2 steps ≠ medium.
    eng.ao_settings.samples = 8;
    assert_ne!(eng.render_values(View::AoRaw).unwrap(), raw[1]);

    // More slices and steps: less per-pixel noise. Noise = mean |difference| between horizontal
    // neighbours of the raw (unblurred) visibility where both see the same smooth surface.
    let noise = |v: &[f32]| {
        let (w, h) = (256usize, 192usize);
        let mut sum = 0.0;
        let mut n = 0.0;
        for y in 0..h {
            for x in 0..w - 1 {
                let (a, b) = (v[y * w + x], v[y * w + x + 1]);
                if a < 1.0 && b < 1.0 {
                    sum += (a - b).abs();
                    n += 1.0;
                }
            }
        }
        sum / n
    };
    let n_low = noise(&raw[0]);
    let n_ultra = noise(&raw[3]);
    eprintln!("GTAO raw noise: low {n_low:.4}, ultra {n_ultra:.4}");
    assert!(
        n_ultra < n_low,
        "ultra {n_ultra} should be smoother than low {n_low}"
    );
}

#[test]
fn every_engine_methods_packed_blur_equals_the_two_texture_separable_blur() {
    use opengl3d::ao::AoMethod;
    for method in AoMethod::ALL {
        if method != AoMethod::SaoLesson {
            packed_blur_equals_the_separable_blur(method);
        }
    }
}

fn packed_blur_equals_the_separable_blur(method: opengl3d::ao::AoMethod) {
    let ctx = common::context();
    let dir = common::temp_dir(&format!("packed-blur-{}", method.name()));
    let mut scene = common::crease_scene(
        &dir,
        Vec3::new(4.0, 2.0, 4.0),
        Vec3::new(0.0, 1.0, 0.0),
        320,
        240,
    );
    scene.ao.method = method;
    // Both blurs read the same targets: no guard band (its margin is cropped after the blur).
    scene.ao.guard_band = opengl3d::ao::GuardBand::Off;
    let mut eng = common::engine(&ctx, &scene);
    eng.render_image().unwrap();
    let names: Vec<String> = eng.ao_textures().into_iter().map(|t| t.name).collect();
    assert!(names.iter().any(|n| n == "FBO(ao packed)"), "{names:?}");
    let packed = eng
        .ao_targets()
        .unwrap()
        .result_texture(true)
        .read_f32(0, 1);
    common::assert_finite("packed blur", &packed);
    // The same raw occlusion through the plain blur (occlusion and depth from two textures).
    let separable = opengl3d::ao::blur::SeparableBlur::new(
        opengl3d::gl::ProgramObject::from_res(
            eng.gl(),
            &opengl3d::res::ResDirs::default(),
            "simple.vert",
            "ao/blur_separable.frag",
            // The method's own Gaussian, if it has one: the two blurs must weigh alike.
            &opengl3d::ao::method_pass::blur_defines(
                &eng.camera,
                method.info().blur_sigma,
                &eng.ao_settings,
            ),
        )
        .unwrap(),
    );
    separable
        .run(eng.gl(), eng.ao_targets().unwrap(), &eng.meshes, None)
        .unwrap();
    let plain = eng
        .ao_targets()
        .unwrap()
        .result_texture(true)
        .read_f32(0, 1);
    let occluded = plain.iter().filter(|v| **v > 0.05).count();
    assert!(
        occluded > 100,
        "{}: the crease must be occluded ({occluded} texels)",
        method.name()
    );
    // The packed pass blurs the unquantised occlusion; the plain one its R8 copy: within 1.5/255.
    let worst = packed
        .iter()
        .zip(&plain)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    eprintln!(
        "{}: packed vs plain blur: worst difference {worst}",
        method.name()
    );
    assert!(
        worst <= 1.5 / 255.0,
        "{}: packed vs plain blur differ by {worst}",
        method.name()
    );
}
