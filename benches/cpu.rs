//! CPU benchmarks (divan): `cargo bench --bench cpu`.
//!
//! The BVH build of the demo scene, the ray-traced and the screen-space references on a small
//! image, and the bench's image metrics (SSIM, FLIP) on a 960×540 pair. Nothing here needs GL:
//! the screen-space reference reads the ray-traced reference's depth (the same pixel centres as
//! the engine's depth buffer).

use std::sync::OnceLock;

use glam::Vec3;
use opengl3d::math::Camera;
use opengl3d::res::ResDirs;
use opengl3d::scene::SceneDesc;
use opengl3d::tools::bench::metrics::{self, Gray};
use opengl3d::tools::reference::{
    render_reference, render_screen_space, AoVariant, DepthBuffer, RefParams, Scene,
};

fn main() {
    divan::main();
}

/// The demo scene's triangles and camera, loaded once.
fn demo() -> &'static (Vec<[Vec3; 3]>, Camera) {
    static DEMO: OnceLock<(Vec<[Vec3; 3]>, Camera)> = OnceLock::new();
    DEMO.get_or_init(|| {
        let res = ResDirs::default();
        let path = res.find("scenes/demo.toml").expect("Res/scenes/demo.toml");
        let desc = SceneDesc::load(&path).expect("demo scene");
        let tris = desc.world_triangles(&res).expect("demo meshes");
        let cam = desc.camera.camera();
        (tris, cam)
    })
}

fn demo_bvh() -> &'static Scene {
    static BVH: OnceLock<Scene> = OnceLock::new();
    BVH.get_or_init(|| Scene::new(demo().0.clone()).expect("BVH"))
}

const SMALL: (u32, u32) = (64, 36);

fn small_params() -> RefParams {
    RefParams {
        radius: 1.0,
        rays: 16,
        variant: AoVariant::Visibility,
        seed: 1,
        progress: false,
        supersample: 1,
    }
}

#[divan::bench(sample_count = 10)]
fn bvh_build_demo(bencher: divan::Bencher) {
    let tris = &demo().0;
    bencher
        .with_inputs(|| tris.clone())
        .bench_values(|t| Scene::new(t).expect("BVH"));
}

#[divan::bench(sample_count = 10)]
fn ray_traced_reference_64x36_16_rays() -> opengl3d::tools::reference::RefImage {
    let (w, h) = SMALL;
    render_reference(demo_bvh(), &demo().1, w, h, &small_params())
}

#[divan::bench(sample_count = 10)]
fn screen_space_reference_64x36_16_rays(bencher: divan::Bencher) {
    let (w, h) = SMALL;
    let cam = demo().1;
    let depth = DepthBuffer::from_reference(
        &render_reference(demo_bvh(), &cam, w, h, &small_params()),
        &cam,
    );
    bencher.bench(|| render_screen_space(&depth, &small_params()).expect("screen-space"));
}

/// Two different smooth 960×540 images in [0, 1].
fn pair() -> &'static (Vec<f32>, Vec<f32>) {
    static PAIR: OnceLock<(Vec<f32>, Vec<f32>)> = OnceLock::new();
    PAIR.get_or_init(|| {
        let (w, h) = (960usize, 540usize);
        let img = |k: f32| -> Vec<f32> {
            (0..w * h)
                .map(|i| {
                    let (x, y) = ((i % w) as f32, (i / w) as f32);
                    0.5 + 0.4 * (x * 0.031 * k).sin() * (y * 0.017 + k).cos()
                })
                .collect()
        };
        (img(1.0), img(1.1))
    })
}

#[divan::bench(sample_count = 10)]
fn ssim_960x540() -> f64 {
    let (a, b) = pair();
    metrics::ssim(Gray::new(960, 540, a), Gray::new(960, 540, b), None)
}

#[divan::bench(sample_count = 10)]
fn flip_960x540() -> f64 {
    let (a, b) = pair();
    metrics::flip(Gray::new(960, 540, a), Gray::new(960, 540, b), None)
}
