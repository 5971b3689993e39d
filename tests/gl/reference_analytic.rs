//! The reference AO renderer against closed-form results.
//!
//! Geometry is built from large quads (kilometre-sized, "infinite" at the scale of the AO
//! radius). For every non-sky pixel the surface point is rebuilt from `linear_depth` and the
//! primary ray, the analytic AO at that point is evaluated and compared with the render:
//! per pixel within 4 standard errors (+ a small slack for the finite quads), and the mean
//! error over all pixels within 4 standard errors of the mean.

use std::f64::consts::PI;

use crate::common::surface_points;
use glam::Vec3;
use opengl3d::math::Camera;
use opengl3d::tools::reference::{
    cache_key, cache_path, load_or_render_cached, read_cached, render_reference, write_cached,
    AoVariant, RefImage, RefParams, Scene,
};

/// Two triangles covering the parallelogram a, b, c, a + c - b.
fn quad(a: Vec3, b: Vec3, c: Vec3) -> [[Vec3; 3]; 2] {
    let d = a + c - b;
    [[a, b, c], [a, c, d]]
}

const BIG: f32 = 1000.0;

/// Horizontal quad at height y, +-BIG in x and z.
fn horizontal(y: f32) -> [[Vec3; 3]; 2] {
    quad(
        Vec3::new(-BIG, y, -BIG),
        Vec3::new(BIG, y, -BIG),
        Vec3::new(BIG, y, BIG),
    )
}

fn camera(eye: Vec3, target: Vec3, up: Vec3, fov_y_deg: f32) -> Camera {
    Camera {
        eye,
        target,
        up,
        fov_y_deg,
        near: 0.05,
        far: 5000.0,
    }
}

fn params(radius: f32, rays: u32, variant: AoVariant) -> RefParams {
    RefParams {
        radius,
        rays,
        variant,
        seed: 12345,
        progress: false,
        supersample: 1,
    }
}

/// Compares the render with `exact(point)` (see the module docs). `slack` covers the
/// (tiny) effect of the quads not being infinite. Returns the number of pixels checked.
fn check_against(
    img: &RefImage,
    cam: &Camera,
    slack: f64,
    what: &str,
    exact: impl Fn(Vec3) -> f64,
) -> usize {
    let pts = surface_points(img, cam);
    assert!(!pts.is_empty(), "{what}: no surface visible");
    let (mut sum_err, mut sum_var) = (0.0f64, 0.0f64);
    for &(i, p) in &pts {
        let (ao, se) = (img.ao[i] as f64, img.std_error[i] as f64);
        let want = exact(p);
        assert!(
            (ao - want).abs() <= 4.0 * se + slack,
            "{what}: pixel {i} at {p}: ao {ao} vs analytic {want} (std error {se})"
        );
        sum_err += ao - want;
        sum_var += se * se;
    }
    let n = pts.len() as f64;
    let mean_err = sum_err / n;
    let mean_se = sum_var.sqrt() / n;
    assert!(
        mean_err.abs() <= 4.0 * mean_se + slack * 0.5,
        "{what}: mean error {mean_err} over {n} pixels (std error of mean {mean_se})"
    );
    pts.len()
}

fn assert_finite(img: &RefImage, w: u32, h: u32) {
    let n = (w * h) as usize;
    assert_eq!((img.width, img.height), (w, h));
    assert_eq!(img.ao.len(), n);
    assert_eq!(img.std_error.len(), n);
    assert_eq!(img.linear_depth.len(), n);
    for i in 0..n {
        let (a, e, d) = (img.ao[i], img.std_error[i], img.linear_depth[i]);
        assert!(a.is_finite() && (0.0..=1.0).contains(&a), "ao[{i}] = {a}");
        assert!(e.is_finite() && e >= 0.0, "std_error[{i}] = {e}");
        assert!(!d.is_nan() && d > 0.0, "linear_depth[{i}] = {d}");
    }
    assert!(img.mean_std_error().is_finite());
}

// 1. An open plane occludes nothing, whatever the radius.
#[test]
fn open_plane_is_unoccluded() {
    let scene = Scene::new(horizontal(0.0).to_vec()).unwrap();
    let cams = [
        // Straight down (up must not be parallel to the view direction).
        camera(Vec3::new(0.0, 10.0, 0.0), Vec3::ZERO, Vec3::NEG_Z, 60.0),
        // Oblique, horizon in view: the upper rows are sky.
        camera(
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.0, 0.0, -10.0),
            Vec3::Y,
            90.0,
        ),
    ];
    for cam in &cams {
        for p in [
            params(0.5, 64, AoVariant::Visibility),
            params(f32::INFINITY, 64, AoVariant::Visibility),
            params(50.0, 64, AoVariant::Obscurance),
        ] {
            let img = render_reference(&scene, cam, 24, 16, &p);
            assert_finite(&img, 24, 16);
            let pts = surface_points(&img, cam);
            assert!(pts.len() > 100);
            for (i, pt) in pts {
                assert!(pt.y.abs() < 1e-3, "surface point {pt} not on the plane");
                assert_eq!(img.ao[i], 1.0, "pixel {i} ({:?})", p.variant);
                assert_eq!(img.std_error[i], 0.0);
            }
        }
    }
    // The oblique view does see sky.
    let img = render_reference(
        &scene,
        &cams[1],
        24,
        16,
        &params(1.0, 4, AoVariant::Visibility),
    );
    assert!(img.sky_mask().iter().any(|&s| s));
}

/// UV sphere; the pole rows are emitted as quads too, so they contain zero-area triangles.
fn uv_sphere(center: Vec3, r: f32, seg: u32, rings: u32) -> Vec<[Vec3; 3]> {
    use std::f32::consts::{PI, TAU};
    let at = |i: u32, j: u32| {
        let (phi, theta) = (TAU * i as f32 / seg as f32, PI * j as f32 / rings as f32);
        center
            + r * Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            )
    };
    let mut tris = Vec::new();
    for j in 0..rings {
        for i in 0..seg {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    tris
}

// 1b. A convex tessellated object does not occlude itself (checks the normal flip and the
//     self-intersection offset on non-planar geometry); seen from inside, it occludes fully.
#[test]
fn convex_sphere_no_self_occlusion() {
    let scene = Scene::new(uv_sphere(Vec3::new(0.3, 1.0, -0.2), 1.0, 24, 12)).unwrap();
    // At the north pole two quad corners coincide exactly (zero-area triangles); at the south
    // pole f32 sin(PI) != 0 leaves valid slivers instead.
    assert_eq!(scene.skipped_count(), 24);
    let outside = camera(
        Vec3::new(2.0, 2.5, 3.0),
        Vec3::new(0.3, 1.0, -0.2),
        Vec3::Y,
        35.0,
    );
    for p in [
        params(5.0, 64, AoVariant::Visibility),
        params(5.0, 64, AoVariant::Obscurance),
    ] {
        let img = render_reference(&scene, &outside, 20, 20, &p);
        assert_finite(&img, 20, 20);
        let pts = surface_points(&img, &outside);
        assert!(pts.len() > 100);
        for (i, _) in pts {
            assert_eq!(img.ao[i], 1.0, "pixel {i} ({:?})", p.variant);
        }
    }
    let inside = camera(
        Vec3::new(0.3, 1.2, -0.2),
        Vec3::new(1.0, 0.5, 0.0),
        Vec3::Y,
        90.0,
    );
    let img = render_reference(
        &scene,
        &inside,
        9,
        7,
        &params(2.5, 64, AoVariant::Visibility),
    );
    assert!(img.sky_mask().iter().all(|&s| !s));
    assert!(img.ao.iter().all(|&a| a == 0.0), "{:?}", img.ao);
}

/// Cosine-weighted probability that a ray from a point at distance `d` from an infinite wall
/// (perpendicular to the point's surface) hits the wall within `r`.
///
/// Cosine-weighted directions project to points uniform on the unit disk of the tangent
/// plane (Malley). A ray with tangent component `w_x` towards the wall reaches it after
/// `d / w_x`, so it is blocked iff `w_x > d / r = a`: the circular segment of the disk beyond
/// `x = a`, of area `acos(a) - a sqrt(1 - a^2)`, divided by the disk area `pi`.
/// For `r -> infinity` this is 1/2 for every `d` (the wall covers half the hemisphere).
fn crease_blocked(d: f64, r: f64) -> f64 {
    let a = (d / r).clamp(0.0, 1.0);
    (a.acos() - a * (1.0 - a * a).sqrt()) / PI
}

// 2. 90-degree crease: floor y = 0 and wall x = 0 (y >= 0).
#[test]
fn crease_matches_segment_formula() {
    let mut tris = horizontal(0.0).to_vec();
    tris.extend(quad(
        Vec3::new(0.0, 0.0, -BIG),
        Vec3::new(0.0, 0.0, BIG),
        Vec3::new(0.0, BIG, BIG),
    ));
    let scene = Scene::new(tris).unwrap();
    let cam = camera(
        Vec3::new(2.5, 1.6, 2.0),
        Vec3::new(0.2, 0.25, 0.0),
        Vec3::Y,
        70.0,
    );

    // A point on the floor is at distance p.x from the wall, a point on the wall at p.y from
    // the floor, and the configuration is symmetric, so d = max(p.x, p.y) covers both.
    let dist = |p: Vec3| (p.x.max(p.y)).max(0.0) as f64;
    for (radius, rays) in [(f32::INFINITY, 1024), (1.0, 1024), (0.35, 1024)] {
        let img = render_reference(
            &scene,
            &cam,
            16,
            12,
            &params(radius, rays, AoVariant::Visibility),
        );
        assert_finite(&img, 16, 12);
        let what = format!("crease R={radius}");
        let n = check_against(&img, &cam, 2e-3, &what, |p| {
            1.0 - crease_blocked(dist(p), radius as f64)
        });
        assert!(n > 150, "{what}: too few surface pixels ({n})");
        // The view must include both planes and points both nearer and farther than R.
        let pts = surface_points(&img, &cam);
        assert!(pts.iter().any(|(_, p)| p.y < 1e-3) && pts.iter().any(|(_, p)| p.x < 1e-3));
        if radius.is_finite() {
            assert!(pts.iter().any(|(_, p)| (dist(*p) as f32) < 0.5 * radius));
            assert!(pts.iter().any(|(_, p)| (dist(*p) as f32) > radius));
        }
    }

    // A couple of points with many rays: pixels as close to the crease as the image allows.
    let img = render_reference(
        &scene,
        &cam,
        16,
        12,
        &params(1.0, 16384, AoVariant::Visibility),
    );
    let pts = surface_points(&img, &cam);
    let mut by_dist: Vec<_> = pts.iter().map(|&(i, p)| (dist(p), i)).collect();
    by_dist.sort_by(|a, b| a.0.total_cmp(&b.0));
    for &(d, i) in by_dist.iter().step_by(by_dist.len() / 4).take(3) {
        let want = 1.0 - crease_blocked(d, 1.0);
        let (ao, se) = (img.ao[i] as f64, img.std_error[i] as f64);
        assert!(se < 0.005, "se {se}");
        assert!(
            (ao - want).abs() <= 4.0 * se + 1e-3,
            "d={d}: ao {ao} vs {want} (se {se})"
        );
    }
}

// 3. Between two parallel planes a distance h apart.
//    A ray at angle theta from the normal meets the other plane after h / cos(theta), so it is
//    unoccluded within R iff cos(theta) < h / R. Under cosine weighting cos^2(theta) is uniform
//    on [0, 1], hence visibility = (h / R)^2 (1 if R <= h, 0 as R -> infinity), and obscurance
//    = P(c^2 < a^2) + E[a^2 / c^2; c^2 >= a^2] = a^2 (1 - 2 ln a) with a = h / R.
#[test]
fn slab_matches_quadratic_law() {
    let h = 1.0f32;
    let mut tris = horizontal(0.0).to_vec();
    tris.extend(horizontal(h));
    let scene = Scene::new(tris).unwrap();
    // Eye between the planes, looking slightly down: floor below, ceiling above the middle.
    let cam = camera(
        Vec3::new(0.0, 0.5, 0.0),
        Vec3::new(4.0, 0.35, -1.5),
        Vec3::Y,
        80.0,
    );
    let cases: [(f32, AoVariant, f64); 5] = [
        (f32::INFINITY, AoVariant::Visibility, 0.0),
        (0.8, AoVariant::Visibility, 1.0),
        (2.0, AoVariant::Visibility, 0.25),
        (1.25, AoVariant::Visibility, 0.64),
        (2.0, AoVariant::Obscurance, 0.25 * (1.0 + 2.0 * 2f64.ln())),
    ];
    for (radius, variant, want) in cases {
        let img = render_reference(&scene, &cam, 16, 12, &params(radius, 1024, variant));
        assert_finite(&img, 16, 12);
        let what = format!("slab R={radius} {variant:?}");
        let n = check_against(&img, &cam, 2e-3, &what, |_| want);
        assert!(n > 150, "{what}: too few surface pixels ({n})");
        let pts = surface_points(&img, &cam);
        assert!(pts.iter().any(|(_, p)| p.y < 1e-3) && pts.iter().any(|(_, p)| p.y > h - 1e-3));
    }
}

// 4. Degenerate input never produces NaN / Inf and never panics.
#[test]
fn degenerate_inputs_stay_finite() {
    // A closed box around the eye, plus zero-area and non-finite triangles.
    let (lo, hi) = (Vec3::splat(-1.0), Vec3::splat(1.0));
    let corner = |i: u32| {
        Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    let mut tris = Vec::new();
    for [a, b, c, d] in [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ] {
        tris.push([corner(a), corner(b), corner(c)]);
        tris.push([corner(a), corner(c), corner(d)]);
    }
    tris.push([Vec3::ZERO; 3]);
    tris.push([Vec3::ZERO, Vec3::X, Vec3::X * 3.0]);
    tris.push([Vec3::new(0.2, 0.1, 0.3); 3]);
    tris.push([Vec3::NAN, Vec3::X, Vec3::Y]);
    tris.push([Vec3::INFINITY, Vec3::X, Vec3::Y]);
    let scene = Scene::new(tris).unwrap();
    assert_eq!(scene.triangle_count(), 12);
    assert_eq!(scene.skipped_count(), 5);

    let inside = camera(
        Vec3::new(0.1, -0.2, 0.3),
        Vec3::new(1.0, 0.5, -0.7),
        Vec3::Y,
        75.0,
    );
    let odd_cams = [
        inside,
        Camera {
            target: inside.eye,
            ..inside
        }, // eye == target
        Camera {
            up: inside.target - inside.eye,
            ..inside
        }, // up parallel to view
        Camera {
            up: Vec3::ZERO,
            ..inside
        },
        Camera {
            eye: Vec3::NAN,
            ..inside
        },
        Camera {
            fov_y_deg: 0.0,
            ..inside
        },
        Camera {
            fov_y_deg: 180.0,
            ..inside
        },
        Camera {
            near: 5.0,
            far: 1.0,
            ..inside
        },
        Camera {
            near: -1.0,
            far: f32::INFINITY,
            ..inside
        },
        Camera {
            near: f32::NAN,
            far: f32::NAN,
            ..inside
        },
        camera(
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(2.0, 0.3, 0.0),
            Vec3::Y,
            60.0,
        ), // eye on a face
        camera(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 60.0), // outside
    ];
    let odd_params = [
        params(0.5, 16, AoVariant::Visibility),
        params(10.0, 16, AoVariant::Obscurance),
        params(f32::INFINITY, 8, AoVariant::Obscurance),
        params(0.0, 8, AoVariant::Obscurance),
        params(f32::NAN, 8, AoVariant::Visibility),
        params(-1.0, 8, AoVariant::Obscurance),
        params(1.0, 0, AoVariant::Visibility),
        params(1.0, 1, AoVariant::Obscurance),
    ];
    for cam in &odd_cams {
        for p in &odd_params {
            for (w, h) in [(1, 1), (3, 5), (5, 3)] {
                let img = render_reference(&scene, cam, w, h, p);
                assert_finite(&img, w, h);
            }
        }
    }
    // Inside the closed box with a radius larger than the box everything is occluded.
    let img = render_reference(
        &scene,
        &inside,
        3,
        5,
        &params(10.0, 64, AoVariant::Visibility),
    );
    assert!(img.sky_mask().iter().all(|&s| !s));
    assert!(img.ao.iter().all(|&a| a == 0.0), "{:?}", img.ao);

    // Empty sizes give empty buffers; an empty scene is all sky.
    for (w, h) in [(0, 0), (0, 7), (7, 0)] {
        let img = render_reference(&scene, &inside, w, h, &odd_params[0]);
        assert_finite(&img, w, h);
        assert_eq!(img.mean_std_error(), 0.0);
    }
    let empty = Scene::new(Vec::new()).unwrap();
    let img = render_reference(&empty, &inside, 3, 5, &odd_params[0]);
    assert_finite(&img, 3, 5);
    assert!(img.sky_mask().iter().all(|&s| s));
    assert!(img.ao.iter().all(|&a| a == 1.0));
}

/// A fresh, empty directory under the system temp dir.
fn temp_dir(tag: &str) -> std::path::PathBuf {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos();
    let dir =
        std::env::temp_dir().join(format!("opengl3d-ref-{tag}-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

// 5. The cache returns exactly what was stored, and reads instead of rendering when it can.
#[test]
fn cache_round_trip() {
    let mut tris = horizontal(0.0).to_vec();
    tris.extend(quad(
        Vec3::new(0.0, 0.0, -5.0),
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::new(0.0, 3.0, 5.0),
    ));
    let scene = Scene::new(tris).unwrap();
    let cam = camera(
        Vec3::new(2.0, 1.5, 2.0),
        Vec3::new(0.0, 0.3, 0.0),
        Vec3::Y,
        60.0,
    );
    let p = params(0.75, 32, AoVariant::Obscurance);
    let dir = temp_dir("cache");

    let key = cache_key(scene.content_hash(), &cam, 12, 9, &p);
    assert_eq!(key.len(), 16);
    assert!(key.chars().all(|c| c.is_ascii_hexdigit()));
    let path = cache_path(&dir, &key);
    assert!(!path.exists());

    let first = load_or_render_cached(&dir, &scene, &cam, 12, 9, &p);
    assert!(path.exists(), "cache file not written");
    assert_eq!(first, render_reference(&scene, &cam, 12, 9, &p));
    assert!(
        first.sky_mask().iter().any(|&s| s),
        "test wants sky (+inf depth) in the file"
    );
    let second = load_or_render_cached(&dir, &scene, &cam, 12, 9, &p);
    assert_eq!(first, second);
    assert_eq!(read_cached(&dir, &key).as_ref(), Some(&first));

    // Proof that the second call reads instead of rendering: plant a different (valid) image
    // under the key and it must come back verbatim.
    let mut planted = first.clone();
    planted.ao.iter_mut().for_each(|a| *a = 0.125);
    write_cached(&dir, &key, &planted).unwrap();
    assert_eq!(
        load_or_render_cached(&dir, &scene, &cam, 12, 9, &p),
        planted
    );

    // A damaged file is ignored and replaced by a fresh render.
    let bytes = std::fs::read(&path).unwrap();
    std::fs::write(&path, &bytes[..bytes.len() - 3]).unwrap();
    assert_eq!(read_cached(&dir, &key), None);
    assert_eq!(load_or_render_cached(&dir, &scene, &cam, 12, 9, &p), first);
    let mut flipped = std::fs::read(&path).unwrap();
    flipped[60] ^= 0x40;
    std::fs::write(&path, &flipped).unwrap();
    assert_eq!(read_cached(&dir, &key), None);
    assert_eq!(load_or_render_cached(&dir, &scene, &cam, 12, 9, &p), first);

    // The key depends on everything that changes the pixels, and on nothing else.
    let h = scene.content_hash();
    let base = cache_key(h, &cam, 12, 9, &p);
    assert_eq!(base, key);
    assert_eq!(
        cache_key(
            h,
            &cam,
            12,
            9,
            &RefParams {
                progress: true,
                ..p
            }
        ),
        base
    );
    for other in [
        cache_key(h ^ 1, &cam, 12, 9, &p),
        cache_key(
            h,
            &Camera {
                fov_y_deg: 61.0,
                ..cam
            },
            12,
            9,
            &p,
        ),
        cache_key(
            h,
            &Camera {
                eye: cam.eye + Vec3::X * 1e-3,
                ..cam
            },
            12,
            9,
            &p,
        ),
        cache_key(h, &cam, 9, 12, &p),
        cache_key(h, &cam, 12, 9, &RefParams { seed: 1, ..p }),
        cache_key(h, &cam, 12, 9, &RefParams { rays: 33, ..p }),
        cache_key(h, &cam, 12, 9, &RefParams { radius: 0.5, ..p }),
        cache_key(
            h,
            &cam,
            12,
            9,
            &RefParams {
                variant: AoVariant::Visibility,
                ..p
            },
        ),
    ] {
        assert_ne!(other, base);
    }
    // Stable across runs and platforms (FNV-1a of the inputs, not std's randomised hasher).
    let fixed = cache_key(
        0x0123_4567_89ab_cdef,
        &camera(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y, 45.0),
        640,
        480,
        &RefParams {
            radius: 0.5,
            rays: 256,
            variant: AoVariant::Visibility,
            seed: 7,
            progress: false,
            supersample: 1,
        },
    );
    assert_eq!(fixed, GOLDEN_KEY);

    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn unwritable_cache_still_returns_the_render() {
    let scene = Scene::new(horizontal(0.0).to_vec()).unwrap();
    let cam = camera(Vec3::new(0.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y, 60.0);
    let p = params(0.5, 8, AoVariant::Visibility);
    // The cache "folder" is a file: nothing can be written under it.
    let dir = temp_dir("cache-is-a-file");
    let cache = dir.join("cache");
    std::fs::write(&cache, b"not a folder").unwrap();
    let img = load_or_render_cached(&cache, &scene, &cam, 8, 6, &p);
    assert_eq!(img, render_reference(&scene, &cam, 8, 6, &p));
    assert_eq!(std::fs::read(&cache).unwrap(), b"not a folder");
    // Writing it directly is the error the warning reports, naming the folder.
    let key = cache_key(scene.content_hash(), &cam, 8, 6, &p);
    let e = format!("{:#}", write_cached(&cache, &key, &img).unwrap_err());
    assert!(e.contains(&cache.display().to_string()), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Recorded value of the fixed key above; changes only when `ALGORITHM_VERSION` or the key
/// layout changes (update it deliberately then).
const GOLDEN_KEY: &str = "f4c8e7691480b0e6";
