//! The window's truth: the ray-traced AO of the current camera, computed on a worker thread and kept
//! per camera, radius, size and scene, so that the window can show the current method's error
//! against it while the user changes method and settings.
//!
//! The tracer itself lives above the window (in the tools) and comes in through [`TruthBackend`]:
//! this file only decides when a truth is wanted, which one is shown and whether it is stale.

use crate::math::Camera;
use anyhow::Result;
use glam::Vec3;
use image::RgbImage;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::mpsc::{self, Receiver, TryRecvError};
use std::sync::Arc;

/// The widest truth traced for the window (pixels): wider windows trace at a whole fraction.
pub const MAX_TRUTH_WIDTH: u32 = 320;
/// The truth is at most a quarter of the window's size on each axis.
pub const MIN_TRUTH_FACTOR: u32 = 4;
/// Truths kept in memory (each a few hundred kilobytes at most).
const CACHE_SIZE: usize = 16;

/// What one truth is traced for.
#[derive(Clone)]
pub struct TruthRequest {
    pub camera: Camera,
    pub radius: f32,
    pub width: u32,
    pub height: u32,
    /// Each truth pixel is the mean over this many sub-pixels squared: the window's pixels the
    /// error map box-averages onto it.
    pub footprint: u32,
    /// The scene's triangles in world space.
    pub triangles: Arc<Vec<[Vec3; 3]>>,
}

/// How far a trace got (rows done), and a way to stop it early.
#[derive(Default)]
pub struct TruthProgress {
    rows_done: AtomicU32,
    cancelled: AtomicBool,
}

impl TruthProgress {
    /// Counts a finished row (the tracer calls it from its threads).
    pub fn row_done(&self) {
        self.rows_done.fetch_add(1, Ordering::Relaxed);
    }
    pub fn rows_done(&self) -> u32 {
        self.rows_done.load(Ordering::Relaxed)
    }
    /// True once the result is no longer wanted: the tracer may stop.
    pub fn cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }
    fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }
}

/// A traced truth: ambient visibility (1 = open), rows top-down.
#[derive(Clone, Debug, PartialEq)]
pub struct Truth {
    pub width: u32,
    pub height: u32,
    pub ao: Vec<f32>,
}

/// The current method against a truth: the error map's picture (with its colour scale) and scores.
#[derive(Clone, Debug)]
pub struct ErrorPicture {
    pub image: RgbImage,
    pub psnr: f64,
    pub rmse: f64,
}

/// What the window needs from the reference tools: a tracer and the error map's comparison.
pub trait TruthBackend: Send + Sync {
    /// Traces `request` on the calling thread, counting rows in `progress`; a cancelled trace may
    /// return anything (it is thrown away).
    fn trace(&self, request: &TruthRequest, progress: &TruthProgress) -> Result<Truth>;
    /// The engine's AO view (`engine_size`, rows top-down, with its sky mask) against `truth`,
    /// box-averaged to the truth's size.
    fn error_map(
        &self,
        ao: &[f32],
        sky: &[bool],
        engine_size: (usize, usize),
        truth: &Truth,
    ) -> Result<ErrorPicture>;
}

/// The tracer the window was given (`opengl3d window` passes the tools' CPU ray tracer).
#[derive(Clone)]
pub struct TruthTools(pub Arc<dyn TruthBackend>);

impl std::fmt::Debug for TruthTools {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("TruthTools")
    }
}

/// The size of the truth for a `width`×`height` window: the window divided by the smallest whole
/// factor of both sides that is at least [`MIN_TRUTH_FACTOR`] and brings the width to
/// [`MAX_TRUTH_WIDTH`] or less (the error map box-averages the window by that factor). None when
/// the two sides share no such factor.
pub fn truth_size(width: u32, height: u32) -> Option<(u32, u32)> {
    let wanted = MIN_TRUTH_FACTOR.max(width.div_ceil(MAX_TRUTH_WIDTH));
    let common = gcd(width, height);
    (wanted..=common)
        .find(|f| common.is_multiple_of(*f))
        .map(|f| (width / f, height / f))
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Identifies a truth: the camera, the radius (the truth's ray length), the size and the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TruthKey {
    camera: [u32; 12],
    radius: u32,
    size: (u32, u32),
    scene: u64,
}

impl TruthKey {
    pub fn new(camera: &Camera, radius: f32, size: (u32, u32), scene: u64) -> TruthKey {
        let mut c = [0u32; 12];
        let fields = camera
            .eye
            .to_array()
            .into_iter()
            .chain(camera.target.to_array());
        let fields = fields.chain(camera.up.to_array());
        let fields = fields.chain([camera.fov_y_deg, camera.near, camera.far]);
        for (slot, v) in c.iter_mut().zip(fields) {
            *slot = v.to_bits();
        }
        TruthKey {
            camera: c,
            radius: radius.to_bits(),
            size,
            scene,
        }
    }
}

/// Why the shown truth no longer fits the view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stale {
    Camera,
    Radius,
    Scene,
    Size,
}

/// Where the truth of the current view stands.
#[derive(Clone, Debug, PartialEq)]
pub enum TruthStatus {
    /// None was asked for yet.
    Off,
    /// Being traced: the share of rows done.
    Computing(f32),
    Ready(Arc<Truth>),
    /// A truth was asked for another view; the reason of the first difference found.
    Stale(Stale),
    Failed(String),
}

struct Job {
    key: TruthKey,
    rows: u32,
    progress: Arc<TruthProgress>,
    result: Receiver<Result<Truth>>,
}

/// The truths traced so far, the trace under way and the last one asked for.
#[derive(Default)]
pub struct TruthState {
    cache: Vec<(TruthKey, Arc<Truth>)>,
    asked: Option<TruthKey>,
    job: Option<Job>,
    failure: Option<(TruthKey, String)>,
    /// Traces started (the cache's hits start none).
    pub traces_started: u32,
}

impl TruthState {
    /// Asks for the truth of `key`: from memory when it was traced before, else traced on a worker
    /// thread (a trace under way for another key is cancelled). True when a trace started.
    pub fn request(
        &mut self,
        key: TruthKey,
        request: TruthRequest,
        backend: Arc<dyn TruthBackend>,
    ) -> bool {
        self.asked = Some(key);
        self.failure = None;
        if self.cached(&key).is_some() || self.job.as_ref().is_some_and(|j| j.key == key) {
            return false;
        }
        if let Some(old) = self.job.take() {
            old.progress.cancel();
        }
        let progress = Arc::new(TruthProgress::default());
        let (send, result) = mpsc::channel();
        let worker_progress = progress.clone();
        let rows = request.height;
        let spawned = std::thread::Builder::new()
            .name("truth".into())
            .spawn(move || {
                // The window may have closed meanwhile: nobody to tell then.
                let _ = send.send(backend.trace(&request, &worker_progress));
            });
        if let Err(e) = spawned {
            self.failure = Some((key, e.to_string()));
            return false;
        }
        self.traces_started += 1;
        self.job = Some(Job {
            key,
            rows,
            progress,
            result,
        });
        true
    }

    /// Takes a finished trace into the cache. True when one finished.
    pub fn poll(&mut self) -> bool {
        let Some(job) = &self.job else { return false };
        let done = match job.result.try_recv() {
            Ok(r) => r,
            Err(TryRecvError::Empty) => return false,
            Err(TryRecvError::Disconnected) => Err(anyhow::anyhow!("the truth's thread stopped")),
        };
        let key = job.key;
        self.job = None;
        match done {
            Ok(truth) => {
                if self.cache.len() >= CACHE_SIZE {
                    self.cache.remove(0);
                }
                self.cache.push((key, Arc::new(truth)));
            }
            Err(e) => self.failure = Some((key, format!("{e:#}"))),
        }
        true
    }

    /// Waits for the trace under way (tests and scripted runs).
    pub fn wait(&mut self) {
        while self.job.is_some() {
            if !self.poll() {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
        }
    }

    fn cached(&self, key: &TruthKey) -> Option<Arc<Truth>> {
        self.cache
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, t)| t.clone())
    }

    /// The truth of the view `key` describes, or why there is none.
    pub fn status(&self, key: &TruthKey) -> TruthStatus {
        if let Some(t) = self.cached(key) {
            return TruthStatus::Ready(t);
        }
        let Some(asked) = self.asked else {
            return TruthStatus::Off;
        };
        if let Some(job) = self.job.as_ref().filter(|j| j.key == *key) {
            let share = job.progress.rows_done() as f32 / job.rows.max(1) as f32;
            return TruthStatus::Computing(share.clamp(0.0, 1.0));
        }
        if let Some((k, e)) = &self.failure {
            if k == key {
                return TruthStatus::Failed(e.clone());
            }
        }
        let reason = if asked.scene != key.scene {
            Stale::Scene
        } else if asked.size != key.size {
            Stale::Size
        } else if asked.camera != key.camera {
            Stale::Camera
        } else {
            Stale::Radius
        };
        TruthStatus::Stale(reason)
    }

    /// True while a trace runs (for any key).
    pub fn busy(&self) -> bool {
        self.job.is_some()
    }
}

impl Drop for TruthState {
    fn drop(&mut self) {
        // A closing window does not wait for a trace nobody will see.
        if let Some(job) = &self.job {
            job.progress.cancel();
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::platform::window::truth::*;
    use std::sync::Mutex;

    /// Traces a constant image (the radius) after the test opens its gate.
    #[derive(Default)]
    struct FakeTracer {
        traced: Mutex<Vec<f32>>,
    }

    impl TruthBackend for FakeTracer {
        fn trace(&self, r: &TruthRequest, progress: &TruthProgress) -> Result<Truth> {
            for _ in 0..r.height {
                progress.row_done();
            }
            self.traced.lock().unwrap().push(r.radius);
            Ok(Truth {
                width: r.width,
                height: r.height,
                ao: vec![r.radius; (r.width * r.height) as usize],
            })
        }
        fn error_map(
            &self,
            _: &[f32],
            _: &[bool],
            _: (usize, usize),
            _: &Truth,
        ) -> Result<ErrorPicture> {
            anyhow::bail!("not used")
        }
    }

    fn camera(x: f32) -> Camera {
        Camera {
            eye: Vec3::new(x, 1.0, 5.0),
            ..Camera::default()
        }
    }

    fn ask(
        state: &mut TruthState,
        tracer: &Arc<FakeTracer>,
        cam: &Camera,
        radius: f32,
    ) -> TruthKey {
        let key = TruthKey::new(cam, radius, (8, 6), 1);
        let request = TruthRequest {
            camera: *cam,
            radius,
            width: 8,
            height: 6,
            footprint: 1,
            triangles: Arc::new(Vec::new()),
        };
        state.request(key, request, tracer.clone());
        state.wait();
        key
    }

    #[test]
    fn nothing_is_traced_until_asked() {
        let state = TruthState::default();
        let key = TruthKey::new(&camera(0.0), 1.0, (8, 6), 1);
        assert_eq!(state.status(&key), TruthStatus::Off);
        assert_eq!(state.traces_started, 0);
    }

    #[test]
    fn moving_the_camera_makes_the_truth_stale_and_moving_back_finds_it_again() {
        let tracer = Arc::new(FakeTracer::default());
        let mut state = TruthState::default();
        let here = ask(&mut state, &tracer, &camera(0.0), 1.0);
        assert!(matches!(state.status(&here), TruthStatus::Ready(t) if t.ao[0] == 1.0));
        let moved = TruthKey::new(&camera(0.5), 1.0, (8, 6), 1);
        assert_eq!(state.status(&moved), TruthStatus::Stale(Stale::Camera));
        // Back at the first pose: the same truth, not traced again.
        assert!(matches!(state.status(&here), TruthStatus::Ready(_)));
        let again = ask(&mut state, &tracer, &camera(0.0), 1.0);
        assert_eq!(again, here);
        assert_eq!(state.traces_started, 1);
        assert_eq!(tracer.traced.lock().unwrap().len(), 1);
    }

    #[test]
    fn a_new_radius_makes_the_truth_stale_and_is_traced_again() {
        let tracer = Arc::new(FakeTracer::default());
        let mut state = TruthState::default();
        ask(&mut state, &tracer, &camera(0.0), 1.0);
        let wider = TruthKey::new(&camera(0.0), 2.0, (8, 6), 1);
        assert_eq!(state.status(&wider), TruthStatus::Stale(Stale::Radius));
        ask(&mut state, &tracer, &camera(0.0), 2.0);
        assert!(matches!(state.status(&wider), TruthStatus::Ready(t) if t.ao[0] == 2.0));
        assert_eq!(*tracer.traced.lock().unwrap(), [1.0, 2.0]);
        // Another scene or size is stale too, named as such.
        let other_scene = TruthKey::new(&camera(0.0), 2.0, (8, 6), 2);
        assert_eq!(state.status(&other_scene), TruthStatus::Stale(Stale::Scene));
        let other_size = TruthKey::new(&camera(0.0), 2.0, (4, 3), 1);
        assert_eq!(state.status(&other_size), TruthStatus::Stale(Stale::Size));
    }

    #[test]
    fn the_truth_is_a_whole_fraction_of_the_window_at_most_a_quarter() {
        assert_eq!(truth_size(1280, 720), Some((320, 180)));
        assert_eq!(truth_size(320, 240), Some((80, 60)));
        assert_eq!(truth_size(1920, 1080), Some((320, 180)));
        // 1000×600: a quarter is 250×150.
        assert_eq!(truth_size(1000, 600), Some((250, 150)));
        // Sides with no common factor of 4 or more.
        assert_eq!(truth_size(1001, 677), None);
        assert_eq!(truth_size(0, 0), None);
    }
}
