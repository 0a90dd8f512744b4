//! `millimpact deck` on LAMMPS decks that load the paper plugin (`pair_style paper`,
//! `fix wall/paper`): read with the plugin's rules and run in lammps-paper. Fast: the laws of
//! each pair, the refusals, and the recorded runs checked again; live: each pair realises the
//! closed form `sqrt((1 − η)/(1 + η))` of its own η within the step's band, and the law stepped
//! to rounding.
//!
//! `UPDATE_DECK_RUNS=1 cargo test --release --test lammps_paper_deck -- --ignored` also writes
//! the runs to `tests/data/deck/lammps-paper/` (read by the fast tests).

// The model difference is a closed form less the same closed form: exactly zero.
#![allow(clippy::float_cmp)]

mod common;

use std::path::Path;

use millimpact::analysis::deck::{
    DeckReport, LiveRunner, RecordedRuns, Recording, check_deck, read_deck,
};
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, TypeRef};
use millimpact::codes::lammps::paper_plugin_modulus as plugin_modulus;
use millimpact::model::exact::restitution;
use millimpact::model::law::CodeLaw;
use millimpact::model::scene::{pair_radius, reduced_mass};

use common::{millimpact, root};

const MILL: &str = "tests/data/deck/lammps-paper/in.paper_mill";
const RUNS: &str = "tests/data/deck/lammps-paper/paper_mill.runs.json";

/// η of each pair of the deck's types, as its pair_coeff lines give it; the liner's η.
const MILL_ETA: [[f64; 3]; 3] = [[0.35, 0.40, 0.45], [0.40, 0.30, 0.50], [0.45, 0.50, 0.55]];
const LINER_ETA: f64 = 0.25;

fn eta_of(types: [TypeRef; 2]) -> f64 {
    match types {
        [TypeRef::Type(i), TypeRef::Type(j)] => MILL_ETA[i as usize - 1][j as usize - 1],
        _ => LINER_ETA,
    }
}

/// Check `report`: every pair run in lammps-paper, its law the paper's with the deck's η, its
/// COR within the step's band of the closed form and below 1e-3 off it, and the run the law
/// stepped to rounding.
fn check_pairs(report: &DeckReport) {
    assert_eq!(report.code, CodeName::LammpsPaper);
    assert_eq!(report.impacts.len(), 9);
    for i in &report.impacts {
        let at = format!("{} at {} m/s", i.pair, i.impact_velocity);
        assert_eq!(i.failure, None, "{at}");
        let CodeLaw::Paper(law) = i.law else {
            panic!("{at}: {:?} is not the paper's law", i.law)
        };
        let eta = eta_of(i.types);
        assert_eq!(law.loss_coefficient, eta, "{at}");
        assert_eq!(i.cor_entered, Some(restitution(eta)), "{at}");
        assert_eq!(i.model_difference, Some(0.0), "{at}");
        let off = i.realised.cor - restitution(eta);
        let band = i
            .integration_band
            .min
            .abs()
            .max(i.integration_band.max.abs());
        assert!(
            off.abs() <= band + 1e-12 && off.abs() < 1e-3,
            "{at}: {off:e} off the closed form, band {band:e}"
        );
        assert!(i.remainder.abs() < 1e-9, "{at}: {:e}", i.remainder);
    }
}

#[test]
fn a_plugin_deck_runs_in_lammps_paper_with_each_pairs_eta_and_materials() {
    let (code, deck) = read_deck(&root().join(MILL), None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::LammpsPaper);
    assert_eq!(deck.contacts.len(), 9);
    let material = [(2e11, 0.3), (2e11, 0.3), (3.7e11, 0.22)];
    for c in &deck.contacts {
        let CodeLaw::Paper(law) = c.law else {
            panic!("{:?}", c.law)
        };
        assert_eq!(law.loss_coefficient, eta_of(c.types), "{:?}", c.types);
        let body = &deck.bodies[c.body];
        let (modulus, r_star, mass) = match c.types {
            [TypeRef::Type(i), TypeRef::Type(j)] => {
                let other = deck.bodies.iter().find(|b| b.type_id == j).unwrap();
                let ((e1, n1), (e2, n2)) = (material[i as usize - 1], material[j as usize - 1]);
                (
                    plugin_modulus(e1, n1, e2, n2),
                    pair_radius(body.radius, other.radius),
                    reduced_mass(body.mass, other.mass),
                )
            }
            _ => (plugin_modulus(2e11, 0.3, 2e11, 0.3), body.radius, body.mass),
        };
        let expected = 4.0 / 3.0 * modulus * r_star.sqrt();
        assert!(
            ((law.stiffness - expected) / expected).abs() < 1e-15,
            "{:?}: {} vs {expected}",
            c.types,
            law.stiffness
        );
        assert_eq!(law.mass, mass);
        assert_eq!(law.exponent, 1.5);
    }
    // The impacts load the plugin by its file name, whatever path the deck gives.
    assert_eq!(
        deck.transplant.common[0],
        "plugin          load paperplugin.so"
    );
    assert_eq!(
        deck.transplant.walls,
        ["fix liner all wall/paper hertz 0.25 200000000000 0.3 200000000000 0.3 zplane 0 NULL"]
    );
}

/// What the plugin stops on is refused before a run, in one line naming the file and line:
/// η outside [0, 1), a pair of types without its pair_coeff, the wrong number of values.
#[test]
fn a_bad_eta_or_a_missing_pair_is_refused_with_its_line() {
    let text = std::fs::read_to_string(root().join(MILL)).unwrap();
    let cases: [(&str, String, &str); 4] = [
        (
            "η = 1.2",
            text.replace("pair_coeff      2 3 0.50", "pair_coeff      2 3 1.2"),
            "in.paper:22: eta = 1.2; supported: 0 <= eta < 1",
        ),
        (
            "a wall's η < 0",
            text.replace("wall/paper hertz 0.25", "wall/paper hertz -0.1"),
            "in.paper:33: eta = -0.1; supported: 0 <= eta < 1",
        ),
        (
            "a missing pair",
            text.replace(
                "pair_coeff      2 3 0.50 ${steel_E} 0.3 ${alumina_E} 0.22\n",
                "",
            ),
            "no pair_coeff for atom types 2 3",
        ),
        (
            "kn under pair_style paper",
            text.replace(
                "pair_coeff      3 3 0.55 ${alumina_E} 0.22",
                "pair_coeff      3 3 0.55 1e8",
            ),
            "supported: the paper plugin's eta E nu [E2 nu2]",
        ),
    ];
    for (what, deck, expected) in cases {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("in.paper");
        std::fs::write(&path, deck).unwrap();
        let out = millimpact()
            .args(["deck"])
            .arg(&path)
            .args(["--impact-velocity", "2"])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{what}");
        assert!(out.stdout.is_empty(), "{what}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{what}: {err}");
        assert!(err.contains(expected), "{what}: {err}");
    }
}

/// A plain LAMMPS build asked for a plugin deck is refused in one line (exit 2): it has not
/// loaded the plugin.
#[test]
fn a_plain_lammps_build_asked_for_a_plugin_deck_is_refused() {
    for code in ["lammps", "lammps-2025"] {
        let out = millimpact()
            .args(["deck", MILL, "--code", code, "--impact-velocity", "2"])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{code}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains(&format!(
                "with --code {code}: the plain build has not loaded the paper plugin"
            )) && err.contains("supported: --code lammps-paper"),
            "{err}"
        );
    }
}

/// The recorded runs, checked again: the model difference 0, each COR within the step's band
/// of its closed form, the remainder at rounding.
#[test]
fn the_recorded_plugin_deck_runs_check_to_their_closed_forms() {
    let (code, deck) = read_deck(&root().join(MILL), None, &DeckOptions::default()).unwrap();
    let runs: RecordedRuns =
        serde_json::from_str(&std::fs::read_to_string(root().join(RUNS)).unwrap()).unwrap();
    let report = check_deck(code, &deck, (vec![2.0], "given".into()), &runs).unwrap();
    check_pairs(&report);
}

#[test]
#[ignore = "live: runs lammps-paper on a three-type plugin deck"]
fn live_a_plugin_deck_realises_each_pairs_closed_form_in_lammps_paper() {
    std::env::set_current_dir(root()).unwrap();
    let (code, deck) = read_deck(Path::new(MILL), None, &DeckOptions::default()).unwrap();
    let live = LiveRunner::default();
    let recording = Recording {
        inner: &live,
        runs: Default::default(),
    };
    let report = check_deck(code, &deck, (vec![2.0], "given".into()), &recording).unwrap();
    check_pairs(&report);
    if std::env::var_os("UPDATE_DECK_RUNS").is_some() {
        let runs: RecordedRuns = recording.runs.into_inner().unwrap();
        std::fs::write(root().join(RUNS), serde_json::to_string(&runs).unwrap()).unwrap();
    }
}
