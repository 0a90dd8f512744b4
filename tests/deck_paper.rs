//! `millimpact deck` on LIGGGHTS decks that select the paper's law (`model paper`,
//! `model paper/linear`), without a code: what the reader makes of them (the build that runs
//! them, each pair's law and the COR its η stands for), every refusal (η out of range or
//! missing, the settings the styles lack, the stock build asked for), and the check of the runs
//! `tests/deck_paper_live.rs` recorded in liggghts-paper.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use std::path::{Path, PathBuf};

use common::{millimpact, root};
use millimpact::analysis::deck::{RecordedRuns, check_deck, read_deck};
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, Partner, TypeRef, UserDeck};
use millimpact::model::exact::restitution;
use millimpact::model::law::{CodeLaw, PaperLaw};
use millimpact::model::scene::{pair_radius, reduced_mass};
use millimpact::output::{Format, export};

const MILL: &str = "tests/data/deck/liggghts-paper/in.paper_mill";
const ROD: &str = "tests/data/deck/liggghts-paper/in.paper_rod";

/// The lossCoefficient matrix of `in.paper_mill`.
const MILL_ETA: [[f64; 3]; 3] = [[0.30, 0.35, 0.40], [0.35, 0.20, 0.45], [0.40, 0.45, 0.55]];

fn read(path: &Path) -> (CodeName, UserDeck) {
    read_deck(&root().join(path), None, &DeckOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn paper(law: CodeLaw) -> PaperLaw {
    match law {
        CodeLaw::Paper(law) => law,
        CodeLaw::Dashpot(law) => panic!("{law:?} is not the paper's law"),
    }
}

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// A deck in a fresh folder.
fn deck_file(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("in.paper");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

#[test]
fn a_model_paper_deck_runs_in_liggghts_paper_with_each_pairs_eta() {
    let (code, deck) = read(Path::new(MILL));
    assert_eq!(code, CodeName::LiggghtsPaper);
    assert_eq!(deck.contacts.len(), 9);
    // E and ν per type as the deck gives them; the liner is type 1.
    let material = [(2.1e11, 0.3), (2.0e11, 0.29), (3.7e11, 0.22)];
    let e_star = |a: usize, b: usize| {
        let ((e1, n1), (e2, n2)) = (material[a], material[b]);
        1.0 / ((1.0 - n1 * n1) / e1 + (1.0 - n2 * n2) / e2)
    };
    for c in &deck.contacts {
        let body = &deck.bodies[c.body];
        let a = body.type_id as usize - 1;
        let (b, r_star, m_star) = match c.partner {
            Partner::Body(o) => {
                let other = &deck.bodies[o];
                (
                    other.type_id as usize - 1,
                    pair_radius(body.radius, other.radius),
                    reduced_mass(body.mass, other.mass),
                )
            }
            Partner::Wall(_) => (0, body.radius, body.mass),
        };
        let law = paper(c.law);
        let at = format!("{:?}", c.types);
        assert_eq!(c.model, "paper", "{at}");
        assert_eq!(law.exponent, 1.5, "{at}");
        assert_eq!(law.loss_coefficient, MILL_ETA[a][b], "{at}");
        assert_eq!(c.cor_entered, Some(restitution(MILL_ETA[a][b])), "{at}");
        assert!(relative(law.mass, m_star) < 1e-15, "{at}");
        assert!(
            relative(law.stiffness, 4.0 / 3.0 * e_star(a, b) * r_star.sqrt()) < 1e-14,
            "{at}"
        );
    }
    // Nine different η, three of them at the wall.
    let walls = deck
        .contacts
        .iter()
        .filter(|c| c.types[1] == TypeRef::Wall)
        .count();
    assert_eq!(walls, 3);
    // The impact carries the deck's own paper lines, and its setup the pair's η.
    let reader = CodeName::LiggghtsPaper.driver().deck().unwrap();
    let wall = deck.contacts.len() - 1;
    let impact = reader.render(&deck, wall, 2.0, 1000).unwrap();
    let text = &impact.input.text;
    for line in [
        "pair_style      gran model paper tangential history",
        "property/global lossCoefficient peratomtypepair 3",
    ] {
        assert!(text.contains(line), "{line}: {text}");
    }
    assert!(
        impact
            .input
            .text
            .contains("wall/gran model paper tangential history primitive type 1 zplane 0.0"),
        "{}",
        impact.input.text
    );
    assert_eq!(impact.setup.loss_coefficient, Some(0.40));
}

#[test]
fn a_model_paper_linear_deck_takes_kn_per_pair() {
    let (code, deck) = read(Path::new(ROD));
    assert_eq!(code, CodeName::LiggghtsPaper);
    assert_eq!(deck.contacts.len(), 2);
    let body = &deck.bodies[0];
    let pair = paper(deck.contacts[0].law);
    assert_eq!(
        (pair.stiffness, pair.exponent, pair.loss_coefficient),
        (5.654866776461627e8, 1.0, 0.35)
    );
    assert!(relative(pair.mass, body.mass / 2.0) < 1e-15);
    let wall = paper(deck.contacts[1].law);
    assert_eq!(
        (wall.stiffness, wall.exponent, wall.loss_coefficient),
        (4e8, 1.0, 0.6)
    );
    assert_eq!(wall.mass, body.mass);
    assert_eq!(deck.contacts[1].cor_entered, Some(restitution(0.6)));
}

/// The lines of a small `model paper` deck up to the pair style: two steel types.
fn paper_deck(eta: &str, pair_line: &str) -> String {
    format!(
        "units si\natom_style granular\nhard_particles yes\ncreate_box 2 box\n\
fix m1 all property/global youngsModulus peratomtype 2e11 2e11\n\
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3\n\
{eta}\
{pair_line}\npair_coeff * *\ncreate_atoms 1 single 0 0 0\nset atom 1 diameter 0.02 density 7800\ntimestep 1e-7\n"
    )
}

#[test]
fn a_bad_eta_or_a_setting_the_styles_lack_is_refused_with_its_line_and_value() {
    let eta = |values: &str| {
        format!("fix m3 all property/global lossCoefficient peratomtypepair 2 {values}\n")
    };
    let pair = "pair_style gran model paper";
    let cases: [(&str, String, &str); 7] = [
        (
            "η = 1",
            paper_deck(&eta("0.3 1 1 0.3"), pair),
            "in.paper:7: lossCoefficient 1 for the types 1 and 2; supported: 0 <= lossCoefficient < 1 for every type pair",
        ),
        (
            "η < 0",
            paper_deck(&eta("-0.1 0.3 0.3 0.3"), pair),
            "in.paper:7: lossCoefficient -0.1 for the types 1 and 1; supported: 0 <= lossCoefficient < 1 for every type pair",
        ),
        (
            "η missing",
            paper_deck("", pair),
            "model paper needs the material property lossCoefficient, which no fix property/global sets",
        ),
        (
            "η short of the pair",
            paper_deck(&eta(""), pair),
            "in.paper:7: lossCoefficient has no value for the types 1 and 1",
        ),
        (
            "η per type",
            paper_deck(
                "fix m3 all property/global lossCoefficient peratomtype 0.3 0.3\n",
                pair,
            ),
            "in.paper:7: lossCoefficient is not a table of type pairs",
        ),
        (
            "limitForce",
            paper_deck(
                &eta("0.3 0.3 0.3 0.3"),
                "pair_style gran model paper limitForce on",
            ),
            "in.paper:8: `limitForce` after model paper: the paper's styles take no settings",
        ),
        (
            "paper/linear without kt",
            paper_deck(
                &format!(
                    "fix k all property/global kn peratomtypepair 2 1e8 1e8 1e8 1e8\n{}",
                    eta("0.3 0.3 0.3 0.3")
                ),
                "pair_style gran model paper/linear",
            ),
            "model paper/linear needs the material property kt",
        ),
    ];
    for (what, text, expected) in cases {
        let (_d, path) = deck_file(&text);
        let error = read_deck(&path, None, &DeckOptions::default())
            .err()
            .unwrap_or_else(|| panic!("{what}: read"))
            .to_string();
        assert!(error.contains(expected), "{what}: {error}");
        assert!(error.contains("in.paper"), "{what}: {error}");
    }
}

#[test]
fn the_stock_build_asked_for_a_paper_deck_is_refused_in_one_line_with_exit_2() {
    for deck in [MILL, ROD] {
        let out = millimpact()
            .args(["deck", deck, "--code", "liggghts"])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{deck}");
        assert!(out.stdout.is_empty(), "{deck}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains(&format!("{deck}:"))
                && err.contains(
                    "with --code liggghts: the stock liggghts build lacks the paper's model"
                )
                && err.contains("supported: --code liggghts-paper"),
            "{err}"
        );
    }
    // Asked for by name, the paper build reads it too, as it reads a stock deck.
    let (code, _) = read_deck(
        &root().join(MILL),
        Some(CodeName::LiggghtsPaper),
        &DeckOptions::default(),
    )
    .unwrap();
    assert_eq!(code, CodeName::LiggghtsPaper);
    let (code, _) = read_deck(
        &root().join("examples/decks/liggghts-mill/in.mill"),
        None,
        &DeckOptions::default(),
    )
    .unwrap();
    assert_eq!(code, CodeName::Liggghts);
}

/// The recorded runs, checked again: the model difference 0, each COR within the step's band
/// of its closed form and below 1e-3 off it, the remainder at rounding.
#[test]
fn the_recorded_paper_runs_check_to_their_closed_forms() {
    for (deck_path, runs, pairs) in [
        (MILL, "paper_mill.runs.json", 9),
        (ROD, "paper_rod.runs.json", 2),
    ] {
        let (code, deck) = read(Path::new(deck_path));
        let runs: RecordedRuns = serde_json::from_str(
            &std::fs::read_to_string(root().join("tests/data/deck/liggghts-paper").join(runs))
                .unwrap(),
        )
        .unwrap();
        let report = check_deck(code, &deck, (vec![2.0], "given".into()), &runs).unwrap();
        assert_eq!(report.impacts.len(), pairs);
        for i in &report.impacts {
            let at = format!("{deck_path} {}", i.pair);
            assert_eq!(i.failure, None, "{at}");
            let closed = restitution(paper(i.law).loss_coefficient);
            assert_eq!(i.model_difference, Some(0.0), "{at}");
            let off = i.realised.cor - closed;
            let band = i
                .integration_band
                .min
                .abs()
                .max(i.integration_band.max.abs());
            assert!(
                off.abs() <= band + 1e-12 && off.abs() < 1e-3,
                "{at}: {off:e}, band {band:e}"
            );
            assert!(i.remainder.abs() < 1e-9, "{at}: {:e}", i.remainder);
        }
        // The JSON names the build that ran it.
        let json = serde_json::to_value(&report).unwrap();
        assert_eq!(json["code"], "liggghts-paper");
    }
}

/// Every format of the paper mill deck's check, from the runs recorded in liggghts-paper.
#[test]
fn snapshots_of_the_paper_mill_deck_in_every_format() {
    std::env::set_current_dir(root()).unwrap();
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string(
            root().join("tests/data/deck/liggghts-paper/paper_mill.runs.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(MILL), None, &DeckOptions::default()).unwrap();
    let report = check_deck(code, &deck, (vec![2.0], "given".into()), &runs).unwrap();
    for format in Format::ALL {
        let text = export(&report, format).unwrap();
        insta::assert_snapshot!(format!("deck_paper_mill_{format}"), text);
    }
}

/// A deck whose wall alone selects the paper's law runs in liggghts-paper too: its balls keep
/// their spring–dashpot (the paper build runs the stock models as the stock build does).
#[test]
fn a_paper_wall_under_a_hertz_pair_style_runs_both_laws_in_liggghts_paper() {
    let text = paper_deck(
        "fix m3 all property/global lossCoefficient peratomtypepair 2 0.35 0.35 0.35 0.35\n\
fix m4 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5\n",
        "pair_style gran model hertz\n\
fix w all wall/gran model paper primitive type 2 zplane 0.0",
    );
    let (_d, path) = deck_file(&text);
    let (code, deck) = read_deck(&path, None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::LiggghtsPaper);
    assert!(matches!(deck.contacts[0].law, CodeLaw::Dashpot(_)));
    assert_eq!(deck.contacts[0].cor_entered, Some(0.5));
    assert_eq!(paper(deck.contacts[1].law).loss_coefficient, 0.35);
    assert_eq!(deck.contacts[1].cor_entered, Some(restitution(0.35)));
    // Without the paper's wall the same deck stays the stock build's.
    let stock = text.replace(
        "fix w all wall/gran model paper primitive type 2 zplane 0.0\n",
        "",
    );
    let (_d, path) = deck_file(&stock);
    let (code, _) = read_deck(&path, None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Liggghts);
}
