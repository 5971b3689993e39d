//! The crate's shape, checked from its source: no loops between files or between folders, every
//! folder importing only the layers below it (the order `src/lib.rs` states), and no source file
//! over 700 lines; and every file that names every AO method is in the docs' list of a new
//! method's files. Unit tests (`#[cfg(test)]` items) are left out: a test may build whatever it needs.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use syn::visit::Visit;

const CRATE: &str = "opengl3d";
const MAX_LINES: usize = 700;

/// The layers from the bottom up, as `src/lib.rs` lists them; a unit is `src/X` (file or folder) or,
/// under `tools`, one tool's folder or file. Units of one layer may use each other, without loops.
const LAYERS: &[&[&str]] = &[
    &["i18n", "res_embedded", "res", "io"],
    &["gl"],
    &["math"],
    &["shader_interface"],
    &["scene"],
    &["ao"],
    &["render"],
    &["platform"],
    &["tools"],
    &["cli"],
];

/// One source file: its module path under the crate, the paths it names, and what it defines.
struct SourceFile {
    module: Vec<String>,
    /// (named in a `pub use`, absolute module path under the crate, the name it binds here)
    uses: Vec<(bool, Vec<String>, String)>,
    /// Identifiers outside `use` items (a `pub use` counts as a use only when the file names it too).
    idents: BTreeSet<String>,
    /// Only `mod` and `use` items: a facade whose `pub use` lines re-export, not use.
    facade: bool,
}

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn module_of(rel: &Path) -> Vec<String> {
    let mut segs: Vec<String> = rel
        .with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(segs.last().map(String::as_str), Some("mod" | "lib")) {
        segs.pop();
    }
    segs
}

fn module_file(files: &BTreeMap<PathBuf, SourceFile>, segs: &[String]) -> Option<PathBuf> {
    let base = segs.iter().fold(PathBuf::new(), |p, s| p.join(s));
    let candidates = if segs.is_empty() {
        vec![PathBuf::from("lib.rs")]
    } else {
        vec![base.with_extension("rs"), base.join("mod.rs")]
    };
    candidates.into_iter().find(|c| files.contains_key(c))
}

fn is_test_only(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg")
            && a.parse_args::<syn::Meta>()
                .is_ok_and(|m| m.path().is_ident("test"))
    })
}

/// Collects every path a file names (use trees and paths in code), outside test-only items.
#[derive(Default)]
struct Names {
    /// (public, path as written, the name it binds; empty for paths in code and globs)
    uses: Vec<(bool, Vec<String>, String)>,
    idents: BTreeSet<String>,
}

/// A `use` tree as (path, the name it binds here; empty for a glob).
fn flatten_use(
    tree: &syn::UseTree,
    prefix: &mut Vec<String>,
    out: &mut Vec<(Vec<String>, String)>,
) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            flatten_use(&p.tree, prefix, out);
            prefix.pop();
        }
        syn::UseTree::Name(n) => {
            let mut full = prefix.clone();
            if n.ident != "self" {
                full.push(n.ident.to_string());
            }
            let bound = full.last().cloned().unwrap_or_default();
            out.push((full, bound));
        }
        syn::UseTree::Rename(r) => {
            let mut full = prefix.clone();
            full.push(r.ident.to_string());
            out.push((full, r.rename.to_string()));
        }
        syn::UseTree::Glob(_) => out.push((prefix.clone(), String::new())),
        syn::UseTree::Group(g) => g.items.iter().for_each(|t| flatten_use(t, prefix, out)),
    }
}

impl<'ast> Visit<'ast> for Names {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        let attrs = match item {
            syn::Item::Mod(m) => &m.attrs,
            syn::Item::Fn(f) => &f.attrs,
            syn::Item::Impl(i) => &i.attrs,
            syn::Item::Use(u) => &u.attrs,
            _ => &Vec::new(),
        };
        if !is_test_only(attrs) {
            syn::visit::visit_item(self, item);
        }
    }
    fn visit_item_use(&mut self, u: &'ast syn::ItemUse) {
        let public = matches!(u.vis, syn::Visibility::Public(_));
        let mut paths = Vec::new();
        flatten_use(&u.tree, &mut Vec::new(), &mut paths);
        self.uses
            .extend(paths.into_iter().map(|(p, bound)| (public, p, bound)));
    }
    fn visit_path(&mut self, path: &'ast syn::Path) {
        let segs: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
        // Every path of two or more names: those of other crates are dropped once the modules are
        // known (`absolute_path`), those through a child module or a name a `use` bound are kept.
        if segs.len() > 1 {
            self.uses.push((false, segs, String::new()));
        }
        syn::visit::visit_path(self, path);
    }
    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        // `mod x;` declares a child; it is not a use of the name the file re-exports.
        if let Some((_, items)) = &m.content {
            items.iter().for_each(|i| self.visit_item(i));
        }
    }
    fn visit_ident(&mut self, ident: &'ast proc_macro2::Ident) {
        self.idents.insert(ident.to_string());
    }
}

fn read_sources() -> BTreeMap<PathBuf, SourceFile> {
    let src = src_dir();
    let mut paths = Vec::new();
    rust_files(&src, &mut paths);
    let mut parsed = BTreeMap::new();
    for path in paths {
        let rel = path.strip_prefix(&src).unwrap().to_path_buf();
        if rel == Path::new("main.rs") {
            continue; // the binary: it reaches the library by its crate name only
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let file = syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", rel.display()));
        let mut names = Names::default();
        names.visit_file(&file);
        let facade = file.items.iter().all(|i| match i {
            syn::Item::Use(_) => true,
            syn::Item::Mod(m) => m.content.is_none() || is_test_only(&m.attrs),
            syn::Item::Macro(_) => true,
            _ => false,
        });
        parsed.insert(rel.clone(), (module_of(&rel), names, facade));
    }
    // Make every path absolute under the crate, now that all modules are known.
    let known: BTreeMap<PathBuf, SourceFile> = parsed
        .iter()
        .map(|(rel, (module, _, facade))| {
            let f = SourceFile {
                module: module.clone(),
                uses: Vec::new(),
                idents: BTreeSet::new(),
                facade: *facade,
            };
            (rel.clone(), f)
        })
        .collect();
    let mut files = BTreeMap::new();
    for (rel, (module, names, facade)) in parsed {
        let bindings: BTreeMap<String, Vec<String>> = names
            .uses
            .iter()
            .filter(|(_, _, bound)| !bound.is_empty())
            .map(|(_, segs, bound)| (bound.clone(), segs.clone()))
            .collect();
        let uses = names
            .uses
            .into_iter()
            .filter_map(|(public, segs, bound)| {
                let absolute = absolute_path(&known, &module, &bindings, segs, 0)?;
                Some((public, absolute, bound))
            })
            .collect();
        files.insert(
            rel,
            SourceFile {
                module,
                uses,
                idents: names.idents,
                facade,
            },
        );
    }
    files
}

/// A path as written in `module`, made absolute under the crate; `None` for another crate's.
fn absolute_path(
    known: &BTreeMap<PathBuf, SourceFile>,
    module: &[String],
    bindings: &BTreeMap<String, Vec<String>>,
    mut segs: Vec<String>,
    depth: u32,
) -> Option<Vec<String>> {
    segs.retain(|s| s != "*");
    let first = segs.first()?.clone();
    match first.as_str() {
        "crate" | CRATE => Some(segs.split_off(1)),
        "super" | "self" => {
            let mut m = module.to_vec();
            while matches!(segs.first().map(String::as_str), Some("super" | "self")) {
                if segs.remove(0) == "super" {
                    m.pop();
                }
            }
            m.extend(segs);
            Some(m)
        }
        _ => {
            let mut child = module.to_vec();
            child.push(first.clone());
            if module_file(known, &child).is_some() {
                let mut m = module.to_vec();
                m.extend(segs);
                return Some(m);
            }
            // A name this file's own `use` bound (`use crate::scene::ao_settings as settings`).
            let bound = bindings.get(&first).filter(|b| depth < 4 && b.len() > 1)?;
            let mut m = bound.clone();
            m.extend(segs.into_iter().skip(1));
            absolute_path(known, module, bindings, m, depth + 1)
        }
    }
}

/// The file a module path leads to, following re-exports to the file that defines the name.
fn resolve(files: &BTreeMap<PathBuf, SourceFile>, segs: &[String], depth: u32) -> Option<PathBuf> {
    for n in (0..=segs.len()).rev() {
        if let Some(target) = module_file(files, &segs[..n]) {
            let rest = &segs[n..];
            if let (Some(name), true) = (rest.first(), depth < 8) {
                let reexport = files[&target]
                    .uses
                    .iter()
                    .find(|(public, _, bound)| *public && bound == name);
                if let Some((_, s, _)) = reexport {
                    let mut further = s.clone();
                    further.extend(rest[1..].iter().cloned());
                    return resolve(files, &further, depth + 1);
                }
            }
            return Some(target);
        }
    }
    None
}

/// Which file uses which, `pub use` re-exports left out.
fn file_edges(files: &BTreeMap<PathBuf, SourceFile>) -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let mut edges: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
    for (rel, f) in files {
        let out = edges.entry(rel.clone()).or_default();
        for (public, segs, _) in &f.uses {
            let named_here = segs.last().is_some_and(|n| f.idents.contains(n));
            if *public && (f.facade || !named_here) {
                continue;
            }
            if let Some(target) = resolve(files, segs, 0) {
                if &target != rel {
                    out.insert(target);
                }
            }
        }
    }
    edges
}

/// Groups of more than one node that reach each other (Tarjan's strongly connected components).
fn loops<N: Ord + Clone>(edges: &BTreeMap<N, BTreeSet<N>>) -> Vec<Vec<N>> {
    struct State<N> {
        index: BTreeMap<N, usize>,
        low: BTreeMap<N, usize>,
        stack: Vec<N>,
        found: Vec<Vec<N>>,
    }
    fn visit<N: Ord + Clone>(v: &N, edges: &BTreeMap<N, BTreeSet<N>>, s: &mut State<N>) {
        let i = s.index.len();
        s.index.insert(v.clone(), i);
        s.low.insert(v.clone(), i);
        s.stack.push(v.clone());
        for w in edges.get(v).into_iter().flatten() {
            if !s.index.contains_key(w) {
                visit(w, edges, s);
                let low = s.low[v].min(s.low[w]);
                s.low.insert(v.clone(), low);
            } else if s.stack.contains(w) {
                let low = s.low[v].min(s.index[w]);
                s.low.insert(v.clone(), low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut group = Vec::new();
            while let Some(w) = s.stack.pop() {
                let done = &w == v;
                group.push(w);
                if done {
                    break;
                }
            }
            if group.len() > 1 {
                group.sort();
                s.found.push(group);
            }
        }
    }
    let mut s = State {
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !s.index.contains_key(v) {
            visit(v, edges, &mut s);
        }
    }
    s.found
}

/// `src/X`, or `tools/Y` one level deeper.
fn unit_of(module: &[String]) -> Option<String> {
    match module {
        [] => None,
        [tools, tool, ..] if tools == "tools" => Some(format!("tools/{tool}")),
        [first, ..] => Some(first.clone()),
    }
}

fn layer_of(unit: &str) -> usize {
    let top = unit.split('/').next().unwrap();
    LAYERS
        .iter()
        .position(|l| l.contains(&top))
        .unwrap_or_else(|| panic!("src/{unit} is in no layer of tests/layers.rs (and src/lib.rs)"))
}

fn unit_edges(files: &BTreeMap<PathBuf, SourceFile>) -> BTreeMap<String, BTreeSet<String>> {
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (rel, targets) in file_edges(files) {
        let Some(from) = unit_of(&files[&rel].module) else {
            continue;
        };
        for t in targets {
            if let Some(to) = unit_of(&files[&t].module).filter(|to| to != &from) {
                edges.entry(from.clone()).or_default().insert(to);
            }
        }
    }
    edges
}

#[test]
fn no_file_reaches_back_to_a_file_that_uses_it() {
    let files = read_sources();
    let found = loops(&file_edges(&files));
    let shown: Vec<String> = found
        .iter()
        .map(|g| {
            g.iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(" ⇄ ")
        })
        .collect();
    assert!(
        found.is_empty(),
        "import loops between files:\n{}",
        shown.join("\n")
    );
}

#[test]
fn no_folder_reaches_back_to_a_folder_that_uses_it() {
    let files = read_sources();
    let found = loops(&unit_edges(&files));
    let shown: Vec<String> = found.iter().map(|g| g.join(" ⇄ ")).collect();
    assert!(
        found.is_empty(),
        "import loops between folders:\n{}",
        shown.join("\n")
    );
}

#[test]
fn each_layer_uses_only_the_layers_below_it() {
    let files = read_sources();
    let mut upward = Vec::new();
    for (from, targets) in unit_edges(&files) {
        for to in targets {
            if layer_of(&to) > layer_of(&from) {
                upward.push(format!("src/{from} uses src/{to}"));
            }
        }
    }
    assert!(
        upward.is_empty(),
        "a lower layer uses a higher one:\n{}",
        upward.join("\n")
    );
}

#[test]
fn the_layer_order_is_the_one_lib_rs_states() {
    let lib = std::fs::read_to_string(src_dir().join("lib.rs")).unwrap();
    let doc: String = lib
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .collect::<Vec<_>>()
        .join(" ");
    let mut below: Option<(&str, usize)> = None;
    for layer in LAYERS {
        let named = layer
            .iter()
            .filter(|u| !matches!(**u, "i18n" | "res_embedded"));
        let at: Vec<(&str, usize)> = named
            .map(|u| {
                let at = doc.find(&format!("`{u}`"));
                (
                    *u,
                    at.unwrap_or_else(|| panic!("src/lib.rs's layer list does not name `{u}`")),
                )
            })
            .collect();
        if let Some((lower, lower_at)) = below {
            for (unit, unit_at) in &at {
                assert!(
                    *unit_at > lower_at,
                    "src/lib.rs names `{unit}` before `{lower}`, a layer below it"
                );
            }
        }
        below = at.into_iter().max_by_key(|(_, a)| *a);
    }
}

#[test]
fn the_reader_sees_uses_through_re_exports() {
    let files = read_sources();
    let units = unit_edges(&files);
    for (from, to) in [
        ("render", "ao"),
        ("ao", "scene"),
        ("tools/grade", "gl"),
        ("ao", "gl"),
    ] {
        assert!(
            units[from].contains(to),
            "src/{from} is known to use src/{to}"
        );
    }
    // `crate::ao::settings` is `scene/ao_settings.rs` re-exported by `ao/mod.rs`.
    let edges = file_edges(&files);
    let engine = &edges[Path::new("render/engine.rs")];
    assert!(
        engine.contains(Path::new("scene/ao_settings.rs")),
        "{engine:?}"
    );
}

#[test]
fn no_source_file_is_over_the_line_limit() {
    let mut paths = Vec::new();
    rust_files(&src_dir(), &mut paths);
    let long: Vec<String> = paths
        .iter()
        .filter_map(|p| {
            let n = std::fs::read_to_string(p).unwrap().lines().count();
            (n > MAX_LINES).then(|| format!("{} ({n} lines)", p.display()))
        })
        .collect();
    assert!(
        long.is_empty(),
        "over {MAX_LINES} lines: {}",
        long.join(", ")
    );
}

/// A file that names every AO method (`AoMethod::X` for each X: an exhaustive match, which the
/// compiler makes a new method fill) is in the list of a new method's files that
/// `docs/architecture.md` gives.
#[test]
fn every_file_that_names_every_ao_method_is_in_the_new_method_list() {
    use opengl3d::ao::method::NEW_METHOD_FILES;
    use opengl3d::ao::AoMethod;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&src_dir(), &mut files);
    let mut naming_all = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let names_every = AoMethod::ALL.iter().all(|m| {
            let path = format!("AoMethod::{m:?}");
            text.match_indices(&path).any(|(i, _)| {
                let next = text[i + path.len()..].chars().next();
                !next.is_some_and(|c| c.is_alphanumeric() || c == '_')
            })
        });
        if names_every {
            let rel = f.strip_prefix(root).unwrap();
            naming_all.push(rel.to_string_lossy().replace('\\', "/"));
        }
    }
    assert!(naming_all.iter().any(|f| f == "src/ao/method/mod.rs"));
    for f in &naming_all {
        assert!(
            NEW_METHOD_FILES.contains(&f.as_str()),
            "{f} names every AO method but the list of a new method's files leaves it out"
        );
    }
}

#[test]
fn the_loop_finder_finds_a_loop() {
    // The checks above pass on an empty answer; this one shows the finder can answer otherwise.
    let edges: BTreeMap<u8, BTreeSet<u8>> = [
        (1, [2].into()),
        (2, [3].into()),
        (3, [1].into()),
        (4, [1].into()),
    ]
    .into();
    assert_eq!(loops(&edges), vec![vec![1, 2, 3]]);
}
