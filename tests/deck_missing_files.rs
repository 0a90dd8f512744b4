//! A file a deck names that is not there (an include, a mesh, a data file, a Kratos `.mdpa` or
//! materials file) is refused before any code runs: exit 2, one line with the deck's line (or
//! field) and the missing path, as the code itself would stop there.

mod common;

use common::deck::{GRANULAR, HEAD, deck_files, hide_codes, kratos_deck};
use common::{codes_hidden, millimpact, root};
use millimpact::analysis::deck::read_deck;
use millimpact::codes::CodeName;
use millimpact::codes::deck::DeckOptions;

const ATOMS: &str = "pair_coeff * *\ncreate_atoms 1 single 0 0 0\nset atom 1 diameter 0.02 density 7800\ntimestep 1e-7\n";

fn refusal(path: &std::path::Path, code: Option<CodeName>) -> String {
    hide_codes();
    read_deck(path, code, &DeckOptions::default())
        .unwrap_err()
        .to_string()
}

#[test]
fn a_missing_include_is_refused_at_the_include_line() {
    let (_d, path) = deck_files(&[(
        "in.main",
        &format!("{HEAD}pair_style gran model hertz\ninclude parts/nowhere.in\n{ATOMS}"),
    )]);
    let e = refusal(&path, None);
    let at = format!("{}:9: include ", path.display());
    assert!(e.starts_with(&at), "{e}");
    assert!(e.contains("`parts/nowhere.in` does not exist"), "{e}");
    // An include inside an include is named at the inner file's line.
    let (_d, path) = deck_files(&[
        ("in.main", &format!("{HEAD}include more.in\n")),
        ("more.in", "# settings\ninclude gone.in\n"),
    ]);
    let e = refusal(&path, None);
    assert!(e.contains("more.in:2: include "), "{e}");
}

#[test]
fn a_missing_mesh_file_is_refused_at_its_fix_line() {
    let deck = format!(
        "{HEAD}pair_style gran model hertz\nfix cad all mesh/surface file meshes/drum.stl type 3\n\
fix walls all wall/gran model hertz mesh n_meshes 1 meshes cad\n{ATOMS}"
    );
    let (dir, path) = deck_files(&[("in.mesh", &deck)]);
    let e = refusal(&path, None);
    let at = format!("{}:9: mesh file ", path.display());
    assert!(
        e.starts_with(&at) && e.contains("`meshes/drum.stl` does not exist"),
        "{e}"
    );
    // With the mesh there, the deck reads.
    std::fs::create_dir(dir.path().join("meshes")).unwrap();
    std::fs::write(
        dir.path().join("meshes/drum.stl"),
        "solid drum\nendsolid drum\n",
    )
    .unwrap();
    hide_codes();
    let deck = read_deck(&path, None, &DeckOptions::default()).unwrap().1;
    assert_eq!(deck.walls.len(), 1);
}

#[test]
fn a_missing_data_file_is_refused_at_its_read_data_line() {
    let text = std::fs::read_to_string(root().join(GRANULAR)).unwrap();
    let text = text.replace(
        "create_box      2 box",
        "create_box      2 box\nread_data       beads.data add append",
    );
    let (_d, path) = deck_files(&[("in.data", &text)]);
    let e = refusal(&path, Some(CodeName::Lammps));
    assert!(e.contains("data file `beads.data` does not exist"), "{e}");
    let line = text
        .lines()
        .position(|l| l.starts_with("read_data"))
        .unwrap()
        + 1;
    assert!(
        e.starts_with(&format!("{}:{line}: ", path.display())),
        "{e}"
    );
}

#[test]
fn a_missing_kratos_model_part_or_materials_file_is_refused_at_the_project_field() {
    let (dir, path) = kratos_deck(|_| {}, |_| {});
    std::fs::remove_file(dir.path().join("millDEM.mdpa")).unwrap();
    let e = refusal(&path, None);
    assert!(
        e.contains("ProjectParametersDEM.json: problem_name: ")
            && e.contains("`millDEM.mdpa` does not exist"),
        "{e}"
    );
    let (dir, _) = kratos_deck(|_| {}, |_| {});
    std::fs::remove_file(dir.path().join("MaterialsDEM.json")).unwrap();
    let project = dir.path().join("ProjectParametersDEM.json");
    let e = refusal(&project, None);
    assert!(
        e.contains("materials_filename: the materials file")
            && e.contains("`MaterialsDEM.json` does not exist"),
        "{e}"
    );
}

#[test]
fn the_command_refuses_a_missing_file_in_one_line_with_exit_2_and_runs_nothing() {
    let (_d, path) = deck_files(&[(
        "in.main",
        &format!("{HEAD}pair_style gran model hertz\ninclude nowhere.in\n{ATOMS}"),
    )]);
    let out = millimpact()
        .args(["deck", path.to_str().unwrap()])
        .envs(codes_hidden())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("in.main:9: include ") && err.contains("nowhere.in"),
        "{err}"
    );
}
