//! Which keys of a scene's `[ao]` table the file writes, so that a method's recommended
//! configuration (`ao_defaults`) fills in only the others.

/// The `[ao]` keys a recommendation covers, with whether the scene file or a flag wrote each one
/// (a written key is never replaced).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WrittenKeys {
    /// `quality`; also set by `--samples`, an explicit count for the methods with presets.
    pub quality: bool,
    pub resolution: bool,
    pub normals: bool,
    pub guard_band: bool,
    pub layers: bool,
    pub thickness: bool,
    /// `rays`; also set by `--rays-per-pixel`.
    pub rays: bool,
}

impl WrittenKeys {
    /// The keys the `[ao]` table of a scene file's text writes (none when the text is not TOML:
    /// parsing it reports that).
    pub fn in_scene_text(text: &str) -> WrittenKeys {
        let Ok(table) = text.parse::<toml::Table>() else {
            return WrittenKeys::default();
        };
        let Some(ao) = table.get("ao").and_then(|v| v.as_table()) else {
            return WrittenKeys::default();
        };
        WrittenKeys {
            quality: ao.contains_key("quality"),
            resolution: ao.contains_key("resolution"),
            normals: ao.contains_key("normals"),
            guard_band: ao.contains_key("guard_band"),
            layers: ao.contains_key("layers"),
            thickness: ao.contains_key("thickness"),
            rays: ao.contains_key("rays"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_keys_are_read_from_the_ao_table_only() {
        let w = WrittenKeys::in_scene_text(
            "layers = 2\n[ao]\nnormals = \"depth\"\nguard_band = 0\n[output]\nquality = 1\n",
        );
        assert!(w.normals && w.guard_band);
        assert!(!w.layers && !w.quality && !w.thickness && !w.resolution);
        assert_eq!(
            WrittenKeys::in_scene_text("not toml ["),
            WrittenKeys::default()
        );
    }
}
