//! The typed laws of the benchmark's COR chart measured in the codes themselves, at Chung &
//! Ooi's test-3 alumina: each code given a COR directly (no driver compensating) realises what
//! `TypedLaw::cor` says its law realises, within its step at about 1,000 steps per contact.

mod common;

use millimpact::analysis::benchmark::cor_chart::TypedLaw;
use serde_json::Value;

/// How far a run at about 1,000 steps per contact may lie from its law's exact COR (the step's
/// offset is below 2e-5 in every such run here).
const STEP: f64 = 1e-4;

/// `millimpact ARGS --format json`, required to succeed, as JSON.
fn json(args: &[&str]) -> Value {
    let output = common::millimpact()
        .args(args)
        .args(["--format", "json"])
        .output()
        .unwrap();
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).unwrap()
}

/// Every impact of a deck's check realises `law` with `typed` given, and the check's own model
/// difference says the same.
fn deck_realises(deck: &str, law: TypedLaw, typed: f64) {
    let expected = law.cor(typed).unwrap();
    let report = json(&["deck", deck, "--impact-velocity", "3.9"]);
    let impacts = report["impacts"].as_array().unwrap();
    assert_eq!(
        impacts.len(),
        2,
        "{deck}: a bead pair and a bead on the wall"
    );
    for impact in impacts {
        let realised = impact["cor_realised"].as_f64().unwrap();
        assert!(
            (realised - expected).abs() < STEP,
            "{deck} {}: {realised} against {expected}",
            impact["pair"]
        );
        let model = impact["model_difference"].as_f64().unwrap();
        assert!(
            (typed + model - expected).abs() < 1e-6,
            "{deck}: model {model}"
        );
    }
}

/// YADE with `en = 0.95` typed: Thornton's fit realises 0.9481, 1.9e-3 below.
#[test]
#[ignore = "live: runs YADE on tests/data/deck/yade/alumina-thornton.py"]
fn yade_realises_thorntons_fit_with_the_cor_typed() {
    assert!((TypedLaw::ThorntonClamped.cor(0.95).unwrap() - 0.948082).abs() < 1e-6);
    deck_realises(
        "tests/data/deck/yade/alumina-thornton.py",
        TypedLaw::ThorntonClamped,
        0.95,
    );
}

/// LAMMPS 2021 with `damping tsuji` and 0.5 typed: the fit without its √2 realises 0.6161.
#[test]
#[ignore = "live: runs LAMMPS (the Debian build) on tests/data/deck/lammps-tsuji-alumina.in"]
fn lammps_realises_tsujis_fit_without_its_root_two() {
    assert!((TypedLaw::Tsuji.cor(0.5).unwrap() - 0.616076).abs() < 1e-6);
    deck_realises(
        "tests/data/deck/lammps-tsuji-alumina.in",
        TypedLaw::Tsuji,
        0.5,
    );
}

/// LIGGGHTS with `limitForce on` and 0.5 asked (η = 0.6): the clamped law realises 0.5503.
#[test]
#[ignore = "live: runs LIGGGHTS on cases/benchmarks/chung_ooi_3_alumina.toml"]
fn liggghts_realises_the_clamped_law_with_limit_force_on() {
    let expected = TypedLaw::DampedHertzClamped.cor(0.5).unwrap();
    assert!((expected - 0.550283).abs() < 1e-6);
    let record = json(&[
        "reference",
        "--code",
        "liggghts",
        "cases/benchmarks/chung_ooi_3_alumina.toml",
        "--loss-coefficient",
        "0.6",
        "--clamp",
        "--steps-per-contact",
        "1000",
    ]);
    assert_eq!(record["target_restitution"].as_f64(), Some(0.5));
    let realised = record["cor"].as_f64().unwrap();
    assert!(
        (realised - expected).abs() < STEP,
        "{realised} against {expected}"
    );
    let law = record["law_exact"]["cor"].as_f64().unwrap();
    assert!((law - expected).abs() < 1e-8, "{law} against {expected}");
}
