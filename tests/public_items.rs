//! The library's public surface, read from the source with `syn`: every item declared `pub`
//! (not `pub(crate)`) that a user can reach, with its module path, as one snapshot, so that a
//! new `pub` is a visible change in review. An item is reachable when every module above it is
//! declared `pub`: a `pub` item inside a crate-private module (`pub(crate) mod`, `mod`, such as
//! the command line's `cli` and `commands`) is not public and is not counted. Test-only items
//! are left out.

mod common;

use std::path::{Path, PathBuf};

use syn::{ImplItem, Item, Visibility};

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

fn test_only(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg")
            && a.parse_args::<syn::Meta>()
                .is_ok_and(|m| m.path().is_ident("test"))
    })
}

fn public(vis: &Visibility) -> bool {
    matches!(vis, Visibility::Public(_))
}

/// `module` with `name` after it.
fn join(module: &str, name: impl std::fmt::Display) -> String {
    if module.is_empty() {
        name.to_string()
    } else {
        format!("{module}::{name}")
    }
}

/// The public items of `items` in `module`, as `kind path` lines.
fn collect(module: &str, items: &[Item], out: &mut Vec<String>) {
    for item in items {
        let line =
            |kind: &str, name: &dyn std::fmt::Display| format!("{kind} {}", join(module, name));
        match item {
            Item::Fn(f) if public(&f.vis) && !test_only(&f.attrs) => {
                out.push(line("fn", &f.sig.ident));
            }
            Item::Struct(s) if public(&s.vis) && !test_only(&s.attrs) => {
                out.push(line("struct", &s.ident));
            }
            Item::Enum(e) if public(&e.vis) => out.push(line("enum", &e.ident)),
            Item::Trait(t) if public(&t.vis) => out.push(line("trait", &t.ident)),
            Item::Const(c) if public(&c.vis) => out.push(line("const", &c.ident)),
            Item::Static(s) if public(&s.vis) => out.push(line("static", &s.ident)),
            Item::Type(t) if public(&t.vis) => out.push(line("type", &t.ident)),
            // A re-export is counted as the items it makes reachable (`surface`), not as a line.
            Item::Use(_) => {}
            Item::Mod(m) if !test_only(&m.attrs) && public(&m.vis) => {
                out.push(line("mod", &m.ident));
                if let Some((_, inner)) = &m.content {
                    collect(&join(module, &m.ident), inner, out);
                }
            }
            Item::Impl(i) if !test_only(&i.attrs) => {
                let self_ty = type_name(&i.self_ty);
                for member in &i.items {
                    if let ImplItem::Fn(f) = member
                        && public(&f.vis)
                    {
                        out.push(format!(
                            "fn {}",
                            join(module, format!("{self_ty}::{}", f.sig.ident))
                        ));
                    }
                }
            }
            _ => {}
        }
    }
}

fn type_name(ty: &syn::Type) -> String {
    match ty {
        syn::Type::Path(p) => p
            .path
            .segments
            .last()
            .map(|s| s.ident.to_string())
            .unwrap_or_default(),
        _ => "_".to_string(),
    }
}

/// The module path of a library file: `src/analysis/run.rs` → `analysis::run`.
fn module_of(src: &Path, file: &Path) -> String {
    let relative = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts.join("::")
}

/// The module paths of the files' `mod x;` declarations that are not `pub`.
fn private_modules(files: &[(String, syn::File)]) -> Vec<String> {
    let mut private = Vec::new();
    for (module, parsed) in files {
        for item in &parsed.items {
            if let Item::Mod(m) = item
                && !public(&m.vis)
            {
                private.push(join(module, &m.ident));
            }
        }
    }
    private
}

fn surface() -> Vec<String> {
    let src = common::root().join("src");
    let mut paths = Vec::new();
    rust_files(&src, &mut paths);
    let files: Vec<(String, syn::File)> = paths
        .iter()
        .map(|file| {
            let text = std::fs::read_to_string(file).unwrap();
            (module_of(&src, file), syn::parse_file(&text).unwrap())
        })
        .filter(|(module, _)| module != "main")
        .collect();
    let private = private_modules(&files);
    let reachable = |module: &str| {
        !private
            .iter()
            .any(|p| module == p || module.starts_with(&format!("{p}::")))
    };
    let mut out = Vec::new();
    for (module, parsed) in &files {
        if reachable(module) {
            collect(module, &parsed.items, &mut out);
        }
    }
    // A `pub use` of an item of a crate-private module makes that item reachable, with its
    // public methods: counted under the re-exporting module. One of an already reachable
    // item adds nothing (it is counted where it is declared).
    for (module, parsed) in files.iter().filter(|(m, _)| reachable(m)) {
        for item in &parsed.items {
            let Item::Use(u) = item else { continue };
            if !public(&u.vis) {
                continue;
            }
            for (target, name) in use_leaves(module, &u.tree, Vec::new()) {
                if reachable(&target) {
                    continue;
                }
                let Some((_, declared)) = files.iter().find(|(m, _)| *m == target) else {
                    continue;
                };
                let mut found = Vec::new();
                collect("", &declared.items, &mut found);
                out.extend(
                    found
                        .iter()
                        .filter_map(|l| l.split_once(' '))
                        .filter(|(_, path)| {
                            name == "*" || *path == name || path.starts_with(&format!("{name}::"))
                        })
                        .map(|(kind, path)| format!("{kind} {}", join(module, path))),
                );
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

/// The (module, name) pairs a `use` tree names, the module resolved from `crate::`, `super::`
/// or the using module's own children.
fn use_leaves(module: &str, tree: &syn::UseTree, prefix: Vec<String>) -> Vec<(String, String)> {
    let resolve = |segments: &[String]| -> String {
        let mut path: Vec<String> = if segments.first().is_some_and(|s| s == "crate") {
            Vec::new()
        } else {
            module
                .split("::")
                .filter(|s| !s.is_empty())
                .map(String::from)
                .collect()
        };
        for s in segments {
            match s.as_str() {
                "crate" | "self" => {}
                "super" => {
                    path.pop();
                }
                other => path.push(other.to_string()),
            }
        }
        path.join("::")
    };
    match tree {
        syn::UseTree::Path(p) => {
            let mut next = prefix;
            next.push(p.ident.to_string());
            use_leaves(module, &p.tree, next)
        }
        syn::UseTree::Name(n) => vec![(resolve(&prefix), n.ident.to_string())],
        syn::UseTree::Rename(r) => vec![(resolve(&prefix), r.ident.to_string())],
        syn::UseTree::Glob(_) => vec![(resolve(&prefix), "*".to_string())],
        syn::UseTree::Group(g) => g
            .items
            .iter()
            .flat_map(|t| use_leaves(module, t, prefix.clone()))
            .collect(),
    }
}

#[test]
fn the_public_surface_is_as_reviewed() {
    let surface = surface();
    // The reader finds what the crate's docs promise a user, and not the command line's items.
    assert!(!surface.iter().any(|l| l.contains("commands::")));
    for expected in [
        "fn analysis::store::verify::verify",
        "fn run_command_line",
        "enum analysis::store::StoreError",
        "struct model::case::Case",
    ] {
        assert!(surface.iter().any(|l| l == expected), "{expected}");
    }
    let text = format!("{} public items\n{}\n", surface.len(), surface.join("\n"));
    insta::assert_snapshot!("public_items", text);
}
