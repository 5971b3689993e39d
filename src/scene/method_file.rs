//! A method of the user's own (`--method-file my_ao.toml`): its name, a GLSL file beside the TOML
//! file, what the engine must draw for it, its `aoCounts`, and its parameters with ranges and
//! defaults, which reach the shader as `#define`s. The interface the shader sees is the one the
//! engine's own methods see (`Res/ao/common.glsl`); `docs/method-file.md` describes both.

use super::ao_defaults::Recommended;
pub use super::method_inputs::MethodReads;
use super::method_inputs::RawRecommended;
use super::places::KeyPlaces;
use anyhow::{anyhow, bail, Context as _, Result};
use rust_i18n::t;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// A method file is a few hundred bytes; anything much bigger is the wrong file.
pub const MAX_METHOD_FILE_BYTES: u64 = 64 << 10;
/// Enough sliders for a method; more is a generated file gone wrong.
pub const MAX_PARAMETERS: usize = 32;

/// Names the engine defines itself (camera planes, the normal source, the mip offset) or that the
/// GLSL preprocessor reserves: a parameter of the same name would be redefined or shadowed.
const RESERVED_PREFIXES: [&str; 3] = ["AO_", "CAMERA_", "GL_"];
const RESERVED_NAMES: [&str; 4] = ["LOG_MAX_OFFSET", "PI", "BLUR_REACH", "SAO_SAMPLES"];

/// One of the two `aoCounts` numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CountRule {
    Fixed(i32),
    /// The whole number of units of this many taps nearest to the sample budget (`"samples/4"`).
    SamplesPer(u32),
}

impl CountRule {
    pub fn value(self, samples: u32) -> i32 {
        match self {
            CountRule::Fixed(n) => n,
            CountRule::SamplesPer(unit) => {
                let unit = unit.max(1);
                ((samples + unit / 2) / unit).max(1) as i32
            }
        }
    }
}

/// A parameter: `#define NAME value` in the method's shader, a slider in the window's panel.
#[derive(Clone, Debug, PartialEq)]
pub struct MethodParameter {
    pub name: String,
    pub default: f32,
    pub min: f32,
    pub max: f32,
    /// The value in use (the default until changed).
    pub value: f32,
}

/// A method file, read and checked.
#[derive(Clone, Debug, PartialEq)]
pub struct MethodFile {
    /// The TOML file.
    pub path: PathBuf,
    pub name: String,
    /// The fragment shader, inside the TOML file's folder.
    pub shader: PathBuf,
    pub reads: MethodReads,
    pub counts: [CountRule; 2],
    pub parameters: Vec<MethodParameter>,
    /// What runs where neither the scene nor a flag sets a key (`[recommended]`).
    pub recommended: Recommended,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMethodFile {
    name: String,
    shader: String,
    #[serde(default)]
    reads: Vec<String>,
    #[serde(default)]
    counts: Option<[RawCount; 2]>,
    #[serde(default, rename = "parameter")]
    parameters: Vec<RawParameter>,
    #[serde(default)]
    recommended: RawRecommended,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawCount {
    Number(i64),
    Rule(String),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawParameter {
    name: String,
    default: f64,
    min: f64,
    max: f64,
}

impl MethodFile {
    /// Reads and checks `path`; every error names the file, and the line and column of the value
    /// at fault where the file writes one.
    pub fn read(path: &Path) -> Result<MethodFile> {
        let shown = path.display().to_string();
        let bytes = crate::io::read_capped(path, MAX_METHOD_FILE_BYTES)
            .with_context(|| t!("method_file.cannot_read", path = shown).into_owned())?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let byte = e.utf8_error().valid_up_to();
            anyhow!("{}", t!("method_file.not_utf8", path = shown, byte = byte))
        })?;
        let raw: RawMethodFile = toml::from_str(&text).map_err(|e| {
            let at = e
                .span()
                .map(|s| line_col(&text, s.start))
                .map(|(l, c)| format!(":{l}:{c}"))
                .unwrap_or_default();
            anyhow!("{shown}{at}: {}", e.message())
        })?;
        let places = KeyPlaces::of(&text);
        let at = |key: &str| match places.line_col(key, &text) {
            Some((line, col)) => format!("{shown}:{line}:{col}"),
            None => shown.clone(),
        };
        check_name(&raw.name).map_err(|why| anyhow!("{}: {why}", at("name")))?;
        let shader =
            shader_beside(path, &raw.shader).map_err(|why| anyhow!("{}: {why}", at("shader")))?;
        let mut reads = MethodReads::default();
        for (i, r) in raw.reads.iter().enumerate() {
            match r.as_str() {
                "normals" => reads.normals = true,
                "back-faces" => reads.back_faces = true,
                "second-layer" => reads.second_layer = true,
                "thickness" => reads.thickness = true,
                other => bail!(
                    "{}: {}",
                    at(&format!("reads[{i}]")),
                    t!("method_file.unknown_read", name = other)
                ),
            }
        }
        let mut counts = [CountRule::SamplesPer(1), CountRule::Fixed(1)];
        if let Some(raw_counts) = &raw.counts {
            for (i, c) in raw_counts.iter().enumerate() {
                counts[i] = count_rule(c)
                    .map_err(|why| anyhow!("{}: {why}", at(&format!("counts[{i}]"))))?;
            }
        }
        if raw.parameters.len() > MAX_PARAMETERS {
            bail!(
                "{}: {}",
                at("parameter"),
                t!("method_file.too_many_parameters", max = MAX_PARAMETERS)
            );
        }
        let mut parameters: Vec<MethodParameter> = Vec::new();
        for (i, p) in raw.parameters.iter().enumerate() {
            let here = |key: &str| at(&format!("parameter[{i}].{key}"));
            check_parameter_name(&p.name).map_err(|why| anyhow!("{}: {why}", here("name")))?;
            if parameters.iter().any(|q| q.name == p.name) {
                bail!(
                    "{}: {}",
                    here("name"),
                    t!("method_file.duplicate_parameter", name = p.name)
                );
            }
            let finite = |v: f64| v.is_finite() && v.abs() <= f32::MAX as f64;
            for (key, v) in [("min", p.min), ("max", p.max), ("default", p.default)] {
                if !finite(v) {
                    bail!("{}: {}", here(key), t!("method_file.not_finite", key = key));
                }
            }
            if p.min > p.max {
                bail!(
                    "{}: {}",
                    here("max"),
                    t!("method_file.max_below_min", min = p.min, max = p.max)
                );
            }
            if p.default < p.min || p.default > p.max {
                bail!(
                    "{}: {}",
                    here("default"),
                    t!(
                        "method_file.default_outside",
                        default = p.default,
                        min = p.min,
                        max = p.max
                    )
                );
            }
            parameters.push(MethodParameter {
                name: p.name.clone(),
                default: p.default as f32,
                min: p.min as f32,
                max: p.max as f32,
                value: p.default as f32,
            });
        }
        let recommended = super::method_inputs::check(&raw.recommended, &reads)
            .map_err(|(key, why)| anyhow!("{}: {why}", at(&format!("recommended.{key}"))))?;
        Ok(MethodFile {
            path: path.to_path_buf(),
            name: raw.name,
            shader,
            reads,
            counts,
            parameters,
            recommended,
        })
    }

    /// `aoCounts` for a sample budget.
    pub fn counts(&self, samples: u32) -> [i32; 2] {
        [self.counts[0].value(samples), self.counts[1].value(samples)]
    }

    /// The parameters' `#define`s, in the file's order.
    pub fn defines(&self) -> Vec<(String, String)> {
        self.parameters
            .iter()
            .map(|p| (p.name.clone(), crate::gl::preprocess::glsl_float(p.value)))
            .collect()
    }

    /// Sets a parameter, brought into its range (a slider or a flag cannot leave it).
    pub fn set(&mut self, name: &str, value: f32) -> Result<()> {
        let Some(p) = self.parameters.iter_mut().find(|p| p.name == name) else {
            let known: Vec<&str> = self.parameters.iter().map(|p| p.name.as_str()).collect();
            bail!(
                "{}",
                t!(
                    "method_file.no_such_parameter",
                    path = self.path.display(),
                    name = name,
                    known = known.join(", ")
                )
            );
        };
        p.value = if value.is_finite() {
            value.clamp(p.min, p.max)
        } else {
            p.default
        };
        Ok(())
    }
}

fn line_col(text: &str, byte: usize) -> (usize, usize) {
    let before = &text[..byte.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().unwrap_or("").chars().count() + 1;
    (line, col)
}

fn check_name(name: &str) -> Result<(), String> {
    let ok = !name.is_empty()
        && name.len() <= 40
        && name.starts_with(|c: char| c.is_ascii_lowercase())
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-');
    if !ok {
        return Err(t!("method_file.bad_name", name = name).into_owned());
    }
    if crate::scene::ao_settings::AoMethod::from_name(name).is_some() {
        return Err(t!("method_file.builtin_name", name = name).into_owned());
    }
    Ok(())
}

fn check_parameter_name(name: &str) -> Result<(), String> {
    let identifier = name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && name.len() <= 64;
    if !identifier {
        return Err(t!("method_file.bad_parameter_name", name = name).into_owned());
    }
    let reserved = RESERVED_NAMES.contains(&name)
        || RESERVED_PREFIXES.iter().any(|p| name.starts_with(p))
        || name.contains("__");
    if reserved {
        return Err(t!("method_file.reserved_parameter_name", name = name).into_owned());
    }
    Ok(())
}

fn count_rule(raw: &RawCount) -> Result<CountRule, String> {
    match raw {
        RawCount::Number(n) if (1..=1024).contains(n) => Ok(CountRule::Fixed(*n as i32)),
        RawCount::Rule(s) => match s.strip_prefix("samples") {
            Some("") => Ok(CountRule::SamplesPer(1)),
            Some(rest) => match rest
                .strip_prefix('/')
                .and_then(|u| u.trim().parse::<u32>().ok())
            {
                Some(unit) if (1..=256).contains(&unit) => Ok(CountRule::SamplesPer(unit)),
                _ => Err(t!("method_file.bad_count", value = s).into_owned()),
            },
            None => Err(t!("method_file.bad_count", value = s).into_owned()),
        },
        RawCount::Number(n) => Err(t!("method_file.bad_count", value = n).into_owned()),
    }
}

/// The shader `name` beside the method file: relative, no climbing out, inside the folder once
/// links are followed, and a regular file.
fn shader_beside(method_file: &Path, name: &str) -> Result<PathBuf, String> {
    let folder = match method_file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let relative = Path::new(name);
    let outside = || {
        t!(
            "method_file.shader_outside",
            name = name,
            dir = folder.display()
        )
        .into_owned()
    };
    if name.is_empty() || relative.has_root() || !crate::gl::model_refs::stays_inside(relative) {
        return Err(outside());
    }
    let file = folder.join(relative);
    let (Ok(base), Ok(resolved)) = (folder.canonicalize(), file.canonicalize()) else {
        return Err(t!("method_file.no_shader", path = file.display()).into_owned());
    };
    if !resolved.starts_with(&base) {
        return Err(outside());
    }
    if !resolved.is_file() {
        return Err(t!("method_file.shader_not_file", path = file.display()).into_owned());
    }
    Ok(file)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!(
            "opengl3d-method-file-{name}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("my.frag"), "#version 450\nvoid main() {}\n").unwrap();
        d
    }

    fn read(name: &str, toml: &str) -> (Result<MethodFile>, PathBuf) {
        let d = folder(name);
        let path = d.join("my.toml");
        std::fs::write(&path, toml).unwrap();
        let r = MethodFile::read(&path);
        (r, d)
    }

    const GOOD: &str = r#"name = "my-hbao"
shader = "my.frag"
reads = ["normals"]
counts = [4, "samples/4"]

[[parameter]]
name = "SIN_BIAS"
default = 0.1736
min = 0.0
max = 0.5
"#;

    #[test]
    fn a_good_file_reads_and_gives_counts_and_defines() {
        let (m, d) = read("good", GOOD);
        let m = m.unwrap();
        assert_eq!(m.name, "my-hbao");
        assert!(m.reads.normals && !m.reads.back_faces);
        // The built-in hbao's counts at 11 samples: 4 directions of 3 steps.
        assert_eq!(m.counts(11), [4, 3]);
        assert_eq!(m.counts(1), [4, 1]);
        assert_eq!(
            m.defines(),
            vec![("SIN_BIAS".to_string(), "0.1736".to_string())]
        );
        let _ = std::fs::remove_dir_all(d);
    }

    #[test]
    fn set_keeps_a_parameter_in_its_range() {
        let (m, d) = read("set", GOOD);
        let mut m = m.unwrap();
        m.set("SIN_BIAS", 7.0).unwrap();
        assert_eq!(m.parameters[0].value, 0.5);
        m.set("SIN_BIAS", f32::NAN).unwrap();
        assert_eq!(m.parameters[0].value, 0.1736);
        assert!(m
            .set("NOPE", 1.0)
            .unwrap_err()
            .to_string()
            .contains("SIN_BIAS"));
        let _ = std::fs::remove_dir_all(d);
    }

    #[test]
    fn errors_point_at_the_line_and_column() {
        let cases: [(&str, String, &str); 7] = [
            ("name", GOOD.replace("my-hbao", "hbao"), ":1:8"),
            ("badname", GOOD.replace("my-hbao", "My AO"), ":1:8"),
            ("outside", GOOD.replace("my.frag", "../my.frag"), ":2:10"),
            ("missing", GOOD.replace("my.frag", "none.frag"), ":2:10"),
            ("read", GOOD.replace("\"normals\"", "\"colour\""), ":3:10"),
            (
                "count",
                GOOD.replace("\"samples/4\"", "\"samples/0\""),
                ":4:14",
            ),
            ("reserved", GOOD.replace("SIN_BIAS", "CAMERA_FAR"), ":7:8"),
        ];
        for (name, text, at) in cases {
            let (r, d) = read(name, &text);
            let e = format!("{:#}", r.unwrap_err());
            assert!(e.contains(&format!("my.toml{at}:")), "{name}: {e}");
            let _ = std::fs::remove_dir_all(d);
        }
        let range = GOOD.replace("default = 0.1736", "default = 0.9");
        let (r, d) = read("range", &range);
        let e = format!("{:#}", r.unwrap_err());
        assert!(e.contains("my.toml:8:11:"), "{e}");
        let _ = std::fs::remove_dir_all(d);
        // A TOML syntax error and an unknown key name their place too.
        let (r, d) = read("syntax", "name = \"x\"\nshader = \n");
        assert!(format!("{:#}", r.unwrap_err()).contains("my.toml:2:"));
        let _ = std::fs::remove_dir_all(d);
        let (r, d) = read("unknown", &format!("{GOOD}colour = 1\n"));
        assert!(format!("{:#}", r.unwrap_err()).contains("colour"));
        let _ = std::fs::remove_dir_all(d);
    }

    #[cfg(unix)]
    #[test]
    fn a_link_out_of_the_folder_is_refused() {
        let d = folder("link");
        let outside = std::env::temp_dir().join(format!(
            "opengl3d-method-outside-{}.frag",
            std::process::id()
        ));
        std::fs::write(&outside, "#version 450\n").unwrap();
        std::os::unix::fs::symlink(&outside, d.join("link.frag")).unwrap();
        let path = d.join("my.toml");
        std::fs::write(&path, GOOD.replace("my.frag", "link.frag")).unwrap();
        let e = format!("{:#}", MethodFile::read(&path).unwrap_err());
        assert!(e.contains("my.toml:2:10:"), "{e}");
        let _ = std::fs::remove_dir_all(d);
        let _ = std::fs::remove_file(outside);
    }
}
