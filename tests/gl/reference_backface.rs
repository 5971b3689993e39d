//! The screen-space reference with `--thickness backface` (each pixel's slab reaches the back face
//! behind it, `vbao`'s per-pixel thickness), from depth buffers rendered on real Mesa GL, against
//! the geometry and closed forms; and the bench's split against it.

use crate::common::*;
use crate::reference_screen::{assert_valid, params, ref_camera};
use crate::reference_slabs::slab_blocked;
use glam::Vec3;
use opengl3d::ao::AoMethod;
use opengl3d::gl::mesh::MeshData;
use opengl3d::res::ResDirs;
use opengl3d::scene::{shapes, SceneDesc};
use opengl3d::tools::bench::perf;
use opengl3d::tools::reference::{load_or_render_cached, render_screen_space, DepthBuffer, Scene};

/// A box 0.7 m deep (front face 3 m from the camera, in the view's centre) over a one-sided
/// ground plane, seen from the origin down −z.
fn box_over_ground(dir: &std::path::Path, w: u32, h: u32) -> SceneDesc {
    let mut boxed = MeshData::default();
    shapes::add_box(
        &mut boxed,
        Vec3::new(-1.0, -1.0, -3.7),
        Vec3::new(1.0, 1.0, -3.0),
    );
    let mut desc = SceneDesc::default();
    desc.objects
        .push(object(dir, "box", &boxed, Vec3::ZERO, Vec3::ONE));
    desc.objects.push(object(
        dir,
        "ground",
        &shapes::ground(50.0, 10),
        Vec3::new(0.0, -1.5, 0.0),
        Vec3::ONE,
    ));
    desc.camera.eye = [0.0, 0.0, 0.0];
    desc.camera.target = [0.0, 0.0, -1.0];
    desc.camera.fov_y = 60.0;
    desc.output.width = w;
    desc.output.height = h;
    desc.bloom.enabled = false;
    desc
}

#[test]
fn back_faces_of_a_box_give_the_depth_each_ray_crosses_and_an_open_plane_none() {
    let ctx = context();
    let dir = temp_dir("backface-box");
    let (w, h) = (64u32, 48u32);
    let desc = box_over_ground(&dir, w, h);
    let mut e = engine(&ctx, &desc);
    let settings = e.ao_settings;
    let buf = DepthBuffer::from_engine_with_back_faces(&mut e, 0).unwrap();
    // The engine's AO settings are not changed by the back-face render.
    assert_eq!(e.ao_settings, settings);
    let back = buf.back_depth.as_ref().expect("back faces");
    assert_eq!(back.len(), (w * h) as usize);
    // The box's front face spans |x|, |y| ≤ 1 at depth 3: pixel centres with |ndc| < 1 / (3·tan 30°)
    // (and the aspect) see it; the ground (one-sided, y = −1.5) has no back face.
    let t = 30f64.to_radians().tan();
    let (mut on_box, mut on_ground, mut full_depth) = (0, 0, 0);
    for y in 0..h as usize {
        for x in 0..w as usize {
            let i = y * w as usize + x;
            let ndc_x = (2.0 * (x as f64 + 0.5) / w as f64 - 1.0) * t * w as f64 / h as f64;
            let ndc_y = (1.0 - 2.0 * (y as f64 + 0.5) / h as f64) * t;
            let (front, back) = (buf.linear_depth[i], back[i]);
            if ndc_x.abs() * 3.0 < 0.97 && ndc_y.abs() * 3.0 < 0.97 {
                // The ray leaves the box through its back face (depth 3.7) or, nearer the
                // corners, through a side face |x| = 1 or |y| = 1 (depth 1 / |ndc|).
                let exit = 3.7f64.min(1.0 / ndc_x.abs()).min(1.0 / ndc_y.abs());
                assert!((front - 3.0).abs() < 1e-3, "front {front} at ({x}, {y})");
                assert!(
                    (back as f64 - exit).abs() < 2e-3,
                    "back {back} vs {exit} at ({x}, {y})"
                );
                if exit == 3.7 {
                    full_depth += 1;
                }
                on_box += 1;
            } else if ndc_y * 3.0 < -1.05 {
                // Below the box's front edge, so below the whole box: the ground, one-sided.
                assert!(front.is_finite(), "ground pixel ({x}, {y})");
                assert_eq!(back, f32::INFINITY, "ground pixel ({x}, {y}) front {front}");
                on_ground += 1;
            }
        }
    }
    assert!(
        on_box > 200 && full_depth > 100 && on_ground > 100,
        "{on_box} box ({full_depth} through its back face), {on_ground} ground"
    );
    // With a guard band the inner pixels keep their back faces.
    let g = 6u32;
    let wide = DepthBuffer::from_engine_with_back_faces(&mut e, g).unwrap();
    assert_eq!(e.size(), (w, h));
    assert_eq!((wide.width, wide.height), (w + 2 * g, h + 2 * g));
    let wide_back = wide.back_depth.as_ref().unwrap();
    for y in 0..h as usize {
        for x in 0..w as usize {
            let (a, b) = (
                back[y * w as usize + x],
                wide_back[(y + g as usize) * wide.width as usize + x + g as usize],
            );
            assert!(
                a == b || (a - b).abs() <= 1e-4 * a,
                "pixel ({x}, {y}): {a} vs {b}"
            );
        }
    }
}

/// A wall facing the camera at depth 5 (a box 1 m thick) and, covering the left half of the view
/// (edge on the camera's axis), two objects whose fronts lie at depth 2.98: above the axis a plate
/// 2 cm thick, below it a block reaching depth 4.75. Their slabs are their true extents, so a
/// wall point right of the edge at distance a is occluded as the closed form `slab_blocked` says
/// with the height of the object's back above the wall: 2.02 m for the plate (beyond R: open), 0.25
/// m for the block. No single thickness gets both right.
#[test]
fn each_pixel_keeps_its_own_thickness_against_the_closed_form() {
    let ctx = context();
    let dir = temp_dir("backface-plate-block");
    let (w, h) = (128u32, 96u32);
    let mut wall = MeshData::default();
    shapes::add_box(
        &mut wall,
        Vec3::new(-20.0, -20.0, -6.0),
        Vec3::new(20.0, 20.0, -5.0),
    );
    let mut plate = MeshData::default();
    shapes::add_box(
        &mut plate,
        Vec3::new(-20.0, 0.0, -3.0),
        Vec3::new(0.0, 20.0, -2.98),
    );
    let mut block = MeshData::default();
    shapes::add_box(
        &mut block,
        Vec3::new(-20.0, -20.0, -4.75),
        Vec3::new(0.0, 0.0, -2.98),
    );
    let mut desc = SceneDesc::default();
    for (name, mesh) in [("wall", &wall), ("plate", &plate), ("block", &block)] {
        desc.objects
            .push(object(&dir, name, mesh, Vec3::ZERO, Vec3::ONE));
    }
    desc.camera.eye = [0.0, 0.0, 0.0];
    desc.camera.target = [0.0, 0.0, -1.0];
    desc.camera.fov_y = 60.0;
    desc.output.width = w;
    desc.output.height = h;
    desc.bloom.enabled = false;
    let mut e = engine(&ctx, &desc);
    let radius = 0.5f32;
    // vbao's thickness for the pixels without a back face (none here: every object is closed).
    let fallback = 0.25f32;
    let back_faces = DepthBuffer::from_engine_with_back_faces(&mut e, 0)
        .unwrap()
        .with_thickness(fallback);
    let heightfield = DepthBuffer::from_engine(&mut e).unwrap();
    let cam = ref_camera(&e);
    let p = params(radius, 512);
    let img = render_screen_space(&back_faces, &p).unwrap();
    assert_valid(&img);
    let scene = Scene::new(desc.world_triangles(&ResDirs::default()).unwrap()).unwrap();
    let rt = load_or_render_cached(&temp_dir("backface-plate-cache"), &scene, &cam, w, h, &p);
    let footprint = 5.0 * 2.0 * 30f64.to_radians().tan() / h as f64;
    let r = radius as f64;
    // Wall points right of the edge, clear of it by 2.5 footprints, more than R from the other
    // object's quadrant, whose rays (depth 4.5 to 5) stay on the screen (half height 4.5·tan 30°).
    let (mut plate_side, mut block_side) = (Vec::new(), Vec::new());
    for (i, q) in surface_points(&img, &cam) {
        let (a, y) = (q.x as f64, q.y as f64);
        if (q.z + 5.0).abs() > 1e-3 || a < 2.5 * footprint || a + r > 3.4 {
            continue;
        }
        if y.abs() < r + footprint || y.abs() + r > 2.55 {
            continue;
        }
        if y > 0.0 {
            plate_side.push((i, a));
        } else {
            block_side.push((i, a));
        }
    }
    assert!(
        plate_side.len() > 300 && block_side.len() > 300,
        "{} plate side, {} block side",
        plate_side.len(),
        block_side.len()
    );
    for (i, _) in &plate_side {
        // 2 m of air behind the plate: nothing within R, exactly, as in the ray-traced truth.
        assert_eq!(img.ao[*i], 1.0, "plate side pixel {i}");
        assert_eq!(rt.ao[*i], 1.0, "ray-traced plate side pixel {i}");
    }
    let (mut sum_err, mut sum_var, mut occluded) = (0.0, 0.0, Vec::new());
    for &(i, a) in &block_side {
        let want = 1.0 - slab_blocked(a, 5.0 - 4.75, r);
        let (ao, se) = (img.ao[i] as f64, img.std_error[i] as f64);
        assert!(
            (ao - want).abs() <= 4.0 * se + 0.03,
            "block side pixel {i} at a = {a}: ao {ao} vs {want} (se {se})"
        );
        sum_err += ao - want;
        sum_var += se * se;
        if want < 0.95 {
            occluded.push(i);
        }
    }
    let n = block_side.len() as f64;
    assert!(
        (sum_err / n).abs() <= 4.0 * sum_var.sqrt() / n + 0.005,
        "mean error {} beside the block",
        sum_err / n
    );
    assert!(occluded.len() >= 30, "{} occluded pixels", occluded.len());
    // Wall points beside the plate as close to its edge as the occluded ones beside the block.
    let plate_pixels: Vec<usize> = plate_side
        .iter()
        .filter(|(_, a)| *a < 0.3)
        .map(|(i, _)| *i)
        .collect();
    assert!(
        plate_pixels.len() >= 30,
        "{} near the plate",
        plate_pixels.len()
    );
    // The truth, the back-face ceiling and two uniform thicknesses beside each object.
    let truth = (mean_over(&rt, &occluded), mean_over(&rt, &plate_pixels));
    let seen = (mean_over(&img, &occluded), mean_over(&img, &plate_pixels));
    assert!(
        (seen.0 - truth.0).abs() < 0.03,
        "block: {seen:?} vs {truth:?}"
    );
    let uniform = |t: f32| {
        let img = render_screen_space(&heightfield.clone().with_thickness(t), &p).unwrap();
        (mean_over(&img, &occluded), mean_over(&img, &plate_pixels))
    };
    // vbao's R/2 slabs end 1.77 m above the wall: the block's occlusion is lost.
    let thin = uniform(fallback);
    assert!(
        thin.0 > truth.0 + 0.05,
        "R/2 slabs beside the block: {thin:?} vs {truth:?}"
    );
    // Slabs thick enough to reach the wall behind the block reach it behind the plate too.
    let thick = uniform(2.5);
    assert!(
        thick.1 < truth.1 - 0.05,
        "thick slabs beside the plate: {thick:?} vs {truth:?}"
    );
}

#[test]
fn cli_takes_backface_for_the_screen_space_reference() {
    let dir = temp_dir("backface-cli");
    let out = dir.join("ss.pfm");
    let o = run(&[
        "reference",
        "--screen-space",
        "--thickness",
        "backface",
        "--guard-band",
        "4",
        "--width",
        "32",
        "--height",
        "18",
        "--rays",
        "4",
        "--radius",
        "0.5",
        "--out",
        out.to_str().unwrap(),
        "--cache",
        dir.join("cache").to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}\n{}", stderr(&o));
    // The fallback is vbao's: half the radius.
    assert!(
        stdout.contains(
            "slabs from each surface to its back face (0.25 m thick where there is none)"
        ) && stdout.contains("guard band 4 px"),
        "{stdout}"
    );
    assert!(std::fs::read(&out).unwrap().starts_with(b"Pf\n32 18\n"));
    fails_with(
        &["reference", "--thickness", "backface", "--rays", "4"],
        &["--thickness", "--screen-space"],
    );
    fails_with(
        &["reference", "--screen-space", "--thickness", "backfaces"],
        &["backfaces", "backface"],
    );
}

/// Runs the bench on `room.toml` with `thickness` written into its `[ao]` table (a copy in a temp
/// folder; the meshes are found in Res/).
fn bench_room(out: &std::path::Path, thickness: &str) -> perf::Report {
    let res = ResDirs::default();
    let text = std::fs::read_to_string(res.find("scenes/room.toml").unwrap()).unwrap();
    assert!(text.contains("[ao]\n"));
    let scene = out.join("room.toml");
    std::fs::create_dir_all(out).unwrap();
    std::fs::write(
        &scene,
        text.replace("[ao]\n", &format!("[ao]\nthickness = {thickness}\n")),
    )
    .unwrap();
    let cfg = perf::PerfConfig {
        scenes: vec![scene],
        models: Vec::new(),
        width: 64,
        height: 36,
        out: out.to_path_buf(),
        methods: vec![AoMethod::Vbao],
        samples: vec![8],
        radii: vec![0.5],
        qualities: Vec::new(),
        ref_rays: 8,
        screen_rays: 8,
        ref_scale: 1,
        cache: out.parent().unwrap().join("cache"),
        warmup: 0,
        frames: 1,
        flip: false,
        charts: false,
        progress: false,
        ceilings: true,
        grid: perf::Grid::Full,
        scaled: Vec::new(),
    };
    perf::run(&res, &cfg).expect("bench run")
}

#[test]
fn bench_splits_backface_vbao_against_the_back_face_ceiling() {
    let dir = temp_dir("backface-bench");
    let back = bench_room(&dir.join("backface"), "\"backface\"");
    let metres = bench_room(&dir.join("metres"), "0.25");
    let (b, m) = (&back.rows[0], &metres.rows[0]);
    assert_eq!(b.method, "vbao");
    assert_eq!((b.ceiling, b.ceiling_thickness), ("back faces", Some(0.25)));
    assert_eq!(b.ceiling_label, "back faces (0.25 m where none)");
    assert_eq!((m.ceiling, m.ceiling_thickness), ("slabs", Some(0.25)));
    // Same depth buffer and fallback thickness, another ceiling: the room's walls, beams and
    // furniture are closed, so their slabs end at their back faces instead of 0.25 m behind.
    assert_ne!(b.depth_buffer_error.rmse, m.depth_buffer_error.rmse);
    assert_eq!(
        back.reference.screen_rendered + back.reference.screen_cached,
        2
    );
    let md = std::fs::read_to_string(dir.join("backface/report.md")).unwrap();
    let row = "| room | vbao | n8 r0.5 | back faces (0.25 m where none) |";
    assert!(md.contains(row), "{row} not in {md}");
    let json = std::fs::read_to_string(dir.join("backface/report.json")).unwrap();
    assert!(json.contains("\"ceiling\": \"back faces\""), "{json}");
    let md = std::fs::read_to_string(dir.join("metres/report.md")).unwrap();
    assert!(md.contains("| room | vbao | n8 r0.5 | 0.25 m |"), "{md}");
}
