//! Where each key of a TOML file is written (line and column), so a bad value can be pointed at.
//!
//! The text is read a second time into a tree of `toml::Spanned` nodes: serde keeps the byte range
//! of every value, which is all an error message needs.

use serde::de::{Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use std::collections::BTreeMap;
use toml::Spanned;

/// Byte ranges of the values of a TOML document, looked up by key ("camera.near", "object[2].scale[0]").
#[derive(Clone, Debug, Default)]
pub struct KeyPlaces {
    root: BTreeMap<String, Spanned<Node>>,
    line_starts: Vec<usize>,
}

#[derive(Clone, Debug)]
enum Node {
    Table(BTreeMap<String, Spanned<Node>>),
    Array(Vec<Spanned<Node>>),
    Leaf,
}

impl KeyPlaces {
    /// Reads the places of `text`; a text that is not TOML has none (its parse error says where).
    pub fn of(text: &str) -> KeyPlaces {
        let root = match toml::from_str::<Node>(text) {
            Ok(Node::Table(t)) => t,
            _ => BTreeMap::new(),
        };
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        KeyPlaces { root, line_starts }
    }

    /// 1-based line and column (in characters) of `key`'s value in `text`, if the file writes it.
    pub fn line_col(&self, key: &str, text: &str) -> Option<(usize, usize)> {
        match self.find(key)? {
            (start, true) => self.to_line_col(start, text),
            (_, false) => None,
        }
    }

    /// Like `line_col`, but a key the file leaves to its default gives its nearest written parent
    /// (the table header); the flag says whether the place is the key's own.
    pub fn nearest_line_col(&self, key: &str, text: &str) -> Option<(usize, usize, bool)> {
        let (start, exact) = self.find(key)?;
        let (line, col) = self.to_line_col(start, text)?;
        Some((line, col, exact))
    }

    fn to_line_col(&self, start: usize, text: &str) -> Option<(usize, usize)> {
        let line = self.line_starts.partition_point(|s| *s <= start);
        let line_start = self.line_starts[line - 1];
        let col = text.get(line_start..start)?.chars().count() + 1;
        Some((line, col))
    }

    /// Byte offset of the value of `key` (true), or of its nearest written parent (false).
    fn find(&self, key: &str) -> Option<(usize, bool)> {
        let mut table = &self.root;
        let mut found = None;
        let mut parts = split_key(key).into_iter().peekable();
        while let Some((name, indices)) = parts.next() {
            let Some(mut node) = table.get(&name) else {
                return found;
            };
            for i in indices {
                match node.get_ref() {
                    Node::Array(items) => match items.get(i) {
                        Some(item) => node = item,
                        None => return Some((node.span().start, false)),
                    },
                    _ => return Some((node.span().start, false)),
                }
            }
            found = Some((node.span().start, false));
            match node.get_ref() {
                Node::Table(t) => table = t,
                _ if parts.peek().is_some() => return found,
                _ => {}
            }
        }
        found.map(|(start, _)| (start, true))
    }
}

/// "object[2].scale[0]" -> [("object", [2]), ("scale", [0])].
fn split_key(key: &str) -> Vec<(String, Vec<usize>)> {
    key.split('.')
        .map(|part| {
            let mut pieces = part.split('[');
            let name = pieces.next().unwrap_or_default().to_string();
            let indices = pieces
                .filter_map(|p| p.trim_end_matches(']').parse().ok())
                .collect();
            (name, indices)
        })
        .collect()
}

impl<'de> Deserialize<'de> for Node {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Node, D::Error> {
        d.deserialize_any(NodeVisitor)
    }
}

struct NodeVisitor;

impl<'de> Visitor<'de> for NodeVisitor {
    type Value = Node;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("any TOML value")
    }
    fn visit_bool<E>(self, _: bool) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_i64<E>(self, _: i64) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_u64<E>(self, _: u64) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_f64<E>(self, _: f64) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_str<E>(self, _: &str) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Node, A::Error> {
        let mut t = BTreeMap::new();
        while let Some(k) = map.next_key::<String>()? {
            let v: Spanned<Node> = map.next_value()?;
            t.insert(k, v);
        }
        Ok(Node::Table(t))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Node, A::Error> {
        let mut items = Vec::new();
        while let Some(v) = seq.next_element::<Spanned<Node>>()? {
            items.push(v);
        }
        Ok(Node::Array(items))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_found_at_their_values() {
        let text = "[camera]\nnear = 1e-30\n\n[[object]]\nmesh = \"a.obj\"\n\n[[object]]\nmesh = \"b.obj\"\nscale = [1, nan, 1]\n";
        let p = KeyPlaces::of(text);
        assert_eq!(p.line_col("camera.near", text), Some((2, 8)));
        assert_eq!(p.line_col("object[1].mesh", text), Some((8, 8)));
        assert_eq!(p.line_col("object[1].scale[1]", text), Some((9, 13)));
        // A key the file does not write has no place of its own, only its table's header.
        assert_eq!(p.line_col("camera.far", text), None);
        assert_eq!(p.nearest_line_col("camera.far", text), Some((1, 1, false)));
        assert_eq!(p.line_col("bloom.strength", text), None);
    }
}
