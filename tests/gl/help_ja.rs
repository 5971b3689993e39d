//! `--help` under `--lang ja` has no English left: every command's help (the program's, each
//! subcommand's, `help COMMAND`) is run through the binary and read for clap's own English words
//! ("Usage:", "[possible values: …]", "[default: …]"), options with no help at all, and runs of
//! three or more English words outside option names, values, placeholders, file names and code.
//! The commands come from the command tree itself, so a new command or option is covered at once.

use clap::CommandFactory;
use opengl3d::cli::Cli;
use std::collections::BTreeSet;
use std::process::Command;

fn help(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_opengl3d"))
        .args(args)
        .env_remove("LC_ALL")
        .env_remove("LC_MESSAGES")
        .env("LANG", "C")
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

/// Each visible command as its path of names ([] for the program itself).
fn command_paths(cmd: &clap::Command, path: Vec<String>, out: &mut Vec<Vec<String>>) {
    out.push(path.clone());
    for sub in cmd.get_subcommands().filter(|s| !s.is_hide_set()) {
        let mut p = path.clone();
        p.push(sub.get_name().to_string());
        command_paths(sub, p, out);
    }
}

/// What may stand in Japanese help as it is: command names, value names, possible and default
/// values (options are written with their dashes, which the check leaves alone).
fn code_words(cmd: &clap::Command, out: &mut BTreeSet<String>) {
    out.insert(cmd.get_name().to_string());
    for a in cmd.get_arguments() {
        for n in a.get_value_names().unwrap_or_default() {
            out.insert(n.to_string());
        }
        for v in a.get_possible_values() {
            out.extend(v.get_name_and_aliases().map(String::from));
        }
        for v in a.get_default_values() {
            out.insert(v.to_string_lossy().into_owned());
        }
    }
    for sub in cmd.get_subcommands() {
        code_words(sub, out);
    }
}

/// clap's own words, which the Japanese help writes in Japanese.
const CLAP_WORDS: &[&str] = &[
    "Usage:",
    "Options:",
    "Arguments:",
    "Commands:",
    "[possible values",
    "[default:",
    "[aliases:",
    "[alias:",
    "[env:",
    "Print help",
    "Print version",
];

/// The English in one help text: clap's words, and each run of three or more English words (a word
/// of ASCII letters that is no name from `code`, no acronym and no one-letter placeholder).
fn english_in(text: &str, code: &BTreeSet<String>) -> Vec<String> {
    let mut out: Vec<String> = CLAP_WORDS
        .iter()
        .filter(|w| text.contains(**w))
        .map(|w| format!("clap's own \"{w}\""))
        .collect();
    for line in text.lines() {
        let mut run: Vec<&str> = Vec::new();
        let mut flush = |run: &mut Vec<&str>| {
            if run.len() >= 3 {
                out.push(format!("English \"{}\" in: {}", run.join(" "), line.trim()));
            }
            run.clear();
        };
        for token in line.split_whitespace() {
            // A leading dot stays: `.png` is a file name, not the word "png".
            let word = token
                .trim_start_matches(|c: char| "([<\"'`".contains(c))
                .trim_end_matches(|c: char| ",.;:)]>\"'`!?".contains(c));
            if word.is_empty() {
                continue;
            }
            let is_english = word.is_ascii()
                && word.chars().all(|c| c.is_ascii_alphabetic() || c == '\'')
                && !code.contains(word)
                && !(word.len() == 1 && word.chars().all(|c| c.is_ascii_uppercase()))
                && !(word.len() > 1 && word.chars().all(|c| !c.is_ascii_lowercase()));
            if is_english {
                run.push(word);
            } else {
                flush(&mut run);
            }
        }
        flush(&mut run);
    }
    out
}

/// The options in `cmd`'s help `text` shown with nothing after them.
fn options_without_help(cmd: &clap::Command, text: &str) -> Vec<String> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for a in cmd.get_arguments().filter(|a| !a.is_hide_set()) {
        let Some(long) = a.get_long() else { continue };
        let flag = format!("--{long}");
        let Some(i) = lines.iter().position(|l| {
            let t = l.trim_start();
            t.split(", ")
                .any(|part| part.split_whitespace().next() == Some(flag.as_str()))
        }) else {
            continue;
        };
        // Same line: the text after the option and its value, two spaces or more on.
        let same_line = lines[i]
            .trim()
            .split("  ")
            .skip(1)
            .any(|s| !s.trim().is_empty());
        // Next line: indented deeper than any option (which stand at 2 or 6 spaces).
        let next_line = lines.get(i + 1).is_some_and(|n| {
            let t = n.trim_start();
            !t.is_empty() && n.len() - t.len() > 6
        });
        if !same_line && !next_line {
            out.push(format!("{flag} has no help"));
        }
    }
    out
}

#[test]
fn every_commands_help_in_japanese_has_no_english() {
    let tree = Cli::command();
    let mut code = BTreeSet::new();
    code_words(&tree, &mut code);
    let mut paths = Vec::new();
    command_paths(&tree, Vec::new(), &mut paths);
    assert!(paths.len() >= 9, "{paths:?}");
    let mut problems = Vec::new();
    let mut check = |args: Vec<String>, cmd: &clap::Command| {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let text = help(&args);
        for p in english_in(&text, &code)
            .into_iter()
            .chain(options_without_help(cmd, &text))
        {
            problems.push(format!("opengl3d {}: {p}", args.join(" ")));
        }
    };
    for path in &paths {
        let mut cmd = &tree;
        for name in path {
            cmd = cmd.find_subcommand(name).unwrap();
        }
        let mut args: Vec<String> = vec!["--lang".into(), "ja".into()];
        args.extend(path.iter().cloned());
        args.push("--help".into());
        check(args, cmd);
        // `help COMMAND` writes the same help.
        if path.len() == 1 && path[0] != "help" {
            check(
                vec!["--lang".into(), "ja".into(), "help".into(), path[0].clone()],
                cmd,
            );
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_english_check_finds_the_english_help_and_spares_names() {
    let tree = Cli::command();
    let mut code = BTreeSet::new();
    code_words(&tree, &mut code);
    // The English help is all English: the check must see it.
    let english = help(&["--lang", "en", "render", "--help"]);
    let found = english_in(&english, &code);
    assert!(found.iter().any(|p| p.contains("Usage:")), "{found:?}");
    assert!(found.iter().any(|p| p.contains("Output file")), "{found:?}");
    // Names, values, acronyms and file names are no English prose.
    let ja =
        "      --method <METHOD>  AOの手法 [指定できる値: sao-lesson, sao, crytek, hemisphere]\n\
              --composite tintedのとき、blend tinted ambient-onlyとPNG PFM TOML out/frame.png";
    assert_eq!(english_in(ja, &code), Vec::<String>::new());
    assert_eq!(
        english_in("既定値 the scene file's value", &code).len(),
        1,
        "a run of English words"
    );
    assert!(english_in("--scene FILE --out DIR", &code).is_empty());
    // An option printed with nothing after it.
    let render = tree.find_subcommand("render").unwrap();
    let text = "オプション:\n      --near <NEAR>\n          \n      --far <FAR>\n          --viewとファー平面\n";
    assert_eq!(options_without_help(render, text), ["--near has no help"]);
    let text = "      --near <NEAR>  ニア平面\n      --far <FAR>\n";
    assert_eq!(options_without_help(render, text), ["--far has no help"]);
}
