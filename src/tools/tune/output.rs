//! What `tune` hands back: each chosen `[ao]` table as TOML (the whole table, so that pasted over
//! a scene's `[ao]` it reproduces the figure), a summary line per method, and `tune.md`; for a
//! method file also the file with its parameters' defaults set to the chosen values.

use super::config::TuneConfig;
use super::evaluate::MethodResult;
use crate::ao::AoSettings;
use anyhow::{Context as _, Result};
use std::fmt::Write as _;

/// `[ao]` of `ao` as TOML, its floats written as the shortest decimals of their `f32` values.
pub fn ao_toml(ao: &AoSettings) -> Result<String> {
    let mut value = toml::Value::try_from(ao).context("AO settings as TOML")?;
    shorten_floats(&mut value);
    let mut table = toml::map::Map::new();
    table.insert("ao".to_string(), value);
    Ok(toml::to_string(&toml::Value::Table(table))?)
}

/// Every float of `v` as the shortest decimal that reads back as the same `f32` (the settings
/// are `f32`; serde widens them to `f64` digits such as 0.012000000104308128).
fn shorten_floats(v: &mut toml::Value) {
    match v {
        toml::Value::Float(f) => {
            if let Ok(short) = (*f as f32).to_string().parse::<f64>() {
                *f = short;
            }
        }
        toml::Value::Array(a) => a.iter_mut().for_each(shorten_floats),
        toml::Value::Table(t) => t.iter_mut().for_each(|(_, v)| shorten_floats(v)),
        _ => {}
    }
}

/// The chosen table with a comment of its figures, ready to paste into the scene file.
pub fn toml_table(r: &MethodResult) -> Result<String> {
    let which = match &r.file {
        Some(f) => format!("--method-file {}", f.path.display()),
        None => format!("--methods {}", r.method.name()),
    };
    let mut s = format!(
        "# opengl3d tune --scene {} {}: training PSNR {:.2} dB (scene's own {:.2}), \
         test {:.2} dB (scene's own {:.2}); {}x{}, truth {} rays at 1/{}\n",
        r.scene_path.display(),
        which,
        r.train_tuned,
        r.train_default,
        r.test_tuned,
        r.test_default,
        r.width,
        r.height,
        r.ref_rays,
        r.ref_scale
    );
    s.push_str(&ao_toml(&r.tuned)?);
    Ok(s)
}

/// One line of figures for the terminal.
pub fn summary(r: &MethodResult) -> String {
    let changed = changed_keys(r);
    let mut line = rust_i18n::t!(
        "tune.summary",
        scene = r.scene,
        method = r.name(),
        train_default = format!("{:.2}", r.train_default),
        train_tuned = format!("{:.2}", r.train_tuned),
        test_default = format!("{:.2}", r.test_default),
        test_tuned = format!("{:.2}", r.test_tuned),
        evaluated = r.evaluated,
        changed = if changed.is_empty() {
            "-".to_string()
        } else {
            changed.join(", ")
        }
    )
    .into_owned();
    if r.keys.is_empty() {
        line.push('\n');
        line.push_str(&rust_i18n::t!("tune.nothing_free", method = r.name()));
    }
    if let Some(c) = r.cost {
        line.push('\n');
        line.push_str(&rust_i18n::t!(
            "tune.cost",
            budget = c.budget,
            default = format!("{:.2}", c.default_ratio),
            tuned = format!("{:.2}", c.tuned_ratio),
            over = r.over_budget
        ));
    }
    line
}

/// A method file's parameters, default and chosen, one line each, for the terminal.
pub fn parameter_lines(r: &MethodResult) -> String {
    let Some(f) = &r.file else {
        return String::new();
    };
    let lines: Vec<String> = f
        .parameters
        .iter()
        .map(|p| {
            rust_i18n::t!(
                "tune.parameter",
                name = p.name,
                default = p.default,
                tuned = p.tuned
            )
            .into_owned()
        })
        .collect();
    lines.join("\n")
}

/// The keys whose chosen value differs from the scene's, as `key = value`; then a method file's
/// parameters that changed.
fn changed_keys(r: &MethodResult) -> Vec<String> {
    let mut out = changed_ao_keys(r);
    if let Some(f) = &r.file {
        for p in &f.parameters {
            if p.tuned != p.default {
                out.push(format!("{} = {}", p.name, p.tuned));
            }
        }
    }
    out
}

fn changed_ao_keys(r: &MethodResult) -> Vec<String> {
    let (Ok(a), Ok(b)) = (
        toml::Value::try_from(r.default),
        toml::Value::try_from(r.tuned),
    ) else {
        return Vec::new();
    };
    let (Some(a), Some(mut b)) = (a.as_table().cloned(), b.as_table().cloned()) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let parameters: Vec<&str> = match &r.file {
        Some(f) => f.parameters.iter().map(|p| p.name.as_str()).collect(),
        None => Vec::new(),
    };
    for key in r.keys.iter().filter(|k| !parameters.contains(&k.as_str())) {
        let new = b.remove(key.as_str());
        if a.get(key.as_str()) != new.as_ref() {
            let mut shown = new.unwrap_or_else(|| toml::Value::String("(unset)".into()));
            shorten_floats(&mut shown);
            out.push(format!("{key} = {shown}"));
        }
    }
    out
}

/// `SCENE-METHOD.toml` for every result (for a method file: `SCENE-NAME.toml`, the file with the
/// chosen defaults, and `SCENE-NAME.ao.toml`, the `[ao]` table it was measured with) and `tune.md`
/// with all the figures. Never the user's method file itself.
pub fn write(results: &[MethodResult], cfg: &TuneConfig) -> Result<()> {
    std::fs::create_dir_all(&cfg.out)
        .with_context(|| format!("cannot create {}", cfg.out.display()))?;
    for r in results {
        let table = match &r.file {
            Some(f) => {
                let tuned = cfg.out.join(tuned_file_name(r, f));
                let text = super::method_text::tuned_method_file(r, f)?;
                crate::io::write_file(&tuned, text.as_bytes())?;
                format!("{}-{}.ao.toml", r.scene, f.name)
            }
            None => format!("{}-{}.toml", r.scene, r.method.name()),
        };
        crate::io::write_file(&cfg.out.join(table), toml_table(r)?.as_bytes())?;
    }
    crate::io::write_file(&cfg.out.join("tune.md"), markdown(results, cfg).as_bytes())?;
    Ok(())
}

/// Where `write` puts a method file with the chosen defaults.
pub fn tuned_file_name(r: &MethodResult, f: &super::FileResult) -> String {
    format!("{}-{}.toml", r.scene, f.name)
}

/// The run's figures as a markdown table.
fn markdown(results: &[MethodResult], cfg: &TuneConfig) -> String {
    let p = &cfg.protocol;
    let mut s = String::from("# opengl3d tune\n\n");
    let _ = writeln!(
        s,
        "Output {}×{}, truth {}×{} at {} rays per pixel (box average by {}); PSNR on the \
         truth's surface pixels, mean over the training cameras (searched) and the test cameras \
         (held out); at most {} coordinate-descent passes{}.\n",
        p.width,
        p.height,
        p.width.div_ceil(p.ref_scale),
        p.height.div_ceil(p.ref_scale),
        p.ref_rays,
        p.ref_scale,
        cfg.passes,
        match cfg.budget {
            Some(b) => format!(
                "; budget {b} × the lesson chain's AO time, each configuration timed (wall clock \
                 around glFinish, median of {} frames at the scene's camera and the output size) \
                 just after the lesson chain",
                p.frames
            ),
            None => String::new(),
        }
    );
    s.push_str(
        "| scene | method | train (scene's) | train (tuned) | test (scene's) | test (tuned) | \
         configurations | AO time / lesson (scene's → tuned) | changed |\n\
         |---|---|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for r in results {
        let changed = changed_keys(r);
        let _ = writeln!(
            s,
            "| {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {} | {} |",
            r.scene,
            r.name(),
            r.train_default,
            r.train_tuned,
            r.test_default,
            r.test_tuned,
            r.evaluated,
            match r.cost {
                Some(c) => format!("{:.2} → {:.2}", c.default_ratio, c.tuned_ratio),
                None => "—".to_string(),
            },
            if changed.is_empty() {
                "—".to_string()
            } else {
                changed.join(", ").replace('|', "\\|")
            }
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use crate::ao::{AoMethod, AoSettings, GuardBand, SlicePreset, Thickness};
    use crate::tools::tune::output::ao_toml;

    #[derive(serde::Deserialize)]
    struct File {
        ao: AoSettings,
    }

    #[test]
    fn the_table_reads_back_as_the_same_settings() {
        let ao = AoSettings {
            method: AoMethod::Vbao,
            bias: 0.006,
            thickness: Some(Thickness::Metres(0.375)),
            quality: Some(SlicePreset::High),
            guard_band: GuardBand::Auto,
            ..AoSettings::default()
        };
        let text = ao_toml(&ao).unwrap();
        assert!(text.starts_with("[ao]\n"), "{text}");
        assert!(text.contains("bias = 0.006\n"), "{text}");
        assert!(text.contains("thickness = 0.375\n"), "{text}");
        let back: File = toml::from_str(&text).unwrap();
        assert_eq!(back.ao, ao);
        let back: File = toml::from_str(&ao_toml(&AoSettings::default()).unwrap()).unwrap();
        assert_eq!(back.ao, AoSettings::default());
    }
}
