//! `--help` in Japanese: clap writes its help from the English doc comments, so with Japanese
//! chosen the command tree is rewritten before parsing: the headings ("Usage:", "Commands:",
//! "Arguments:", "Options:"), the built-in help and version lines, each command's summary and the
//! options that `locales/ja.yml` translates (`help.about.PATH`, `help.arg.PATH.ID`, PATH the
//! command's path such as `lesson` or `grade`); an option without a translation keeps its English.

use clap::Command;
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
        let mut a = a.help_heading(heading);
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

/// The program's command tree with its help in Japanese.
pub fn japanese(mut cmd: Command) -> Command {
    cmd.build();
    localise(cmd, "", Headings::new())
}
