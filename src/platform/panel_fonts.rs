//! The fonts of the window's panel and error overlay, and so the language they can be shown in.
//! egui's bundled fonts have no Japanese glyphs, so Japanese labels need a CJK font from the
//! system: the first of the known Debian/Ubuntu (and Fedora) font files found is added as a
//! fallback after the bundled fonts. Without one the panel stays in English (tofu boxes would be
//! unreadable) and one line says which package to install.

use crate::i18n::Lang;
use rust_i18n::t;
use std::path::{Path, PathBuf};

/// The package the README and the warning name.
pub const CJK_PACKAGE: &str = "fonts-noto-cjk";

/// CJK font files, in the order tried: Noto Sans CJK (`fonts-noto-cjk`), IPA and IPAex Gothic
/// (`fonts-ipafont-gothic`, `fonts-ipaexfont-gothic`), Takao Gothic (`fonts-takao-gothic`), then
/// the Debian alternatives link any Japanese Gothic font package sets.
pub const CJK_FONTS: [&str; 7] = [
    "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/noto-cjk/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/google-noto-cjk/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/opentype/ipafont-gothic/ipag.ttf",
    "/usr/share/fonts/opentype/ipaexfont-gothic/ipaexg.ttf",
    "/usr/share/fonts/truetype/takao-gothic/TakaoGothic.ttf",
    "/usr/share/fonts/truetype/fonts-japanese-gothic.ttf",
];

/// Whether `bytes` start like a font file egui can read: TrueType, OpenType (CFF) or a collection.
fn looks_like_a_font(bytes: &[u8]) -> bool {
    matches!(
        bytes.get(..4),
        Some([0, 1, 0, 0]) | Some(b"OTTO") | Some(b"ttcf") | Some(b"true")
    )
}

/// The first of `candidates` that can be read and looks like a font, with its bytes; files that
/// are missing, unreadable or not fonts are passed over.
pub fn find_font(candidates: &[PathBuf]) -> Option<(PathBuf, Vec<u8>)> {
    candidates.iter().find_map(|p| {
        let bytes = std::fs::read(p).ok()?;
        looks_like_a_font(&bytes).then(|| (p.clone(), bytes))
    })
}

/// The language the panel is shown in: the chosen one when its script can be drawn.
pub fn panel_lang(chosen: Lang, cjk_font: bool) -> Lang {
    match chosen {
        Lang::Ja if !cjk_font => Lang::En,
        l => l,
    }
}

/// What `install_fonts` did.
pub struct FontSetup {
    /// The language of the panel's labels.
    pub lang: Lang,
    /// Lines for the console: an unreadable `OPENGL3D_FONT`, a missing CJK font.
    pub warnings: Vec<String>,
}

/// Installs the panel's fonts into `ctx`: egui's bundled fonts, `OPENGL3D_FONT` (a TrueType file)
/// first when set, and the first CJK font of `cjk_candidates` as a fallback, so Japanese labels,
/// file names and messages show. `chosen` is the language asked for.
pub fn install_fonts(ctx: &egui::Context, chosen: Lang, cjk_candidates: &[PathBuf]) -> FontSetup {
    let mut fonts = egui::FontDefinitions::default();
    let mut warnings = Vec::new();
    let add = |fonts: &mut egui::FontDefinitions, name: &str, bytes: Vec<u8>, first: bool| {
        fonts.font_data.insert(
            name.to_string(),
            std::sync::Arc::new(egui::FontData::from_owned(bytes)),
        );
        for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
            let list = fonts.families.entry(family).or_default();
            if first {
                list.insert(0, name.to_string());
            } else {
                list.push(name.to_string());
            }
        }
    };
    if let Some(path) = std::env::var_os("OPENGL3D_FONT") {
        let path = PathBuf::from(path);
        match std::fs::read(&path) {
            Ok(bytes) if looks_like_a_font(&bytes) => {
                // Only the proportional family: a user font is rarely monospaced.
                add(&mut fonts, "user", bytes, true);
                if let Some(mono) = fonts.families.get_mut(&egui::FontFamily::Monospace) {
                    mono.retain(|n| n != "user");
                }
            }
            Ok(_) => warnings.push(format!(
                "OPENGL3D_FONT={}: not a TrueType or OpenType font; using the bundled font",
                path.display()
            )),
            Err(e) => warnings.push(format!(
                "OPENGL3D_FONT={}: {e}; using the bundled font",
                path.display()
            )),
        }
    }
    let cjk = find_font(cjk_candidates);
    let found = cjk.is_some();
    if let Some((_, bytes)) = cjk {
        add(&mut fonts, "cjk", bytes, false);
    }
    ctx.set_fonts(fonts);
    let lang = panel_lang(chosen, found);
    if lang != chosen {
        warnings.push(no_cjk_font_warning(chosen));
    }
    FontSetup { lang, warnings }
}

/// The one line said when the panel falls back to English: which package to install.
fn no_cjk_font_warning(chosen: Lang) -> String {
    t!(
        "panel.no_cjk_font",
        locale = chosen.code(),
        package = CJK_PACKAGE
    )
    .into_owned()
}

/// The known CJK font files as paths.
pub fn known_cjk_fonts() -> Vec<PathBuf> {
    CJK_FONTS.iter().map(PathBuf::from).collect()
}

/// Whether any of the known CJK font files exists (the tests' way to know what to expect).
pub fn cjk_font_installed() -> bool {
    CJK_FONTS.iter().any(|p| Path::new(p).is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("opengl3d-fonts-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn no_candidates_mean_english_and_one_line_naming_the_package() {
        assert!(find_font(&[]).is_none());
        let ctx = egui::Context::default();
        let setup = install_fonts(&ctx, Lang::Ja, &[]);
        assert_eq!(setup.lang, Lang::En);
        assert_eq!(setup.warnings.len(), 1, "{:?}", setup.warnings);
        assert!(
            setup.warnings[0].contains(CJK_PACKAGE),
            "{:?}",
            setup.warnings
        );
        // English asked for needs no CJK font and says nothing.
        let setup = install_fonts(&ctx, Lang::En, &[]);
        assert_eq!(setup.lang, Lang::En);
        assert!(setup.warnings.is_empty(), "{:?}", setup.warnings);
    }

    #[test]
    fn missing_unreadable_and_non_font_files_are_passed_over() {
        let d = scratch("lookup");
        let text = d.join("notes.ttf");
        std::fs::write(&text, "not a font").unwrap();
        let font = d.join("fake.ttc");
        std::fs::write(&font, b"ttcf\0\x01\0\0rest").unwrap();
        let candidates = [d.join("missing.ttc"), d.clone(), text, font.clone()];
        let (path, bytes) = find_font(&candidates).unwrap();
        assert_eq!(path, font);
        assert!(bytes.starts_with(b"ttcf"));
        assert!(find_font(&candidates[..3]).is_none());
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn japanese_is_kept_only_with_a_cjk_font() {
        assert_eq!(panel_lang(Lang::Ja, true), Lang::Ja);
        assert_eq!(panel_lang(Lang::Ja, false), Lang::En);
        assert_eq!(panel_lang(Lang::En, true), Lang::En);
    }

    #[test]
    fn the_known_paths_include_the_debian_noto_file() {
        assert!(known_cjk_fonts().contains(&PathBuf::from(
            "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc"
        )));
    }
}
