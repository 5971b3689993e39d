//! A method file with its parameters' defaults set to the values `tune` chose: the user's text
//! kept as written (comments, order, layout), only each `default = …` value replaced. The format
//! has no way to set a parameter from outside the file, so this copy is how a result goes back.

use super::evaluate::{FileResult, MethodResult};
use crate::scene::method_file::MAX_METHOD_FILE_BYTES;
use crate::scene::KeyPlaces;
use anyhow::{anyhow, bail, Result};

/// The text of `f`'s method file with the chosen defaults, under a comment of the run's figures.
pub fn tuned_method_file(r: &MethodResult, f: &FileResult) -> Result<String> {
    let bytes = crate::io::read_capped(&f.path, MAX_METHOD_FILE_BYTES)?;
    let text = String::from_utf8(bytes)
        .map_err(|_| anyhow!("{}: not UTF-8 any more", f.path.display()))?;
    let values: Vec<f32> = f.parameters.iter().map(|p| p.tuned).collect();
    let body =
        with_defaults(&text, &values).map_err(|why| anyhow!("{}: {why}", f.path.display()))?;
    let header = rust_i18n::t!(
        "tune.method_file_header",
        path = f.path.display(),
        scene = r.scene_path.display(),
        train = format!("{:.2}", r.train_tuned),
        test = format!("{:.2}", r.test_tuned)
    );
    let header: String = header.lines().map(|l| format!("# {l}\n")).collect();
    Ok(format!("{header}{body}"))
}

/// `text` (a method file) with the `default` of its `i`-th `[[parameter]]` set to `values[i]`.
pub fn with_defaults(text: &str, values: &[f32]) -> Result<String> {
    let places = KeyPlaces::of(text);
    // Byte ranges of the values to replace, last first so earlier offsets stay valid.
    let mut spans = Vec::new();
    let line_starts: Vec<usize> = std::iter::once(0)
        .chain(text.match_indices('\n').map(|(i, _)| i + 1))
        .collect();
    for (i, v) in values.iter().enumerate() {
        let key = format!("parameter[{i}].default");
        let Some((line, col)) = places.line_col(&key, text) else {
            bail!("{key} is not written in the file");
        };
        let line_start = line_starts[line - 1];
        let start = line_start
            + text[line_start..]
                .char_indices()
                .nth(col - 1)
                .map_or(0, |(b, _)| b);
        let len = text[start..]
            .find(|c: char| c.is_whitespace() || matches!(c, '#' | ',' | '}' | ']'))
            .unwrap_or(text.len() - start);
        if len == 0 {
            bail!("{key} has no value to replace");
        }
        spans.push((start, start + len, toml_float(*v)));
    }
    spans.sort_by_key(|s| std::cmp::Reverse(s.0));
    let mut out = text.to_string();
    for (start, end, value) in spans {
        out.replace_range(start..end, &value);
    }
    Ok(out)
}

/// `v` as a TOML float that reads back as the same `f32`: its shortest decimal, with a point.
fn toml_float(v: f32) -> String {
    let s = v.to_string();
    if s.contains(['.', 'e', 'E']) {
        s
    } else {
        format!("{s}.0")
    }
}

#[cfg(test)]
mod tests {
    use super::with_defaults;

    const FILE: &str =
        "name = \"mine\" # mine\nshader = \"m.frag\"\n\n[[parameter]]\nname = \"A\"\n\
        default = 0.1736 # sin 10°\nmin = 0.0\nmax = 0.5\n\n[[parameter]]\n\
        name = \"B\"\nmin = -2\nmax = 8\ndefault = 3\n";

    #[derive(serde::Deserialize)]
    struct Raw {
        parameter: Vec<Param>,
    }
    #[derive(serde::Deserialize)]
    struct Param {
        name: String,
        default: f64,
    }

    #[test]
    fn only_the_defaults_change_and_the_text_reads_back() {
        let out = with_defaults(FILE, &[0.0625, 5.0]).unwrap();
        let raw: Raw = toml::from_str(&out).unwrap();
        let got: Vec<(String, f32)> = raw
            .parameter
            .into_iter()
            .map(|p| (p.name, p.default as f32))
            .collect();
        assert_eq!(got, [("A".to_string(), 0.0625), ("B".to_string(), 5.0)]);
        assert!(out.contains("default = 0.0625 # sin 10°\n"), "{out}");
        assert!(out.contains("default = 5.0\n"), "{out}");
        // Everything else as written.
        assert_eq!(
            out.replace("0.0625", "0.1736").replace("5.0\n", "3\n"),
            FILE
        );
        // Inline tables too.
        let inline = "name = \"m\"\nshader = \"m.frag\"\n\
            parameter = [{ name = \"A\", default = 1, min = 0, max = 2 }]\n";
        let out = with_defaults(inline, &[1.5]).unwrap();
        assert!(out.contains("default = 1.5, min"), "{out}");
        // A value the file does not write cannot be replaced.
        assert!(with_defaults("name = \"m\"\n", &[1.0]).is_err());
    }
}
