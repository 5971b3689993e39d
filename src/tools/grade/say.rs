//! `say!`: a verdict's message from a `grade.verdict.*` key of `locales/*.yml`, written in English
//! (what `--json`'s `message` keeps) and, when another language is chosen, in that language too
//! (`message_localised`). Numbers are formatted before they are passed, so both languages show the
//! same digits.

/// `say!(KEY, name = value, …)`, KEY a literal `grade.verdict.*` key: the `crate::i18n::Text` of that
/// key with those values (each `Display`) in English and the chosen language.
///
/// `say!(l => KEY, …)` names the locale `l` for the values, for those that are words to translate
/// too.
macro_rules! say {
    ($locale:ident => $key:tt $(, $name:ident = $value:expr)* $(,)?) => {
        $crate::i18n::Text::new(|$locale: &str| {
            rust_i18n::t!($key, locale = $locale $(, $name = $value)*).into_owned()
        })
    };
    ($key:tt $(, $name:ident = $value:expr)* $(,)?) => {
        $crate::i18n::Text::new(|locale| {
            rust_i18n::t!($key, locale = locale $(, $name = $value)*).into_owned()
        })
    };
}

pub(crate) use say;
