//! The library's errors are typed: `anyhow` lives only in the binary (`main.rs`, `cli.rs`,
//! `commands/`), and a user's own test can match a library error by its variant, read the
//! values it carries, and ask whether it is the user's (exit 2) or not.

use std::path::{Path, PathBuf};

use millimpact::analysis::run::{RunError, run_case};
use millimpact::analysis::sweep::SweepError;
use millimpact::analysis::sweep::merge;
use millimpact::error::{Blame, Chain};
use millimpact::{Case, CodeName, Method, Settings, StoreError, find_stored, verify};

mod common;

/// Library files that still use `anyhow`, each with the reason. The list only shrinks: a file
/// named here that no longer uses `anyhow` fails the test until it is taken off.
const STILL_ON_ANYHOW: &[(&str, &str)] = &[];

/// Every `.rs` file under `dir`, as paths relative to `root`.
fn rust_files(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(root, &path, out);
        } else if path.extension().is_some_and(|x| x == "rs") {
            out.push(path.strip_prefix(root).unwrap().to_path_buf());
        }
    }
}

#[test]
fn anyhow_is_used_only_by_the_binary() {
    let root = common::root();
    let mut files = Vec::new();
    rust_files(&root, &root.join("src"), &mut files);
    assert!(files.len() > 50, "{} source files found", files.len());
    let binary = |path: &Path| {
        path == Path::new("src/main.rs")
            || path == Path::new("src/cli.rs")
            || path.starts_with("src/commands")
    };
    let mut offenders = Vec::new();
    let mut binary_uses = 0;
    for path in &files {
        let text = std::fs::read_to_string(root.join(path)).unwrap();
        let uses = text.contains("anyhow");
        let listed = STILL_ON_ANYHOW
            .iter()
            .any(|(file, _)| Path::new(file) == path);
        if binary(path) {
            binary_uses += usize::from(uses);
        } else if listed {
            assert!(
                uses,
                "{} no longer uses anyhow: take it off STILL_ON_ANYHOW",
                path.display()
            );
        } else if uses {
            offenders.push(path.display().to_string());
        }
    }
    assert!(offenders.is_empty(), "anyhow in the library: {offenders:?}");
    // The binary is where anyhow belongs (the command line's `Failure` holds one): a scan that
    // saw none of it read nothing.
    assert!(binary_uses >= 1, "{binary_uses} binary files use anyhow");
}

#[test]
fn a_missing_cases_folder_is_the_users_and_names_the_folder() {
    let root = common::root();
    let missing = root.join("no-such-cases");
    let error = verify(&missing, &root.join("reference")).unwrap_err();
    match &error {
        StoreError::CasesUnreadable { folder, reason } => {
            assert_eq!(folder, &missing);
            assert_eq!(reason.kind(), std::io::ErrorKind::NotFound);
        }
        other => panic!("expected CasesUnreadable, got {other:?}"),
    }
    assert!(error.is_user_error());
    assert!(
        error.to_string().starts_with(&format!(
            "--cases = {}: cannot read the folder",
            missing.display()
        )),
        "{error}"
    );
}

#[test]
fn a_file_that_is_not_a_reference_is_named_with_the_json_readers_cause() {
    let folder = tempfile::tempdir().unwrap();
    let file = folder.path().join("lammps").join("ball_plate.json");
    std::fs::create_dir_all(file.parent().unwrap()).unwrap();
    std::fs::write(&file, "{ not json").unwrap();
    let error = find_stored(folder.path(), CodeName::Lammps, "ball_plate", 0.35).unwrap_err();
    let StoreError::NotAReferenceFile { path, source } = &error else {
        panic!("expected NotAReferenceFile, got {error:?}");
    };
    assert_eq!(path, &file);
    assert!(source.is_syntax(), "{source}");
    assert!(!error.is_user_error());
    // The chain on one line, as a failed row or a finding writes it.
    let line = Chain(&error).to_string();
    assert!(
        line.starts_with(&format!("{}: not a reference file: ", file.display())),
        "{line}"
    );
}

#[test]
fn a_step_beyond_the_stability_limit_is_the_users_through_every_wrapper() {
    let case = Case::load(&common::root().join("cases/ball_plate.toml")).unwrap();
    let settings = Settings {
        method: Method::Rk4,
        timestep: Some(2e-4),
        ..Settings::default()
    };
    let error = run_case(&case, &settings).unwrap_err();
    let RunError::Unsolvable { case: path, source } = &error else {
        panic!("expected Unsolvable, got {error:?}");
    };
    assert_eq!(path, &case.path);
    assert!(matches!(
        source,
        millimpact::solve::SolveError::Unstable { method: "rk4", .. }
    ));
    assert!(error.is_user_error());
    // Wrapped transparently, it is still the user's, and reads the same.
    let wrapped = SweepError::from(error);
    assert!(wrapped.is_user_error());
    assert!(
        wrapped.to_string().starts_with(&format!(
            "{}: --timestep: rk4: time step",
            case.path.display()
        )),
        "{wrapped}"
    );
}

#[test]
fn a_shard_that_is_not_there_is_a_read_failure_not_the_users() {
    let missing = Path::new("no-such-shard.csv");
    let error = merge(&[missing]).unwrap_err();
    let SweepError::Read { path, source } = &error else {
        panic!("expected Read, got {error:?}");
    };
    assert_eq!(path, missing);
    assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
    assert!(!error.is_user_error());
}
