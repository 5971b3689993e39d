//! The grader's fixed test inputs: linear-depth images of small box scenes, ray-cast on the CPU with
//! exactly the mapping `sao.frag` uses to rebuild view positions (`ndcToView`), so the SAO step sees
//! the same geometry whatever the student's restore and down-sampling passes do.

use crate::math::Camera;
use glam::{Mat4, Vec2, Vec3};

/// An axis-aligned box (solid).
#[derive(Clone, Copy, Debug)]
pub struct Aabb {
    pub lo: Vec3,
    pub hi: Vec3,
}

impl Aabb {
    pub fn new(lo: [f32; 3], hi: [f32; 3]) -> Aabb {
        Aabb {
            lo: Vec3::from(lo),
            hi: Vec3::from(hi),
        }
    }
    /// Entry distance of the ray `o + t·d` (t > 0), if it hits.
    fn hit(&self, o: Vec3, d: Vec3) -> Option<f32> {
        let mut t0 = 0.0f32;
        let mut t1 = f32::INFINITY;
        for a in 0..3 {
            if d[a].abs() < 1e-12 {
                if o[a] < self.lo[a] || o[a] > self.hi[a] {
                    return None;
                }
                continue;
            }
            let (mut ta, mut tb) = ((self.lo[a] - o[a]) / d[a], (self.hi[a] - o[a]) / d[a]);
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
            }
            t0 = t0.max(ta);
            t1 = t1.min(tb);
            if t0 > t1 {
                return None;
            }
        }
        (t0 > 0.0).then_some(t0)
    }
}

/// A probe: a point of the scene whose occlusion must meet an expectation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProbeKind {
    /// Open, flat surface: no occlusion.
    Open,
    /// A 90° crease: clearly occluded.
    Crease,
    /// A band beside a step, where occlusion fades with the distance: its mean must match the
    /// reference (the falloff's shape).
    Falloff,
}

#[derive(Clone, Debug)]
pub struct Probe {
    pub name: &'static str,
    pub at: Vec3,
    /// With `Some`, the probe is the screen rectangle spanned by `at` and `to`; else a 5×5 window
    /// around `at`.
    pub to: Option<Vec3>,
    pub kind: ProbeKind,
}

/// A scene of boxes seen by a camera, rendered as linear depth at `width`×`height` (the size of
/// `texSAODepth` level 0).
#[derive(Clone, Debug)]
pub struct SynthScene {
    pub name: &'static str,
    pub camera: Camera,
    pub boxes: Vec<Aabb>,
    pub width: u32,
    pub height: u32,
    pub probes: Vec<Probe>,
}

impl SynthScene {
    fn fov_scale(&self) -> f32 {
        crate::math::camera::fov_scale(self.camera.fov_y_deg)
    }
    fn inverse_view(&self) -> Mat4 {
        self.camera.view().inverse()
    }
    /// View-space direction at 1 m through texture coordinate `uv` (as `GetViewSpacePosition`).
    fn view_dir(&self, uv: Vec2) -> Vec3 {
        let fs = self.fov_scale();
        let aspect = self.width as f32 / self.height as f32;
        let ndc = uv * 2.0 - Vec2::ONE;
        Vec3::new(ndc.x * aspect / fs, ndc.y / fs, -1.0)
    }
    /// Linear depth (metres, `far` for sky) at the centre of every texel, rows bottom-up.
    pub fn depth(&self) -> Vec<f32> {
        let inv = self.inverse_view();
        let (w, h) = (self.width as usize, self.height as usize);
        let far = self.camera.far;
        let mut out = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let uv = Vec2::new((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
                let d = inv.transform_vector3(self.view_dir(uv));
                let t = self
                    .boxes
                    .iter()
                    .filter_map(|b| b.hit(self.camera.eye, d))
                    .fold(f32::INFINITY, f32::min);
                out.push(if t.is_finite() { t.min(far) } else { far });
            }
        }
        out
    }
    /// Texel (x, y from the bottom) that shows world point `p`.
    pub fn project(&self, p: Vec3) -> (usize, usize) {
        let v = self.camera.view().transform_point3(p);
        let depth = (-v.z).max(1e-6);
        let fs = self.fov_scale();
        let aspect = self.width as f32 / self.height as f32;
        let ndc = Vec2::new(v.x / depth * fs / aspect, v.y / depth * fs);
        let uv = (ndc + Vec2::ONE) * 0.5;
        let x = (uv.x * self.width as f32)
            .floor()
            .clamp(0.0, self.width as f32 - 1.0);
        let y = (uv.y * self.height as f32)
            .floor()
            .clamp(0.0, self.height as f32 - 1.0);
        (x as usize, y as usize)
    }
}

/// A wall seen head-on at 5 m from the camera at the origin, with `reliefs` standing out of it and
/// no probes: the scenes where a step measures one number the pages fix.
pub fn facing_wall(
    name: &'static str,
    reliefs: &[Aabb],
    (width, height): (u32, u32),
) -> SynthScene {
    let mut boxes = vec![Aabb::new([-60.0, -60.0, -6.0], [60.0, 60.0, -5.0])];
    boxes.extend_from_slice(reliefs);
    SynthScene {
        name,
        camera: Camera {
            eye: Vec3::ZERO,
            target: Vec3::new(0.0, 0.0, -5.0),
            ..Camera::default()
        },
        boxes,
        width,
        height,
        probes: vec![],
    }
}

/// The floor every SAO scene stands on (its top is y = 0).
pub fn floor() -> Aabb {
    Aabb::new([-60.0, -1.0, -60.0], [60.0, 0.0, 60.0])
}

/// The grader's SAO scenes at `width`×`height`. Wider than high, as a screen is: the lesson's disc is
/// round on screen only through `aspectFix`, and positions are rebuilt right only through both
/// components of `ndcToView` (on a square target both mistakes go unseen).
pub fn sao_scenes((width, height): (u32, u32)) -> Vec<SynthScene> {
    let camera = |eye: [f32; 3], target: [f32; 3]| Camera {
        eye: Vec3::from(eye),
        target: Vec3::from(target),
        ..Camera::default()
    };
    vec![
        // A wall (its face is the plane x = 0) on a floor, with a crate: creases, depth edges, sky.
        SynthScene {
            name: "corner",
            camera: camera([5.0, 2.2, 3.5], [0.8, 0.5, -0.5]),
            boxes: vec![
                floor(),
                Aabb::new([-1.0, 0.0, -60.0], [0.0, 3.0, 60.0]),
                Aabb::new([1.2, 0.0, -1.6], [2.2, 0.9, -0.6]),
            ],
            width,
            height,
            probes: vec![
                Probe {
                    name: "open floor",
                    at: Vec3::new(3.6, 0.0, 1.4),
                    to: None,
                    kind: ProbeKind::Open,
                },
                Probe {
                    name: "wall-floor crease",
                    at: Vec3::new(0.04, 0.04, 1.0),
                    to: None,
                    kind: ProbeKind::Crease,
                },
                Probe {
                    name: "crate-floor crease",
                    at: Vec3::new(2.24, 0.04, -1.1),
                    to: None,
                    kind: ProbeKind::Crease,
                },
            ],
        },
        // Looking straight at a wall (fronto-parallel) with a step in front of it.
        SynthScene {
            name: "facing wall",
            camera: camera([0.3, 1.4, 1.5], [0.3, 1.4, -6.0]),
            boxes: vec![
                floor(),
                Aabb::new([-60.0, 0.0, -5.0], [60.0, 3.2, -4.0]),
                Aabb::new([-1.5, 0.0, -5.0], [1.0, 0.7, -3.4]),
            ],
            width,
            height,
            probes: vec![
                Probe {
                    name: "open wall",
                    at: Vec3::new(2.2, 2.2, -4.0),
                    to: None,
                    kind: ProbeKind::Open,
                },
                Probe {
                    name: "step-floor crease",
                    at: Vec3::new(-0.2, 0.04, -3.36),
                    to: None,
                    kind: ProbeKind::Crease,
                },
                Probe {
                    name: "wall-floor crease",
                    at: Vec3::new(2.4, 0.04, -3.96),
                    to: None,
                    kind: ProbeKind::Crease,
                },
            ],
        },
        // A wall seen head-on with a raised panel (0.25 m) on its left half: the wall beside the
        // panel is occluded less and less with the distance from it (the falloff f³).
        SynthScene {
            name: "relief",
            camera: camera([0.0, 0.0, 0.0], [0.0, 0.0, -5.0]),
            boxes: vec![
                Aabb::new([-60.0, -60.0, -6.0], [60.0, 60.0, -5.0]),
                Aabb::new([-60.0, -60.0, -5.0], [0.0, 60.0, -4.75]),
            ],
            width,
            height,
            probes: vec![
                Probe {
                    name: "wall beside the panel",
                    at: Vec3::new(0.12, -1.5, -5.0),
                    to: Some(Vec3::new(0.75, 1.5, -5.0)),
                    kind: ProbeKind::Falloff,
                },
                Probe {
                    name: "open wall",
                    at: Vec3::new(2.0, 1.0, -5.0),
                    to: None,
                    kind: ProbeKind::Open,
                },
                Probe {
                    name: "open panel",
                    at: Vec3::new(-2.0, 1.0, -4.75),
                    to: None,
                    kind: ProbeKind::Open,
                },
            ],
        },
    ]
}
