//! `millimpact deck` on LIGGGHTS decks written for the paper's law (`model paper`,
//! `model paper/linear`), run in liggghts-paper: each pair realises the closed form
//! `sqrt((1 − η)/(1 + η))` of its own η to within the step's band, and the code's own law (the
//! paper's) stepped as the code steps it to rounding.
//!
//! `UPDATE_DECK_RUNS=1 cargo test --release --test deck_paper_live -- --ignored` also writes the
//! runs to `tests/data/deck/liggghts-paper/` (read by `tests/deck_paper.rs`).

// The model difference is a closed form less the same closed form: exactly zero.
#![allow(clippy::float_cmp)]

mod common;

use std::path::Path;

use millimpact::analysis::deck::{
    DeckReport, LiveRunner, RecordedRuns, Recording, check_deck, read_deck,
};
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, TypeRef};
use millimpact::model::exact::restitution;
use millimpact::model::law::CodeLaw;

/// The speed the runs are recorded at, m/s.
const VELOCITY: f64 = 2.0;

/// η of the pair `types` as the deck's `lossCoefficient` matrix gives it (`wall_type`: the
/// wall's atom type).
fn eta_of<const N: usize>(matrix: &[[f64; N]; N], types: [TypeRef; 2], wall_type: u32) -> f64 {
    let index = |t: TypeRef| match t {
        TypeRef::Type(t) => t as usize - 1,
        TypeRef::Wall => wall_type as usize - 1,
    };
    matrix[index(types[0])][index(types[1])]
}

/// Check `report`: every pair run, its law the paper's with the deck's η, its COR within the
/// step's band of the closed form and below 1e-3 off it, and the run the law stepped to
/// rounding.
fn check_pairs(report: &DeckReport, etas: &dyn Fn([TypeRef; 2]) -> f64, pairs: usize) {
    assert_eq!(report.code, CodeName::LiggghtsPaper);
    assert_eq!(report.impacts.len(), pairs);
    for i in &report.impacts {
        let at = format!("{} at {} m/s", i.pair, i.impact_velocity);
        assert_eq!(i.failure, None, "{at}");
        let eta = etas(i.types);
        let CodeLaw::Paper(law) = i.law else {
            panic!("{at}: {:?} is not the paper's law", i.law)
        };
        assert_eq!(law.loss_coefficient, eta, "{at}");
        let closed = restitution(eta);
        assert_eq!(i.cor_entered, Some(closed), "{at}");
        assert_eq!(i.model_difference, Some(0.0), "{at}");
        let off = i.realised.cor - closed;
        let band = i
            .integration_band
            .min
            .abs()
            .max(i.integration_band.max.abs());
        assert!(
            off.abs() <= band + 1e-12,
            "{at}: COR {} is {off:e} off the closed form {closed}, beyond the step's band {band:e}",
            i.realised.cor
        );
        assert!(off.abs() < 1e-3, "{at}: {off:e}");
        assert!(
            i.remainder.abs() < 1e-9,
            "{at}: remainder {:e}",
            i.remainder
        );
        assert!(
            (i.integration_difference - off).abs() < 1e-9,
            "{at}: integration {:e} against {off:e}",
            i.integration_difference
        );
    }
}

fn run(path: &Path, name: &str) -> DeckReport {
    std::env::set_current_dir(common::root()).unwrap();
    let (code, deck) = read_deck(path, None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::LiggghtsPaper);
    let live = LiveRunner::default();
    let recording = Recording {
        inner: &live,
        runs: Default::default(),
    };
    let report = check_deck(code, &deck, (vec![VELOCITY], "given".into()), &recording).unwrap();
    if std::env::var_os("UPDATE_DECK_RUNS").is_some() {
        let runs: RecordedRuns = recording.runs.into_inner().unwrap();
        std::fs::write(
            common::root()
                .join("tests/data/deck/liggghts-paper")
                .join(format!("{name}.runs.json")),
            serde_json::to_string(&runs).unwrap(),
        )
        .unwrap();
    }
    report
}

/// The lossCoefficient matrix of `in.paper_mill`.
pub const MILL_ETA: [[f64; 3]; 3] = [[0.30, 0.35, 0.40], [0.35, 0.20, 0.45], [0.40, 0.45, 0.55]];

/// The lossCoefficient matrix of `in.paper_rod`.
pub const ROD_ETA: [[f64; 2]; 2] = [[0.35, 0.6], [0.6, 0.2]];

#[test]
#[ignore = "live: runs liggghts-paper on a three-type model paper deck"]
fn a_model_paper_deck_realises_each_pairs_closed_form_in_liggghts_paper() {
    let report = run(
        Path::new("tests/data/deck/liggghts-paper/in.paper_mill"),
        "paper_mill",
    );
    // Three ball types: six pairs of balls, three against the liner (type 1's steel).
    check_pairs(&report, &|t| eta_of(&MILL_ETA, t, 1), 9);
}

#[test]
#[ignore = "live: runs liggghts-paper on a two-type model paper/linear deck"]
fn a_model_paper_linear_deck_realises_each_pairs_closed_form_in_liggghts_paper() {
    let report = run(
        Path::new("tests/data/deck/liggghts-paper/in.paper_rod"),
        "paper_rod",
    );
    // One rod end, against its own kind and against the liner (type 2).
    check_pairs(&report, &|t| eta_of(&ROD_ETA, t, 2), 2);
}
