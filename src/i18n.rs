//! The language of the messages people read: English or Japanese, chosen by `--lang` or else by the
//! locale variables (`LC_ALL`, then `LC_MESSAGES`, then `LANG`, as POSIX orders them). The texts are
//! in `locales/*.yml` (rust-i18n, compiled in). Machine-read output (`--json` keys and its
//! `message` fields) stays English whatever the language, so scripts do not depend on it.

/// A language the messages are written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    En,
    Ja,
}

impl Lang {
    pub const ALL: [Lang; 2] = [Lang::En, Lang::Ja];

    /// The name on the command line, which is also the locale file's name.
    pub fn code(self) -> &'static str {
        match self {
            Lang::En => "en",
            Lang::Ja => "ja",
        }
    }
}

/// The language to use: the flag if given, else the first of `LC_ALL`, `LC_MESSAGES`, `LANG` that
/// is set and not empty (Japanese when it starts with `ja`, English for anything else, `C.UTF-8`
/// included), else English. The variables' values are arguments so this can be tested without
/// touching the process environment.
pub fn choose(
    flag: Option<Lang>,
    lc_all: Option<&str>,
    lc_messages: Option<&str>,
    lang: Option<&str>,
) -> Lang {
    if let Some(l) = flag {
        return l;
    }
    match [lc_all, lc_messages, lang]
        .into_iter()
        .flatten()
        .find(|v| !v.is_empty())
    {
        Some(v) if v.starts_with("ja") => Lang::Ja,
        _ => Lang::En,
    }
}

/// The language `flag` and this process's locale variables choose.
pub fn from_env(flag: Option<Lang>) -> Lang {
    let var = |name: &str| std::env::var_os(name).map(|v| v.to_string_lossy().into_owned());
    let (all, messages, lang) = (var("LC_ALL"), var("LC_MESSAGES"), var("LANG"));
    choose(flag, all.as_deref(), messages.as_deref(), lang.as_deref())
}

/// Makes `lang` the language of every message from now on (the process has one language).
pub fn set(lang: Lang) {
    rust_i18n::set_locale(lang.code());
}

/// The language messages are shown in (English until `set` is called).
pub fn current() -> Lang {
    if rust_i18n::locale().starts_with("ja") {
        Lang::Ja
    } else {
        Lang::En
    }
}

/// What an error message starts with in the current language ("error: ").
pub fn error_prefix() -> String {
    rust_i18n::t!("usage.error").into_owned()
}

/// One message in English (what `--json` keeps) and, when the chosen language is another, in that
/// language too.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Text {
    pub en: String,
    pub localised: Option<String>,
}

impl Text {
    /// The message `write` gives for English and for the current language (`write` takes the
    /// locale's code).
    pub fn new(write: impl Fn(&str) -> String) -> Text {
        let lang = current();
        Text {
            en: write(Lang::En.code()),
            localised: (lang != Lang::En).then(|| write(lang.code())),
        }
    }

    /// What a person reads: the localised message, else the English one.
    pub fn shown(&self) -> &str {
        self.localised.as_deref().unwrap_or(&self.en)
    }
}

/// Why an I/O operation failed, in the language `locale`: the common kinds in words of that
/// language, any other as a generic phrase with the system's own message (which is English).
pub fn io_cause(e: &std::io::Error, locale: &str) -> String {
    use std::io::ErrorKind as K;
    let key = match e.kind() {
        K::NotFound => "io.not_found",
        K::PermissionDenied => "io.permission_denied",
        K::AlreadyExists => "io.already_exists",
        K::NotADirectory => "io.not_a_directory",
        K::IsADirectory => "io.is_a_directory",
        K::InvalidData => "io.invalid_data",
        K::StorageFull => "io.storage_full",
        K::ReadOnlyFilesystem => "io.read_only",
        _ => return rust_i18n::t!("io.other", locale = locale, error = e).into_owned(),
    };
    rust_i18n::t!(key, locale = locale).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flag_wins_over_every_variable() {
        let ja = Some("ja_JP.UTF-8");
        assert_eq!(choose(Some(Lang::En), ja, ja, ja), Lang::En);
        assert_eq!(
            choose(Some(Lang::Ja), None, None, Some("C.UTF-8")),
            Lang::Ja
        );
    }

    #[test]
    fn lc_all_then_lc_messages_then_lang() {
        assert_eq!(choose(None, None, None, Some("ja_JP.UTF-8")), Lang::Ja);
        assert_eq!(
            choose(None, None, Some("ja_JP"), Some("en_US.UTF-8")),
            Lang::Ja
        );
        assert_eq!(
            choose(None, Some("C"), Some("ja_JP"), Some("ja_JP")),
            Lang::En
        );
        assert_eq!(choose(None, Some("ja"), None, Some("en_GB")), Lang::Ja);
        // An empty variable counts as unset.
        assert_eq!(
            choose(None, Some(""), Some(""), Some("ja_JP.UTF-8")),
            Lang::Ja
        );
    }

    #[test]
    fn anything_but_ja_is_english() {
        assert_eq!(choose(None, None, None, None), Lang::En);
        assert_eq!(choose(None, None, None, Some("C.UTF-8")), Lang::En);
        assert_eq!(choose(None, None, None, Some("POSIX")), Lang::En);
        assert_eq!(choose(None, None, None, Some("fr_FR.UTF-8")), Lang::En);
    }

    #[test]
    fn both_locale_files_hold_the_same_keys() {
        let keys = |text: &str| -> Vec<String> {
            let mut k: Vec<String> = text
                .lines()
                .filter(|l| !l.starts_with(' ') && !l.starts_with('#') && l.contains(':'))
                .map(|l| l.split(':').next().unwrap_or("").to_string())
                .collect();
            k.sort();
            k
        };
        let en = keys(include_str!("../locales/en.yml"));
        let ja = keys(include_str!("../locales/ja.yml"));
        assert!(en.len() > 10, "{en:?}");
        assert_eq!(en, ja);
    }

    #[test]
    fn a_key_reads_in_each_language() {
        let en = rust_i18n::t!("grade.not_submitted", locale = "en", reason = "x");
        let ja = rust_i18n::t!("grade.not_submitted", locale = "ja", reason = "x");
        assert_eq!(en, "not submitted: x");
        assert_eq!(ja, "未提出: x");
    }
}
