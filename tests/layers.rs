//! The import layers of `src/`, read from the source: every `use` line and every inline
//! `crate::…` path of every file is resolved to the file it names, and
//!
//! - no library file (anything but `main.rs`, `cli.rs` and `commands/`) imports `cli` or
//!   `commands`;
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

/// The code of a file outside its `#[cfg(test)]` module and outside comments.
fn library_lines(text: &str) -> Vec<&str> {
    let mut lines = Vec::new();
    let mut in_tests = false;
    for line in text.lines() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("#[cfg(test)]") {
            in_tests = true;
        }
        if in_tests {
            // The test module runs to the end of the file (its closing brace at column 0).
            if line == "}" {
                in_tests = false;
            }
            continue;
        }
        if !trimmed.starts_with("//") {
            lines.push(line);
        }
    }
    lines
}

/// The module paths a file names: `use crate::a::b…`, inline `crate::a::b…`, `super::a…`
/// in a `use` line or inline, and, in a module's own file, `use child::…` / `child::…` of a declared child.
fn referenced_paths(
    module: &[String],
    lines: &[&str],
    children: &BTreeSet<String>,
) -> Vec<(Vec<String>, bool)> {
    let mut out = Vec::new();
    let path_after = |s: &str| -> Vec<String> {
        s.split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
            .next()
            .unwrap_or("")
            .split("::")
            .filter(|p| !p.is_empty())
            .map(str::to_string)
            .collect()
    };
    for line in lines {
        let mut rest = *line;
        while let Some(at) = rest.find("crate::") {
            let before = rest[..at].chars().last();
            rest = &rest[at + 7..];
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
                continue;
            }
            out.push((path_after(rest), false));
        }
        // Every `super::` path, in a `use` line or inline (`super::x::f()`), names a module
        // relative to the file's own; `super::super::` climbs one more.
        let mut rest = *line;
        while let Some(at) = rest.find("super::") {
            let before = rest[..at].chars().last();
            rest = &rest[at + 7..];
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let mut up = 1;
            while let Some(after) = rest.strip_prefix("super::") {
                rest = after;
                up += 1;
            }
            let mut path = module[..module.len().saturating_sub(up)].to_vec();
            path.extend(path_after(rest));
            out.push((path, false));
        }
        let trimmed = line.trim_start();
        let body = trimmed
            .strip_prefix("pub use ")
            .or_else(|| trimmed.strip_prefix("pub(crate) use "))
            .or_else(|| trimmed.strip_prefix("use "));
        if let Some(body) = body {
            if !body.starts_with("super::") && !body.starts_with("crate::") {
                let first = path_after(body);
                if first.first().is_some_and(|f| children.contains(f)) {
                    let mut path = module.to_vec();
                    path.extend(first);
                    out.push((path, true));
                }
            }
        } else {
            for child in children {
                if line.contains(&format!("{child}::")) {
                    let mut path = module.to_vec();
                    path.push(child.clone());
                    out.push((path, true));
                }
            }
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
        let children: BTreeSet<String> = text
            .lines()
            .filter_map(|l| {
                let t = l.trim_start();
                let t = t.strip_prefix("pub ").unwrap_or(t);
                let declared = t.strip_prefix("mod ")?;
                // `mod x;`, or a registry line `mod x { Variant => Driver },` that declares it.
                declared
                    .strip_suffix(';')
                    .or_else(|| declared.split_once(" {").map(|(name, _)| name))
                    .map(str::to_string)
            })
            .collect();
        let lines = library_lines(&text);
        let mut targets = BTreeSet::new();
        for (path, parent_to_child) in referenced_paths(module, &lines, &children) {
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
        for (to, _) in targets {
            let target = top(to);
            let refused = forbidden
                .iter()
                .any(|(l, banned)| *l == layer && banned.contains(&target))
                || (library && matches!(target, "cli" | "commands"));
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

#[test]
fn an_inline_super_path_is_an_edge() {
    let module = vec!["codes".to_string(), "liggghts".to_string()];
    let lines = ["        super::yade::batch::render_batch(setups)"];
    let paths = referenced_paths(&module, &lines, &BTreeSet::new());
    assert!(
        paths
            .iter()
            .any(|(p, _)| p == &["codes", "yade", "batch", "render_batch"]),
        "{paths:?}"
    );
}
