//! One stress case: render every output of every method and count NaN/Inf and range failures.

use super::cases::Case;
use super::report::{CaseResult, OutputCheck};
use crate::ao::AoMethod;
use crate::platform::HeadlessContext;
use crate::render::{Engine, View};
use crate::res::ResDirs;
use anyhow::{bail, Result};
use std::time::Instant;

fn check(out: &mut Vec<OutputCheck>, method: AoMethod, name: &str, v: &[f32]) -> usize {
    let bad = v.iter().filter(|x| !x.is_finite()).count();
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for x in v.iter().filter(|x| x.is_finite()) {
        lo = lo.min(*x);
        hi = hi.max(*x);
    }
    out.push(OutputCheck {
        method: method.name().into(),
        output: name.into(),
        values: v.len(),
        non_finite: bad,
        min: if lo.is_finite() { lo } else { 0.0 },
        max: if hi.is_finite() { hi } else { 0.0 },
    });
    bad
}

/// Renders `case` with each of its methods and checks every output.
pub fn run_case(ctx: &HeadlessContext, res: &ResDirs, case: &Case) -> Result<CaseResult> {
    let t = Instant::now();
    let s = &case.scene;
    let (w, h) = (s.output.width, s.output.height);
    let mut eng = Engine::new(&ctx.gl, res.clone(), s, w, h)?;
    let mut outputs = Vec::new();
    let mut failures = Vec::new();
    let mut notes = Vec::new();
    let mut non_finite = 0;
    let (mut visibility, mut surface_px) = (Vec::new(), 0usize);
    for &method in &case.methods {
        eng.ao_settings.method = method;
        eng.sync_shader_constants()?;
        let mn = method.name();
        let img = eng.render_image()?;
        if img.dimensions() != (w, h) {
            failures.push(format!("{mn}: composite is {:?}", img.dimensions()));
        }
        let Some(main_colour) = eng.fbo_main.color_texture() else {
            bail!("the engine's main framebuffer has no colour texture");
        };
        non_finite += check(
            &mut outputs,
            method,
            "main colour (RGBA16F)",
            &main_colour.read_f32(0, 4),
        );
        for level in 0..eng.ao_targets()?.tex_depth.levels() {
            let v = eng.ao_targets()?.tex_depth.read_f32(level, 1);
            non_finite += check(
                &mut outputs,
                method,
                &format!("linear depth level {level}"),
                &v,
            );
            if v.iter().any(|d| *d <= 0.0) {
                failures.push(format!(
                    "{mn}: linear depth level {level} has a distance ≤ 0"
                ));
            }
        }
        non_finite += check(
            &mut outputs,
            method,
            "AO buffer",
            &eng.ao_targets()?.sao_texture().read_f32(0, 1),
        );
        non_finite += check(
            &mut outputs,
            method,
            "blurred AO buffer",
            &eng.ao_targets()?.result_texture(true).read_f32(0, 1),
        );
        let depth = eng.render_values(View::LinearDepth)?;
        non_finite += check(&mut outputs, method, "values: linear depth", &depth);
        if depth.iter().any(|d| *d <= 0.0) {
            failures.push(format!("{mn}: linear-depth view has a distance ≤ 0"));
        }
        let far = eng.camera.far;
        for view in [View::AoRaw, View::Ao] {
            let v = eng.render_values(view)?;
            non_finite += check(
                &mut outputs,
                method,
                &format!("values: {}", view.label()),
                &v,
            );
            if v.iter().any(|a| !(0.0..=1.0).contains(a)) {
                failures.push(format!("{mn}: {} outside [0, 1]", view.label()));
            }
            if case.all_visible && v.iter().any(|a| *a != 1.0) {
                failures.push(format!(
                    "{mn}: sky-only frame is not fully visible in the {} view",
                    view.label()
                ));
            }
            if view == View::Ao {
                // Mean visibility of surface pixels (those nearer than far).
                let (sum, n) = v
                    .iter()
                    .zip(&depth)
                    .filter(|(a, d)| a.is_finite() && **d < far)
                    .fold((0.0f64, 0usize), |(s, n), (a, _)| (s + *a as f64, n + 1));
                if n > 0 {
                    visibility.push(format!("{mn} {:.3}", sum / n as f64));
                    surface_px = n;
                }
            }
        }
        if let Some(e) = crate::gl::take_error(&ctx.gl) {
            failures.push(format!("{mn}: {e}"));
        }
    }
    if visibility.is_empty() {
        notes.push("no surface pixel".to_string());
    } else {
        notes.push(format!(
            "mean surface visibility ({surface_px} px): {}",
            visibility.join(", ")
        ));
    }
    Ok(CaseResult {
        category: case.category.into(),
        name: case.name.clone(),
        width: w,
        height: h,
        near: s.camera.near,
        far: s.camera.far,
        fov_y: s.camera.fov_y,
        radius: eng.ao_settings.radius,
        intensity: eng.ao_settings.intensity,
        bias: eng.ao_settings.bias,
        methods: case.methods.iter().map(|m| m.name().to_string()).collect(),
        non_finite,
        ok: non_finite == 0 && failures.is_empty(),
        failures,
        notes,
        ms: t.elapsed().as_secs_f64() * 1e3,
        outputs,
    })
}
