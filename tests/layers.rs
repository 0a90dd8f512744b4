//! The import layers of `src/`, read from the source with `syn`: every `use` tree (grouped ones
//! too) and every path in code and in macro bodies (`crate::…`, `$crate::…`, `super::…`) of
//! every file is resolved to the file it names, and
//!
//! - no library file (anything but `main.rs`, `cli.rs` and `commands/`) imports `cli` or
//!   `commands`, but the crate root, which declares them and hands the binary its one entry
//!   point (`run_command_line`: `cli::parse`, then `commands::run`);
//! - `millimpact::…` inside the crate (the commands name the library as its users do, through
//!   `extern crate self as millimpact`) is read as `crate::…`;
//! - `model` imports none of `solve`, `codes`, `analysis`, `output`;
//! - `solve` imports none of `codes`, `analysis`, `output`;
//! - `codes` imports none of `analysis`, `output`;
//! - `output` imports nothing else of the crate (not even `model`: a summary hands it formatted
//!   sections and serialisable records, so it needs no domain type);
//! - no two files import each other through a chain (no file-level cycle). A parent's `mod.rs`
//!   naming its own children (`pub use child::X`, `child::f()`) is how a module exposes them
//!   and is not counted against the children's `use super::…`; every other edge is.
//!
//! Test modules inside a file (`#[cfg(test)] mod tests`) are left out: they may reach across.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

mod common;

/// Every `.rs` file under `dir`.
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

/// The module path of a file: `src/analysis/run.rs` → `["analysis", "run"]`, `src/codes/mod.rs`
/// → `["codes"]`, `src/lib.rs` → `[]`.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let relative = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// Whether an item is compiled for tests only (`#[cfg(test)]`).
fn test_only(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg")
            && a.parse_args::<syn::Meta>()
                .is_ok_and(|m| m.path().is_ident("test"))
    })
}

/// Every path a file names outside its test-only items, as the words of the path and whether it
/// came from a `use` (where a bare first word is a child module or an external crate) or from
/// code (where it is a path of two words or more).
struct PathCollector {
    /// `use` trees, expanded: `use crate::{a::b, c}` gives `crate::a::b` and `crate::c`.
    used: Vec<Vec<String>>,
    /// Paths in code and in macro bodies (`crate::x::f()`, `$crate::x::Y`).
    inline: Vec<Vec<String>>,
}

impl PathCollector {
    fn use_tree(&mut self, prefix: &mut Vec<String>, tree: &syn::UseTree) {
        match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                self.use_tree(prefix, &p.tree);
                prefix.pop();
            }
            syn::UseTree::Name(n) => {
                let mut path = prefix.clone();
                if n.ident != "self" {
                    path.push(n.ident.to_string());
                }
                self.used.push(path);
            }
            syn::UseTree::Rename(r) => {
                let mut path = prefix.clone();
                if r.ident != "self" {
                    path.push(r.ident.to_string());
                }
                self.used.push(path);
            }
            syn::UseTree::Glob(_) => self.used.push(prefix.clone()),
            syn::UseTree::Group(g) => {
                for item in &g.items {
                    self.use_tree(prefix, item);
                }
            }
        }
    }

    /// Paths inside a macro's tokens (`format!("{}", crate::x::f())`, a `macro_rules!` body's
    /// `$crate::x::Y`), which syn leaves unparsed: every `crate`, `super` or `self` word followed
    /// by `::` and the words after it.
    fn tokens(&mut self, tokens: proc_macro2::TokenStream) {
        use proc_macro2::TokenTree;
        let trees: Vec<TokenTree> = tokens.into_iter().collect();
        let mut i = 0;
        while i < trees.len() {
            match &trees[i] {
                TokenTree::Group(g) => self.tokens(g.stream()),
                TokenTree::Ident(word)
                    if matches!(word.to_string().as_str(), "crate" | "super" | "self") =>
                {
                    let mut path = vec![word.to_string()];
                    let mut j = i + 1;
                    loop {
                        let colons = matches!((trees.get(j), trees.get(j + 1)),
                            (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b))) if a.as_char() == ':' && b.as_char() == ':');
                        match (colons, trees.get(j + 2)) {
                            (true, Some(TokenTree::Ident(next))) => {
                                path.push(next.to_string());
                                j += 3;
                            }
                            _ => break,
                        }
                    }
                    if path.len() > 1 {
                        self.inline.push(path);
                    }
                    i = j.max(i + 1);
                    continue;
                }
                _ => {}
            }
            i += 1;
        }
    }
}

impl<'ast> syn::visit::Visit<'ast> for PathCollector {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        let attrs: &[syn::Attribute] = match item {
            syn::Item::Mod(m) => &m.attrs,
            syn::Item::Fn(f) => &f.attrs,
            syn::Item::Use(u) => &u.attrs,
            syn::Item::Impl(i) => &i.attrs,
            syn::Item::Struct(s) => &s.attrs,
            syn::Item::Const(c) => &c.attrs,
            syn::Item::Macro(m) => &m.attrs,
            _ => &[],
        };
        if !test_only(attrs) {
            syn::visit::visit_item(self, item);
        }
    }

    fn visit_item_use(&mut self, item: &'ast syn::ItemUse) {
        self.use_tree(&mut Vec::new(), &item.tree);
    }

    fn visit_path(&mut self, path: &'ast syn::Path) {
        if path.segments.len() > 1 {
            self.inline
                .push(path.segments.iter().map(|s| s.ident.to_string()).collect());
        }
        syn::visit::visit_path(self, path);
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        self.tokens(mac.tokens.clone());
        syn::visit::visit_macro(self, mac);
    }
}

/// The modules a file declares (`mod x;`, not test-only ones).
fn declared_children(file: &syn::File) -> BTreeSet<String> {
    file.items
        .iter()
        .filter_map(|item| match item {
            syn::Item::Mod(m) if m.content.is_none() && !test_only(&m.attrs) => {
                Some(m.ident.to_string())
            }
            _ => None,
        })
        .collect()
}

/// The module paths the file `module` (with its declared `children`) names in `source`,
/// resolved from the crate's root, and whether each is a parent naming its own child:
/// `crate::a::b…`, `$crate::a…`, `super::a…` (`super::super::` climbs one more), `self::a…`,
/// and a declared child's `child::…`, in `use` trees (grouped ones too), in code and in macro
/// bodies.
fn referenced_paths(
    module: &[String],
    source: &str,
    children: &BTreeSet<String>,
) -> Vec<(Vec<String>, bool)> {
    let file = syn::parse_file(source).expect("a file of the crate parses");
    let mut collector = PathCollector {
        used: Vec::new(),
        inline: Vec::new(),
    };
    syn::visit::Visit::visit_file(&mut collector, &file);
    let mut out = Vec::new();
    for path in collector.used.iter().chain(&collector.inline) {
        let Some(first) = path.first() else { continue };
        match first.as_str() {
            "crate" | "millimpact" => out.push((path[1..].to_vec(), false)),
            "super" => {
                let up = path.iter().take_while(|w| *w == "super").count();
                let mut target = module[..module.len().saturating_sub(up)].to_vec();
                target.extend(path[up..].iter().cloned());
                out.push((target, false));
            }
            "self" => {
                let mut target = module.to_vec();
                target.extend(path[1..].iter().cloned());
                let to_child = path.get(1).is_some_and(|c| children.contains(c));
                out.push((target, to_child));
            }
            child if children.contains(child) => {
                let mut target = module.to_vec();
                target.extend(path.iter().cloned());
                out.push((target, true));
            }
            _ => {}
        }
    }
    out
}

/// The longest prefix of `path` that is a file's module.
fn resolve(path: &[String], files: &BTreeMap<Vec<String>, PathBuf>) -> Option<Vec<String>> {
    (0..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|p| files.contains_key(p))
}

struct Graph {
    /// Module of each file.
    files: BTreeMap<Vec<String>, PathBuf>,
    /// Imports, file module → file modules, and whether the edge is a parent naming its child.
    edges: BTreeMap<Vec<String>, BTreeSet<(Vec<String>, bool)>>,
}

fn graph() -> Graph {
    let src = common::root().join("src");
    let mut paths = Vec::new();
    rust_files(&src, &mut paths);
    let mut files = BTreeMap::new();
    for path in paths.iter().filter(|p| !p.ends_with("main.rs")) {
        files.insert(module_of(&src, path), path.clone());
    }
    let mut edges = BTreeMap::new();
    for (module, path) in &files {
        let text = std::fs::read_to_string(path).unwrap();
        let children = declared_children(&syn::parse_file(&text).unwrap());
        let mut targets = BTreeSet::new();
        for (path, parent_to_child) in referenced_paths(module, &text, &children) {
            if let Some(target) = resolve(&path, &files)
                && &target != module
            {
                targets.insert((target, parent_to_child));
            }
        }
        edges.insert(module.clone(), targets);
    }
    Graph { files, edges }
}

fn top(module: &[String]) -> &str {
    module.first().map(String::as_str).unwrap_or("")
}

#[test]
fn imports_point_down_the_layers() {
    let g = graph();
    assert!(g.files.len() > 30, "read {} files", g.files.len());
    let forbidden: [(&str, &[&str]); 5] = [
        (
            "model",
            &["solve", "codes", "analysis", "output", "commands", "cli"],
        ),
        ("solve", &["codes", "analysis", "output", "commands", "cli"]),
        ("codes", &["analysis", "output", "commands", "cli"]),
        (
            "output",
            &["model", "solve", "codes", "analysis", "commands", "cli"],
        ),
        ("analysis", &["commands", "cli"]),
    ];
    let mut violations = Vec::new();
    for (from, targets) in &g.edges {
        let layer = top(from);
        let library = !matches!(layer, "cli" | "commands");
        for (to, parent_to_child) in targets {
            let target = top(to);
            let root_to_entry = from.is_empty() && *parent_to_child;
            let refused = forbidden
                .iter()
                .any(|(l, banned)| *l == layer && banned.contains(&target))
                || (library && matches!(target, "cli" | "commands") && !root_to_entry);
            if refused {
                violations.push(format!(
                    "{} imports {}",
                    g.files[from].display(),
                    to.join("::")
                ));
            }
        }
    }
    assert!(violations.is_empty(), "{}", violations.join("\n"));
    // The reader sees the imports it is meant to police.
    let analysis_run = vec!["analysis".to_string(), "run".to_string()];
    assert!(
        g.edges[&analysis_run]
            .iter()
            .any(|(t, _)| top(t) == "solve"),
        "analysis::run's imports of solve were not found"
    );
}

/// Every circle of files: for each file, each shortest path back to itself through other
/// files (parent-to-child naming left out), reported once per set of files.
fn cycles(g: &Graph) -> Vec<String> {
    let mut found: BTreeMap<BTreeSet<Vec<String>>, Vec<Vec<String>>> = BTreeMap::new();
    for start in g.edges.keys() {
        // Breadth-first from `start`, remembering each node's predecessor.
        let mut before: BTreeMap<&Vec<String>, &Vec<String>> = BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([start]);
        let mut closing = None;
        while let Some(node) = queue.pop_front() {
            for (next, parent_to_child) in &g.edges[node] {
                if *parent_to_child {
                    continue;
                }
                if next == start {
                    closing = Some(node);
                    break;
                }
                if !before.contains_key(next) {
                    before.insert(next, node);
                    queue.push_back(next);
                }
            }
            if closing.is_some() {
                break;
            }
        }
        let Some(mut node) = closing else { continue };
        let mut path = vec![start.clone()];
        while node != start {
            path.push(node.clone());
            node = before[node];
        }
        path.reverse();
        path.rotate_right(1);
        let members: BTreeSet<Vec<String>> = path.iter().cloned().collect();
        found.entry(members).or_insert(path);
    }
    found
        .into_values()
        .map(|path| {
            let mut names: Vec<String> = path.iter().map(|m| m.join("::")).collect();
            names.push(names[0].clone());
            names.join(" → ")
        })
        .collect()
}

#[test]
fn no_file_level_import_cycle() {
    let g = graph();
    let circles = cycles(&g);
    assert!(
        circles.is_empty(),
        "{} import circle(s):\n{}",
        circles.len(),
        circles.join("\n")
    );
}

fn words(path: &[&str]) -> Vec<String> {
    path.iter().map(|w| w.to_string()).collect()
}

#[test]
fn an_inline_super_path_is_an_edge() {
    let module = words(&["codes", "liggghts"]);
    let source = "fn f() { super::yade::batch::render_batch(setups) }";
    let paths = referenced_paths(&module, source, &BTreeSet::new());
    assert!(
        paths
            .iter()
            .any(|(p, _)| p == &words(&["codes", "yade", "batch", "render_batch"])),
        "{paths:?}"
    );
}

/// A grouped import names every module in its group, and a `$crate::` path in a macro body is
/// an edge like any other: each of these would hide an import that climbs the layers.
#[test]
fn grouped_imports_and_macro_paths_are_edges() {
    let module = words(&["model", "law"]);
    let source = r#"
        use crate::{analysis::run::{self, IntegrationOptions}, codes};
        macro_rules! m { () => { $crate::output::export() }; }
        fn g() { let _ = format!("{}", crate::solve::Method::Rk4); }
        #[cfg(test)]
        mod tests { use crate::commands::x; }
    "#;
    let paths = referenced_paths(&module, source, &BTreeSet::new());
    let targets: BTreeSet<Vec<String>> = paths.into_iter().map(|(p, _)| p).collect();
    for expected in [
        words(&["analysis", "run"]),
        words(&["analysis", "run", "IntegrationOptions"]),
        words(&["codes"]),
        words(&["output", "export"]),
        words(&["solve", "Method", "Rk4"]),
    ] {
        assert!(targets.contains(&expected), "{expected:?} in {targets:?}");
    }
    assert!(
        !targets
            .iter()
            .any(|t| t.first().is_some_and(|w| w == "commands")),
        "test-only imports are left out: {targets:?}"
    );
}

/// A parent naming its declared child (`child::f()`, `pub use child::X`) is told apart.
#[test]
fn a_parent_naming_its_child_is_marked() {
    let module = words(&["codes"]);
    let children: BTreeSet<String> = ["yade".to_string()].into();
    let source = "pub use yade::Yade; fn f() { yade::batch::go() }";
    let paths = referenced_paths(&module, source, &children);
    assert!(
        paths
            .iter()
            .all(|(p, child)| *child && p[..2] == words(&["codes", "yade"])),
        "{paths:?}"
    );
    assert_eq!(paths.len(), 2, "{paths:?}");
}
