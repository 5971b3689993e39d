//! `--help` in Japanese: clap writes its help from the English doc comments, so with Japanese
//! chosen the command tree is rewritten before parsing: the headings ("Usage:", "Commands:",
//! "Arguments:", "Options:"), the built-in help and version lines, each command's summary and the
//! options that `locales/ja.yml` translates (`help.about.PATH`, `help.arg.PATH.ID`, PATH the
//! command's path such as `lesson` or `grade`); an option without a translation keeps its English.
//! clap's own notes after an option ("[possible values: …]", "[default: …]", "[aliases: …]") are
//! hidden and written again in Japanese.

use clap::{Arg, Command};
use rust_i18n::t;

/// The translation of `key`, if the locale files have one (English holds these keys empty).
fn translated(key: &str) -> Option<String> {
    let text = t!(key).into_owned();
    (text != key && !text.is_empty()).then_some(text)
}

/// The help's headings in the current language. clap keeps headings as `&'static str`; they are
/// made once per process, so leaking them costs a few bytes.
#[derive(Clone, Copy)]
struct Headings {
    commands: &'static str,
    arguments: &'static str,
    options: &'static str,
}

impl Headings {
    fn new() -> Headings {
        let leak = |key: &str| -> &'static str { Box::leak(t!(key).into_owned().into_boxed_str()) };
        Headings {
            commands: leak("help.commands"),
            arguments: leak("help.arguments"),
            options: leak("help.options"),
        }
    }
}

/// `cmd` (built, so that the help and version flags and the `help` command exist) with its help
/// in the current language; `path` is its key in `help.about.*` ("" for the program itself).
fn localise(mut cmd: Command, path: &str, headings: Headings) -> Command {
    let key = if path.is_empty() { "opengl3d" } else { path };
    cmd = cmd
        .help_template(t!("help.template").into_owned())
        .subcommand_help_heading(headings.commands);
    if let Some(about) = translated(&format!("help.about.{key}")) {
        cmd = cmd.about(about.clone()).long_about(about);
    }
    let args_key = key.to_string();
    cmd = cmd.mut_args(|a| {
        let heading = if a.is_positional() {
            headings.arguments
        } else {
            headings.options
        };
        let id = a.get_id().as_str().to_string();
        let own = match id.as_str() {
            "help" => Some(t!("help.print_help").into_owned()),
            "version" => Some(t!("help.print_version").into_owned()),
            _ => translated(&format!("help.arg.{args_key}.{id}"))
                .or_else(|| translated(&format!("help.arg.{id}"))),
        };
        let notes = notes(&a);
        let own = match (own, notes.is_empty()) {
            (Some(text), false) => Some(format!("{text} {notes}")),
            (None, false) => Some(notes),
            (own, true) => own,
        };
        let mut a = hide_clap_notes(a.help_heading(heading));
        // Under a heading of its own clap lists positionals by name: keep their order.
        if let Some(index) = a.get_index() {
            a = a.display_order(index);
        }
        match own {
            Some(text) => a.help(text.clone()).long_help(text),
            None => a,
        }
    });
    let names: Vec<String> = cmd
        .get_subcommands()
        .map(|s| s.get_name().to_string())
        .collect();
    for name in names {
        let sub = if name == "help" {
            "help".to_string()
        } else if path.is_empty() {
            name.clone()
        } else {
            format!("{path}.{name}")
        };
        cmd = cmd.mut_subcommand(&name, |s| localise(s, &sub, headings));
    }
    cmd
}

/// clap's notes after an option's help, in the current language: its possible values, default and
/// visible aliases (only for options that take a value, as clap shows them).
fn notes(a: &Arg) -> String {
    let mut out = Vec::new();
    let takes_value = a.get_action().takes_values();
    if takes_value && !a.is_hide_possible_values_set() {
        let values: Vec<String> = a
            .get_possible_values()
            .iter()
            .filter(|v| !v.is_hide_set())
            .map(|v| v.get_name().to_string())
            .collect();
        if !values.is_empty() {
            out.push(t!("help.possible_values", values = values.join(", ")).into_owned());
        }
    }
    if takes_value && !a.is_hide_default_value_set() && !a.get_default_values().is_empty() {
        let value: Vec<String> = a
            .get_default_values()
            .iter()
            .map(|v| v.to_string_lossy().into_owned())
            .collect();
        out.push(t!("help.default_value", value = value.join(", ")).into_owned());
    }
    let aliases: Vec<String> = a
        .get_visible_aliases()
        .unwrap_or_default()
        .iter()
        .map(|s| format!("--{s}"))
        .collect();
    if !aliases.is_empty() {
        out.push(t!("help.aliases", aliases = aliases.join(", ")).into_owned());
    }
    out.join(" ")
}

/// `a` without clap's own (English) notes, which `notes` writes instead; its aliases keep working.
fn hide_clap_notes(a: Arg) -> Arg {
    let aliases: Vec<String> = a
        .get_visible_aliases()
        .unwrap_or_default()
        .iter()
        .map(|s| s.to_string())
        .collect();
    let mut a = a.hide_possible_values(true).hide_default_value(true);
    if !aliases.is_empty() {
        a = a.visible_alias(None::<&str>);
        // clap keeps names as `&'static str` (see `Headings`).
        for alias in aliases {
            a = a.alias(&*Box::leak(alias.into_boxed_str()));
        }
    }
    a
}

/// The program's command tree with its help in Japanese.
pub fn japanese(mut cmd: Command) -> Command {
    cmd.build();
    localise(cmd, "", Headings::new())
}
