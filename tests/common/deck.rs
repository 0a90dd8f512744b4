//! What the deck tests share: the examples' paths, small decks written to a fresh folder, and
//! the readers run with no code started (a LAMMPS build's fallback conventions, YADE's recorded
//! dump of a set-up).

use std::path::{Path, PathBuf};

use super::root;
use millimpact::analysis::deck::read_deck;
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, UserDeck};
use millimpact::codes::yade::deck::YadeDeck;

pub const MILL: &str = "examples/decks/liggghts-mill/in.mill";

pub fn read(path: &Path) -> UserDeck {
    read_deck(path, None, &DeckOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .1
}

/// A deck in a fresh folder: `files` are (name, text); the first is the deck.
pub fn deck_files(files: &[(&str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let path = dir.path().join(files[0].0);
    (dir, path)
}

/// The lines every small deck below shares: two steel types, a wall type, COR 0.5.
pub const HEAD: &str = "units si\natom_style granular\nhard_particles yes\ncreate_box 3 box\n\
fix m1 all property/global youngsModulus peratomtype 2e11 2e11 2e11\n\
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3 0.3\n\
fix m3 all property/global coefficientRestitution peratomtypepair 3 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5\n";

pub fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

pub const GRANULAR: &str = "examples/decks/lammps-granular/in.granular";

/// As on a machine without the codes: a LAMMPS deck is read with the build's fallback
/// conventions (no probe starts).
pub fn hide_codes() {
    for (variable, missing) in super::codes_hidden() {
        // SAFETY: every deck test that sets them sets the same values, before reading.
        unsafe { std::env::set_var(variable, missing) };
    }
}

pub const KRATOS_MILL: &str = "examples/decks/kratos-mill/MaterialsDEM.json";

pub const KRATOS_PROJECT: &str = "examples/decks/kratos-mill/ProjectParametersDEM.json";

pub fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The example's files in a fresh folder, its materials and project edited by `materials`
/// and `project`; the path of the materials file.
pub fn kratos_deck(
    materials: impl Fn(&mut serde_json::Value),
    project: impl Fn(&mut serde_json::Value),
) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let example = root().join("examples/decks/kratos-mill");
    for (name, edit) in [
        (
            "MaterialsDEM.json",
            &materials as &dyn Fn(&mut serde_json::Value),
        ),
        ("ProjectParametersDEM.json", &project),
    ] {
        let mut value = json(&example.join(name));
        edit(&mut value);
        std::fs::write(
            dir.path().join(name),
            serde_json::to_string_pretty(&value).unwrap(),
        )
        .unwrap();
    }
    std::fs::copy(
        example.join("millDEM.mdpa"),
        dir.path().join("millDEM.mdpa"),
    )
    .unwrap();
    let path = dir.path().join("MaterialsDEM.json");
    (dir, path)
}

pub const YADE_MILL: &str = "examples/decks/yade-mill/mill.py";

/// The YADE script at `script` (from the project's root) read from the recorded dump of its
/// set-up `dump` (under `tests/data/deck/yade/`, recorded as its README says): no YADE starts.
pub fn yade_read(script: &str, dump: &str, options: &DeckOptions) -> Result<UserDeck, String> {
    let text = std::fs::read_to_string(root().join("tests/data/deck/yade").join(dump)).unwrap();
    YadeDeck::read_dump(Path::new(script), &text, options).map_err(|e| e.to_string())
}

/// A script of `tests/data/deck/yade/` read from its recorded dump.
pub fn yade_case(name: &str) -> Result<UserDeck, String> {
    std::env::set_current_dir(root()).unwrap();
    yade_read(
        &format!("tests/data/deck/yade/{name}.py"),
        &format!("{name}.dump.json"),
        &DeckOptions::default(),
    )
}

pub const MIXED: &str = "examples/decks/lammps-mixed/in.mixed";

/// Read `path` with the reader of `code` (the build's fallback conventions: no code runs).
pub fn read_with(code: CodeName, path: &Path) -> UserDeck {
    hide_codes();
    read_deck(path, Some(code), &DeckOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .1
}

/// Two bead types, each with lines of its own only: the pair 1 2 is LAMMPS's to mix.
pub fn two_types(lines: &str) -> String {
    format!(
        "units si\natom_style sphere\ncreate_box 2 box\ncreate_atoms 1 single 0 0 0\ncreate_atoms 2 single 1 0 0\n\
set type 1 diameter 0.004 density 2500\nset type 2 diameter 0.006 density 7800\ntimestep 1e-7\npair_style granular\n{lines}"
    )
}
