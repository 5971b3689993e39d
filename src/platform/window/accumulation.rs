//! The running mean over frames in the window: on by default, started again after any change of
//! setting or window size. A moving camera keeps it (`ao::temporal` reprojects it); `rtao` starts it
//! again itself when an object moves (its inputs' key); settings it does not hash (the method, bias,
//! normals, ...) are watched here.

use crate::ao::AoSettings;

/// Frames the window averages over, unless `--accumulate` says otherwise.
pub const WINDOW_ACCUMULATE: u32 = 256;

/// The settings and size of the last frame.
#[derive(Default)]
pub struct AccumulationWatch {
    last: Option<(AoSettings, (u32, u32))>,
}

impl AccumulationWatch {
    /// True when `settings` or `size` differ from the last frame's (the mean must start again).
    pub fn changed(&mut self, settings: &AoSettings, size: (u32, u32)) -> bool {
        let now = Some((*settings, size));
        let changed = self.last.is_some() && self.last != now;
        self.last = now;
        changed
    }
}

/// The accumulation the window starts with: the scene's `--accumulate` when given, else
/// [`WINDOW_ACCUMULATE`].
pub fn window_accumulate(from_scene: u32) -> u32 {
    if from_scene > 1 {
        from_scene
    } else {
        WINDOW_ACCUMULATE
    }
}

#[cfg(test)]
mod tests {
    use crate::ao::AoMethod;
    use crate::platform::window::accumulation::*;

    #[test]
    fn any_change_of_setting_or_size_starts_the_mean_again() {
        let mut watch = AccumulationWatch::default();
        let rtao = AoSettings {
            method: AoMethod::Rtao,
            ..Default::default()
        };
        assert!(!watch.changed(&rtao, (64, 48)), "the first frame");
        assert!(!watch.changed(&rtao, (64, 48)));
        assert!(watch.changed(&rtao, (80, 48)), "resized");
        let sao = AoSettings {
            method: AoMethod::Sao,
            ..rtao
        };
        assert!(watch.changed(&sao, (80, 48)), "another method");
        assert!(watch.changed(&rtao, (80, 48)), "back to rtao");
        let wider = AoSettings {
            radius: rtao.radius * 2.0,
            ..rtao
        };
        assert!(watch.changed(&wider, (80, 48)), "radius");
        let more_rays = AoSettings {
            rays: wider.rays + 1,
            ..wider
        };
        assert!(watch.changed(&more_rays, (80, 48)), "rays");
        assert!(!watch.changed(&more_rays, (80, 48)));
    }

    #[test]
    fn the_window_accumulates_unless_the_scene_says_how_many() {
        assert_eq!(window_accumulate(1), WINDOW_ACCUMULATE);
        assert_eq!(window_accumulate(8), 8);
    }
}
