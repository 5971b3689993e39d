//! Checks of a scene's values. Each problem names its key ("camera.near", "object[2].scale[1]") so
//! the caller can say where the value came from: a line of the scene file, a flag, or a default.
//!
//! Values that can only give a broken frame (NaN, infinity, planes that leave no depth precision) are
//! errors; values that are merely outside what looks sensible (a negative colour) are clamped with a
//! warning.

use super::desc::SceneDesc;

/// Largest far/near ratio accepted: ten times the stress bench's widest case (near 0.01 m, far 1e6 m),
/// which still separates surfaces; near = 1e-30 m with far = 1000 m leaves every depth at 1.0.
pub const MAX_DEPTH_RATIO: f32 = 1e9;
/// Largest output side in pixels.
const MAX_SIZE: u32 = 16384;
/// Bloom strength is a blend weight; beyond this the frame is white.
const MAX_BLOOM_STRENGTH: f32 = 10.0;

/// One bad value of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Issue {
    /// Key path in the scene file ("light.color[1]").
    pub key: String,
    /// The value as it was (before any clamping).
    pub value: String,
    /// What is wrong, and for a clamp what is used instead.
    pub message: String,
}

impl std::fmt::Display for Issue {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "{} = {}: {}", self.key, self.value, self.message)
    }
}

/// `value` is shown with `{:?}`: 1e-30 rather than 0.000…1, arrays as [x, y, z].
fn issue(key: impl Into<String>, value: impl std::fmt::Debug, message: String) -> Issue {
    Issue {
        key: key.into(),
        value: format!("{value:?}"),
        message,
    }
}

/// Errors for every non-finite element of `v` (`key[i]`).
fn finite(out: &mut Vec<Issue>, key: &str, v: &[f32]) {
    for (i, x) in v.iter().enumerate() {
        if !x.is_finite() {
            out.push(issue(
                format!("{key}[{i}]"),
                x,
                "must be a finite number".into(),
            ));
        }
    }
}

/// An error when the single value `x` is not finite.
fn finite_value(out: &mut Vec<Issue>, key: &str, x: f32) {
    if !x.is_finite() {
        out.push(issue(key, x, "must be a finite number".into()));
    }
}

/// Clamps negative elements of `v` to 0, noting each.
fn clamp_negative(out: &mut Vec<Issue>, key: &str, v: &mut [f32]) {
    for (i, x) in v.iter_mut().enumerate() {
        if *x < 0.0 {
            out.push(issue(
                format!("{key}[{i}]"),
                *x,
                "a colour cannot be negative, using 0".into(),
            ));
            *x = 0.0;
        }
    }
}

impl SceneDesc {
    /// Every value that would give a broken frame; empty when the scene can be rendered.
    pub fn errors(&self) -> Vec<Issue> {
        let mut out = Vec::new();
        let c = &self.camera;
        finite(&mut out, "camera.eye", &c.eye);
        finite(&mut out, "camera.target", &c.target);
        if out.is_empty() && c.eye == c.target {
            out.push(issue(
                "camera.target",
                c.target,
                "the camera's eye and target are the same point".into(),
            ));
        }
        if !(c.fov_y > 0.0 && c.fov_y < 179.0) {
            out.push(issue(
                "camera.fov_y",
                c.fov_y,
                "the field of view must be between 0 and 179 degrees".into(),
            ));
        }
        self.plane_errors(&mut out);
        for (key, v) in [
            ("output.width", self.output.width),
            ("output.height", self.output.height),
        ] {
            if v == 0 || v > MAX_SIZE {
                out.push(issue(
                    key,
                    v,
                    format!("the output size must be between 1 and {MAX_SIZE}"),
                ));
            }
        }
        let l = &self.light;
        finite(&mut out, "light.direction", &l.direction);
        if l.direction.iter().all(|x| *x == 0.0) {
            out.push(issue(
                "light.direction",
                l.direction,
                "the light direction cannot be zero".into(),
            ));
        }
        finite(&mut out, "light.color", &l.color);
        finite(&mut out, "light.ambient", &l.ambient);
        finite_value(&mut out, "bloom.threshold", self.bloom.threshold);
        finite_value(&mut out, "bloom.strength", self.bloom.strength);
        let ao = &self.ao;
        for (key, v) in [
            ("ao.radius", ao.radius),
            ("ao.bias", ao.bias),
            ("ao.intensity", ao.intensity),
            ("ao.power", ao.power),
        ] {
            finite_value(&mut out, key, v);
        }
        if ao.radius <= 0.0 {
            out.push(issue(
                "ao.radius",
                ao.radius,
                "the AO radius must be more than 0 m".into(),
            ));
        }
        finite(&mut out, "ao.tint", &ao.tint);
        for (i, o) in self.objects.iter().enumerate() {
            let key = |k: &str| format!("object[{i}].{k}");
            finite(&mut out, &key("position"), &o.position);
            finite(&mut out, &key("rotation"), &o.rotation);
            finite(&mut out, &key("scale"), &o.scale);
            finite(&mut out, &key("color"), &o.color);
            for (j, s) in o.scale.iter().enumerate() {
                if *s == 0.0 {
                    out.push(issue(
                        format!("object[{i}].scale[{j}]"),
                        s,
                        format!("a zero scale flattens {} to nothing", o.mesh),
                    ));
                }
            }
        }
        out
    }

    fn plane_errors(&self, out: &mut Vec<Issue>) {
        let (near, far) = (self.camera.near, self.camera.far);
        if !(near.is_finite() && near > 0.0) {
            out.push(issue(
                "camera.near",
                near,
                "the near plane must be a finite distance above 0 m".into(),
            ));
        } else if !(far.is_finite() && far > near) {
            out.push(issue(
                "camera.far",
                far,
                format!("the far plane must be finite and beyond the near plane ({near} m)"),
            ));
        } else if far / near > MAX_DEPTH_RATIO {
            out.push(issue(
                "camera.near",
                near,
                format!(
                    "with far = {far} m the depth buffer cannot separate surfaces \
                     (far/near must be at most {MAX_DEPTH_RATIO:e}): use near ≥ {} m",
                    far / MAX_DEPTH_RATIO
                ),
            ));
        }
    }

    /// Clamps values outside their sensible range and says what changed (keys name the values).
    pub fn clamp_values(&mut self) -> Vec<Issue> {
        let mut out = Vec::new();
        clamp_negative(&mut out, "light.color", &mut self.light.color);
        clamp_negative(&mut out, "light.ambient", &mut self.light.ambient);
        for (i, o) in self.objects.iter_mut().enumerate() {
            clamp_negative(&mut out, &format!("object[{i}].color"), &mut o.color);
        }
        let b = &mut self.bloom;
        if b.threshold < 0.0 {
            out.push(issue("bloom.threshold", b.threshold, "using 0".into()));
            b.threshold = 0.0;
        }
        if !(0.0..=MAX_BLOOM_STRENGTH).contains(&b.strength) && b.strength.is_finite() {
            let to = b.strength.clamp(0.0, MAX_BLOOM_STRENGTH);
            out.push(issue(
                "bloom.strength",
                b.strength,
                format!("bloom strength is 0 to {MAX_BLOOM_STRENGTH}, using {to}"),
            ));
            b.strength = to;
        }
        out
    }

    /// Fails on the first batch of errors, each named by its key (no file places: see `SceneFile`).
    pub fn validate(&self) -> anyhow::Result<()> {
        let errors = self.errors();
        if errors.is_empty() {
            return Ok(());
        }
        let lines: Vec<String> = errors.iter().map(Issue::to_string).collect();
        anyhow::bail!("{}", lines.join("\n"))
    }
}
