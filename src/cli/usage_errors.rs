//! Command-line usage errors (clap's) in the chosen language. clap writes its errors in English;
//! with Japanese chosen, the common ones (an unknown command or flag, a flag without its value, a
//! value not in the list, a missing or conflicting argument) are written again from the error's
//! parts, followed by clap's own usage line. Others (and help, version) stay as clap writes them.
//! The language cannot come from the parsed flags, which failed: `--lang` is looked for in the raw
//! arguments, then the locale variables decide as usual.

use crate::i18n::Lang;
use clap::error::{ContextKind, ContextValue, ErrorKind};
use rust_i18n::t;
use std::ffi::OsString;

/// The value of `--lang` among raw arguments (`--lang ja` or `--lang=ja`), if a valid one is given.
pub fn lang_in_args(args: &[OsString]) -> Option<Lang> {
    let code = |s: &str| Lang::ALL.into_iter().find(|l| l.code() == s);
    let mut it = args.iter().map(|a| a.to_string_lossy());
    let mut found = None;
    while let Some(a) = it.next() {
        if a == "--" {
            break;
        }
        if a == "--lang" {
            found = it.next().and_then(|v| code(&v)).or(found);
        } else if let Some(v) = a.strip_prefix("--lang=") {
            found = code(v).or(found);
        }
    }
    found
}

/// The context value `kind` of `e` as text ("" when absent).
fn part(e: &clap::Error, kind: ContextKind) -> String {
    match e.get(kind) {
        Some(ContextValue::Strings(v)) => v.join(", "),
        Some(ContextValue::StyledStrs(v)) => v
            .iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        Some(v) => v.to_string(),
        None => String::new(),
    }
}

/// The "Usage: …" lines of clap's rendering of `e`.
fn usage_lines(e: &clap::Error) -> Vec<String> {
    let text = e.render().to_string();
    let mut lines = text
        .lines()
        .skip_while(|l| !l.starts_with("Usage:"))
        .take_while(|l| !l.trim().is_empty());
    let mut out = Vec::new();
    if let Some(first) = lines.next() {
        let rest = first.trim_start_matches("Usage:").trim();
        out.push(format!("{} {rest}", t!("usage.usage", locale = "ja")));
        out.extend(lines.map(str::to_string));
    }
    out
}

/// `e` written in Japanese, or `None` when it is not one of the errors translated here.
pub fn japanese(e: &clap::Error) -> Option<String> {
    let ja = "ja";
    let arg = part(e, ContextKind::InvalidArg);
    let mut text = match e.kind() {
        ErrorKind::InvalidSubcommand => {
            let sub = part(e, ContextKind::InvalidSubcommand);
            t!("usage.unknown_subcommand", locale = ja, name = sub).into_owned()
        }
        ErrorKind::UnknownArgument => {
            t!("usage.unknown_argument", locale = ja, name = arg).into_owned()
        }
        ErrorKind::InvalidValue => {
            let value = part(e, ContextKind::InvalidValue);
            if value.is_empty() {
                t!("usage.missing_value", locale = ja, arg = arg).into_owned()
            } else {
                let mut s =
                    t!("usage.invalid_value", locale = ja, arg = arg, value = value).into_owned();
                let valid = part(e, ContextKind::ValidValue);
                if !valid.is_empty() {
                    s.push('\n');
                    s.push_str(&t!("usage.valid_values", locale = ja, values = valid));
                }
                s
            }
        }
        ErrorKind::MissingRequiredArgument => {
            t!("usage.missing_argument", locale = ja, args = arg).into_owned()
        }
        ErrorKind::ArgumentConflict => {
            let prior = part(e, ContextKind::PriorArg);
            t!("usage.conflict", locale = ja, arg = arg, other = prior).into_owned()
        }
        _ => return None,
    };
    for (kind, key) in [
        (ContextKind::SuggestedSubcommand, "usage.did_you_mean"),
        (ContextKind::SuggestedArg, "usage.did_you_mean"),
        (ContextKind::SuggestedValue, "usage.did_you_mean"),
    ] {
        let s = part(e, kind);
        if !s.is_empty() {
            text.push_str(&format!("\n\n  {}", t!(key, locale = ja, name = s)));
        }
    }
    let usage = usage_lines(e);
    if !usage.is_empty() {
        text.push_str("\n\n");
        text.push_str(&usage.join("\n"));
    }
    text.push_str("\n\n");
    text.push_str(&t!("usage.more", locale = ja));
    Some(format!("{}{text}\n", t!("usage.error", locale = ja)))
}

/// Reports a failed parse in the language the arguments or the locale choose, and exits with
/// clap's code for it (2 for a usage error, 0 for help and version).
pub fn exit(e: clap::Error, args: &[OsString]) -> ! {
    let lang = crate::i18n::from_env(lang_in_args(args));
    if lang == Lang::Ja {
        if let Some(text) = japanese(&e) {
            eprint!("{text}");
            std::process::exit(e.exit_code());
        }
    }
    e.exit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser as _;

    fn os(args: &[&str]) -> Vec<OsString> {
        args.iter().map(OsString::from).collect()
    }

    #[test]
    fn the_lang_flag_is_found_in_raw_arguments() {
        assert_eq!(lang_in_args(&os(&["x", "--lang", "ja"])), Some(Lang::Ja));
        assert_eq!(
            lang_in_args(&os(&["x", "bogus", "--lang=en"])),
            Some(Lang::En)
        );
        assert_eq!(lang_in_args(&os(&["x", "--lang", "fr"])), None);
        assert_eq!(lang_in_args(&os(&["x", "--", "--lang", "ja"])), None);
        assert_eq!(lang_in_args(&os(&["x", "--lang"])), None);
    }

    fn error(args: &[&str]) -> clap::Error {
        crate::cli::Cli::try_parse_from(args).unwrap_err()
    }

    #[test]
    fn common_errors_are_written_in_japanese_with_the_usage_line() {
        let e = japanese(&error(&["opengl3d", "rendr"])).unwrap();
        assert!(e.contains("'rendr'というサブコマンドはありません"), "{e}");
        assert!(e.contains("'render'"), "{e}");
        assert!(e.contains("使い方: opengl3d"), "{e}");
        let e = japanese(&error(&["opengl3d", "render", "--bogus"])).unwrap();
        assert!(e.contains("'--bogus'という引数はありません"), "{e}");
        let e = japanese(&error(&["opengl3d", "render", "--out"])).unwrap();
        assert!(
            e.contains("'--out <OUT>'") && e.contains("値を指定してください"),
            "{e}"
        );
        let e = japanese(&error(&["opengl3d", "render", "--view", "x"])).unwrap();
        assert!(e.contains("'x'") && e.contains("linear-depth"), "{e}");
        // Help is not an error to translate.
        assert!(japanese(&error(&["opengl3d", "--help"])).is_none());
    }
}
