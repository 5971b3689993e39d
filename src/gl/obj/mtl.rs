//! Checking a material library (`.mtl`). The engine colours each object from its scene, so the
//! materials are not used; a library an exporter wrote wrong is still reported by its file and line
//! (it usually means the OBJ beside it is damaged too), and one that is missing is a warning.

use anyhow::{bail, Result};
use rust_i18n::t;

/// Colour statements: 1 or 3 numbers, or `spectral FILE [factor]`, or `xyz X [Y Z]`.
const COLOURS: &[&str] = &["Ka", "Kd", "Ks", "Ke", "Tf"];

/// Statements holding one number (`d` may start with `-halo`).
const SCALARS: &[&str] = &[
    "Ns",
    "Ni",
    "d",
    "Tr",
    "sharpness",
    "illum",
    "Pr",
    "Pm",
    "Ps",
    "Pc",
    "Pcr",
    "aniso",
    "anisor",
];

/// Statements naming a texture file (options may come before the name).
const MAPS: &[&str] = &["bump", "disp", "decal", "refl", "norm"];

/// Checks the text of the material library `shown`: every known statement with values of the right
/// kind, after a `newmtl`. Unknown statements (exporters add their own) are accepted. Returns the
/// material names.
pub fn check(text: &str, shown: &str) -> Result<Vec<String>> {
    let mut names = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let place = format!("{shown}:{}", i + 1);
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or_default();
        let args: Vec<&str> = words.take_while(|w| !w.starts_with('#')).collect();
        if keyword == "newmtl" {
            names.push(line[keyword.len()..].trim().to_string());
            continue;
        }
        let known = COLOURS.contains(&keyword)
            || SCALARS.contains(&keyword)
            || MAPS.contains(&keyword)
            || keyword.starts_with("map_");
        if !known {
            continue;
        }
        if names.is_empty() {
            bail!(
                "{}",
                t!("mtl.before_newmtl", place = place, keyword = keyword)
            );
        }
        let numbers = |args: &[&str], counts: &[usize]| -> Result<()> {
            if !counts.contains(&args.len()) {
                let want = counts
                    .iter()
                    .map(|c| c.to_string())
                    .collect::<Vec<_>>()
                    .join(&t!("cli.or"));
                let count = args.len();
                bail!(
                    "{}",
                    t!(
                        "mtl.value_count",
                        place = place,
                        keyword = keyword,
                        want = want,
                        count = count
                    )
                );
            }
            for a in args {
                if !a.parse::<f32>().is_ok_and(f32::is_finite) {
                    bail!(
                        "{}",
                        t!(
                            "mtl.not_a_number",
                            place = place,
                            keyword = keyword,
                            value = a
                        )
                    );
                }
            }
            Ok(())
        };
        match (args.first().copied(), keyword) {
            (Some("spectral"), k) if COLOURS.contains(&k) => {}
            (Some("xyz"), k) if COLOURS.contains(&k) => numbers(&args[1..], &[1, 3])?,
            (_, k) if COLOURS.contains(&k) => numbers(&args, &[1, 3])?,
            (Some("-halo"), "d") => numbers(&args[1..], &[1])?,
            (_, k) if SCALARS.contains(&k) => numbers(&args, &[1])?,
            (None, _) => bail!("{}", t!("mtl.no_file", place = place, keyword = keyword)),
            _ => {}
        }
    }
    Ok(names)
}
