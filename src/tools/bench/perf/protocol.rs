//! The two protocols of `opengl3d bench`: the **quick** one a plain `opengl3d bench` runs (a few
//! minutes on two software-GL cores: a small output, small references, five settings per method,
//! no ceilings) and the **full** one (`--full`: 1920×1080, every method's whole grid, the error
//! split). A flag given on the command line always wins over either; the reports list what a run
//! scaled down or skipped against the full protocol, and the run prints an estimate first.

/// Which settings each method runs when `--samples`, `--radii` and `--quality` are not given.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Grid {
    /// Each method's own grid (`catalog::settings_for`).
    Full,
    /// Five settings per method: 4, 8 and 16 samples at 1 m, 8 samples at 0.5 and 2 m.
    Quick,
}

/// The values of the options a run was not given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Protocol {
    pub width: u32,
    pub height: u32,
    pub ref_scale: u32,
    pub ref_rays: u32,
    /// Not given, the ray-traced reference's: the ceilings then trace its own rays
    /// (`references::ceiling_shares_truth_rays`), and the error split holds no noise of their own.
    pub screen_rays: u32,
    pub warmup: u32,
    pub frames: u32,
    pub ceilings: bool,
    pub grid: Grid,
}

/// What the bench's published figures were measured with.
pub const FULL: Protocol = Protocol {
    width: 1920,
    height: 1080,
    ref_scale: 6,
    ref_rays: 256,
    screen_rays: 256,
    warmup: 2,
    frames: 7,
    ceilings: true,
    grid: Grid::Full,
};

/// A newcomer's first run: about three minutes on two llvmpipe cores for the demo scene.
pub const QUICK: Protocol = Protocol {
    width: 640,
    height: 360,
    ref_scale: 4,
    ref_rays: 256,
    screen_rays: 256,
    warmup: 1,
    frames: 5,
    ceilings: false,
    grid: Grid::Quick,
};

/// The command that runs the full protocol (printed by quick runs and in the reports).
pub const FULL_COMMAND: &str = "opengl3d bench --full";

/// The options a command line gave (`None`: not given).
#[derive(Clone, Copy, Debug, Default)]
pub struct Given {
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub ref_scale: Option<u32>,
    pub ref_rays: Option<u32>,
    pub screen_rays: Option<u32>,
    pub warmup: Option<u32>,
    pub frames: Option<u32>,
    pub ceilings: bool,
    /// `--samples`, `--radii` or `--quality` was given: they choose the settings.
    pub settings: bool,
}

/// The run's values: each given option, the rest from `base`; and what differs from the full
/// protocol, one line each, for the reports.
pub fn resolve(given: &Given, base: &Protocol) -> (Protocol, Vec<String>) {
    let p = Protocol {
        width: given.width.unwrap_or(base.width),
        height: given.height.unwrap_or(base.height),
        ref_scale: given.ref_scale.unwrap_or(base.ref_scale),
        ref_rays: given.ref_rays.unwrap_or(base.ref_rays),
        screen_rays: given
            .screen_rays
            .unwrap_or(given.ref_rays.unwrap_or(base.ref_rays)),
        warmup: given.warmup.unwrap_or(base.warmup),
        frames: given.frames.unwrap_or(base.frames),
        ceilings: given.ceilings || base.ceilings,
        grid: base.grid,
    };
    let mut scaled = Vec::new();
    if (p.width, p.height) != (FULL.width, FULL.height) {
        scaled.push(format!(
            "output {}×{} (full protocol {}×{}; --width/--height)",
            p.width, p.height, FULL.width, FULL.height
        ));
    }
    let (rw, rh) = (
        p.width.div_ceil(p.ref_scale),
        p.height.div_ceil(p.ref_scale),
    );
    let (fw, fh) = (
        FULL.width.div_ceil(FULL.ref_scale),
        FULL.height.div_ceil(FULL.ref_scale),
    );
    if (rw, rh) != (fw, fh) || p.ref_rays != FULL.ref_rays {
        scaled.push(format!(
            "references {rw}×{rh} at {} rays per pixel (1/{} of the output; full protocol \
             {fw}×{fh} at {}; --ref-scale/--ref-rays)",
            p.ref_rays, p.ref_scale, FULL.ref_rays
        ));
    }
    if p.grid == Grid::Quick && !given.settings {
        scaled.push(
            "settings: 5 per method (4, 8, 16 samples at R 1 m; 8 samples at R 0.5 and 2 m) \
             instead of each method's full grid and presets (--full, or --samples/--radii/--quality)"
                .into(),
        );
    }
    if (p.warmup, p.frames) != (FULL.warmup, FULL.frames) {
        scaled.push(format!(
            "{} warm-up and {} timed frames per setting (full protocol {} and {}; --warmup/--frames)",
            p.warmup, p.frames, FULL.warmup, FULL.frames
        ));
    }
    if !p.ceilings {
        scaled.push(
            "error split skipped: no screen-space references (ceilings); --ceilings or --full"
                .into(),
        );
    }
    (p, scaled)
}

/// How long a run should take on software GL: CPU seconds per output pixel and frame (measured on
/// llvmpipe for the demo scene, AO on, one setting's frames, read-backs and metrics), per
/// reference ray at R 1 m (longer rays cost more), and per screen-space ray (a march through the
/// depth buffer, longer at larger sizes). Generous on a loaded machine, far above a GPU's frames.
const CPU_S_PER_PIXEL_FRAME: f64 = 1.8e-6;
const CPU_S_PER_REF_RAY: f64 = 0.4e-6;
const CPU_S_PER_SCREEN_RAY_PER_SIDE: f64 = 0.012e-6;

/// What a run will do, counted before it starts.
#[derive(Clone, Copy, Debug, Default)]
pub struct Work {
    /// Settings × scenes.
    pub settings: usize,
    /// Cameras per scene.
    pub cameras: usize,
    /// Ray-traced references not in the cache, and those that are.
    pub references: usize,
    pub cached: usize,
    /// Screen-space references (not counting any already cached).
    pub screen_references: usize,
    /// Mean radius of the references to render (m): ray cost grows with it.
    pub mean_radius: f64,
}

/// Estimated wall seconds of a run at `p` doing `work` on `cores` cores (software GL).
pub fn estimate_seconds(p: &Protocol, work: &Work, cores: usize) -> f64 {
    let cores = cores.max(1) as f64;
    let pixels = p.width as f64 * p.height as f64;
    let frames = (p.warmup + p.frames) as f64 + work.cameras as f64;
    let settings = work.settings as f64 * frames * pixels * CPU_S_PER_PIXEL_FRAME;
    let ref_pixels = pixels / (p.ref_scale as f64).powi(2);
    let radius = work.mean_radius.max(0.25);
    let references =
        work.references as f64 * ref_pixels * p.ref_rays as f64 * CPU_S_PER_REF_RAY * radius;
    let side = (p.width.max(p.height) / p.ref_scale.max(1)) as f64;
    let screen = work.screen_references as f64
        * ref_pixels
        * p.screen_rays as f64
        * side
        * CPU_S_PER_SCREEN_RAY_PER_SIDE;
    (settings + references + screen) / cores
}

/// "2 min 40 s", "45 s".
pub fn minutes(seconds: f64) -> String {
    let s = seconds.round().max(0.0) as u64;
    if s < 60 {
        format!("{s} s")
    } else {
        format!("{} min {:02} s", s / 60, s % 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn given_flags_win_and_the_notes_say_what_differs_from_the_full_protocol() {
        let (p, notes) = resolve(&Given::default(), &FULL);
        assert_eq!((p, notes.len()), (FULL, 0), "{notes:?}");
        let (p, notes) = resolve(&Given::default(), &QUICK);
        assert_eq!(p, QUICK);
        let all = notes.join("\n");
        for needle in [
            "output 640×360",
            "references 160×90",
            "5 per method",
            "error split",
        ] {
            assert!(all.contains(needle), "{needle}: {all}");
        }
        let given = Given {
            width: Some(1920),
            height: Some(1080),
            ref_scale: Some(6),
            ceilings: true,
            settings: true,
            warmup: Some(2),
            frames: Some(7),
            ..Given::default()
        };
        let (p, notes) = resolve(&given, &QUICK);
        assert_eq!((p.width, p.ref_scale, p.ceilings), (1920, 6, true));
        assert!(notes.is_empty(), "{notes:?}");
    }

    #[test]
    fn estimate_grows_with_the_work_and_cached_references_cost_nothing() {
        let work = Work {
            settings: 40,
            cameras: 4,
            references: 12,
            cached: 0,
            screen_references: 0,
            mean_radius: 1.2,
        };
        let quick = estimate_seconds(&QUICK, &work, 2);
        assert!(quick > 30.0 && quick < 240.0, "{quick}");
        let cached = Work {
            references: 0,
            cached: 12,
            ..work
        };
        assert!(estimate_seconds(&QUICK, &cached, 2) < quick);
        assert!(estimate_seconds(&FULL, &work, 2) > 5.0 * quick);
        assert_eq!(minutes(45.4), "45 s");
        assert_eq!(minutes(160.0), "2 min 40 s");
    }
}
