//! `millimpact deck` reading a LAMMPS granular deck with the build's fallback conventions (no
//! code runs): the example's bodies, wall and laws, and the pair of two bead types that only
//! have lines of their own, mixed as each build's source mixes it.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use common::deck::{GRANULAR, MIXED, deck_files, hide_codes, read_with, relative, two_types};
use common::root;
use millimpact::analysis::deck::{RecordedRuns, check_deck, read_deck};
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, TypeRef};

#[test]
fn the_lammps_deck_is_read_with_the_builds_conventions() {
    hide_codes();
    let (code, deck) = read_deck(&root().join(GRANULAR), None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Lammps);
    let sizes: Vec<(u32, f64, f64, Option<f64>)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density, b.youngs_modulus))
        .collect();
    assert_eq!(
        sizes,
        [
            (1, 0.005, 2500.0, Some(6.3e10)),
            (2, 0.0025, 2500.0, Some(6.3e10))
        ]
    );
    assert_eq!(
        deck.transplant.walls,
        [
            "fix floor all wall/gran granular hertz/material 63000000000 0.7 0.22 damping tsuji tangential mindlin NULL 1.0 0.5 limit_damping zplane 0 NULL"
        ]
    );
    // The ball on the floor: the 2021 wall's E/(2(1−ν)), R* = R, m* = m, tsuji's α(e_in), clamped.
    let wall = &deck.contacts[3];
    let body = &deck.bodies[0];
    let k = 4.0 / 3.0 * 6.3e10 / (2.0 * (1.0 - 0.22)) * 0.005f64.sqrt();
    let alpha = millimpact::codes::lammps::tsuji_alpha(0.7);
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").stiffness,
            k
        ) < 1e-14
    );
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").damping,
            alpha * (body.mass * k).sqrt()
        ) < 1e-14
    );
    assert!(
        wall.law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
    );
    assert_eq!(wall.cor_entered, Some(0.7));
    // Two beads: the pair's E/(2(1−ν²)), not clamped.
    let pair = &deck.contacts[0];
    let k = 4.0 / 3.0 * 6.3e10 / (2.0 * (1.0 - 0.22 * 0.22)) * 0.0025f64.sqrt();
    assert!(
        relative(
            pair.law.dashpot().expect("a spring–dashpot law").stiffness,
            k
        ) < 1e-14
            && !pair
                .law
                .dashpot()
                .expect("a spring–dashpot law")
                .clamp_attractive
    );
}

const MIXED_HERTZ: &str = "tests/data/deck/lammps-mixed-hertz.in";

/// tsuji's fit as both builds apply it (their probes measure no √2), evaluated at run time as
/// the reader evaluates it: near e = 0.9 its terms (up to 18) cancel to 0.05, and
/// the compiler's folding of a constant argument rounds them otherwise (by 2e-14).
fn poly(e: f64) -> f64 {
    millimpact::codes::lammps::tsuji_alpha(std::hint::black_box(e))
}

/// The glass–steel pair of the mixed example, as each build mixes it from `pair_coeff 1 1`
/// and `2 2`: the 2025 build Hertz with the two materials' E* and tsuji's α of √(e₁e₂), the
/// 2021 build a linear spring of √(k₁k₂) and a dashpot of √(α₁α₂), whatever the lines say.
#[test]
fn each_build_mixes_the_pair_of_two_bead_types_as_its_source_does() {
    let path = root().join(MIXED);
    let (e1, nu1, c1, e2, nu2, c2): (f64, f64, f64, f64, f64, f64) =
        (6.3e10, 0.22, 0.9, 2.0e11, 0.3, 0.6);
    let new = read_with(CodeName::Lammps2025, &path);
    let (glass, steel) = (&new.bodies[0], &new.bodies[1]);
    let r: f64 = glass.radius * steel.radius / (glass.radius + steel.radius);
    let m = glass.mass * steel.mass / (glass.mass + steel.mass);
    let types: Vec<[TypeRef; 2]> = new.contacts.iter().map(|c| c.types).collect();
    assert_eq!(types[1], [TypeRef::Type(1), TypeRef::Type(2)]);
    let pair = &new.contacts[1];
    let e_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
    let k = 4.0 / 3.0 * e_star * r.sqrt();
    let alpha = poly((c1 * c2).sqrt());
    let law = pair.law.dashpot().copied().expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k) < 1e-14, "{} {k}", law.stiffness);
    assert!(relative(law.damping, alpha * (m * k).sqrt()) < 1e-14);
    assert!(relative(law.mass, m) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.5, 0.25));
    assert!(!law.clamp_attractive);
    // The damping is converted after mixing: √(α₁α₂) would be 25 % weaker.
    assert!(alpha / (poly(c1) * poly(c2)).sqrt() > 1.3);
    // No COR is entered for a mixed pair; its lines are both types' own.
    assert_eq!(pair.cor_entered, None);
    let lines: Vec<usize> = pair
        .lines
        .iter()
        .map(|l| match l {
            millimpact::codes::deck::DeckSource::Line(l) => l.line,
            other => panic!("{other}"),
        })
        .collect();
    assert_eq!(lines, [29, 30]);
    assert!(
        pair.traps[0].starts_with("mixed: no pair_coeff sets the types 1 and 2"),
        "{:?}",
        pair.traps
    );
    assert!(
        pair.traps.iter().any(|t| t.starts_with(
            "COR of the mixed pair: none entered (the lines have e = 0.9 in 1 1, e = 0.6 in 2 2)"
        )),
        "{:?}",
        pair.traps
    );
    // The types' own pairs are their own lines.
    assert_eq!(new.contacts[0].cor_entered, Some(c1));
    assert_eq!(new.contacts[2].cor_entered, Some(c2));

    let old = read_with(CodeName::Lammps, &path);
    let pair = &old.contacts[1];
    let stored = |e: f64, nu: f64| 4.0 / 3.0 * e / (2.0 * (1.0 - nu * nu));
    let k = (stored(e1, nu1) * stored(e2, nu2)).sqrt();
    let d = (poly(c1) * poly(c2)).sqrt();
    let law = pair.law.dashpot().copied().expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k) < 1e-14, "{} {k}", law.stiffness);
    assert!(relative(law.damping, d) < 1e-14, "{} {d}", law.damping);
    assert_eq!((law.exponent, law.damping_exponent), (1.0, 0.0));
    assert!(!law.clamp_attractive);
    assert_eq!(pair.cor_entered, None);
    assert!(
        pair.traps
            .iter()
            .any(|t| t.starts_with("mixed pair's model left unset")),
        "{:?}",
        pair.traps
    );
    // The own pairs read the same in both builds.
    assert_eq!(old.contacts[0].law, new.contacts[0].law);
}

/// hertz with damping velocity: the 2025 build keeps the form with √(k₁k₂) and √(d₁d₂); the
/// 2021 build runs those numbers as hooke.
#[test]
fn a_hertz_pair_is_mixed_whole_in_2025_and_as_hooke_in_2021() {
    let path = root().join(MIXED_HERTZ);
    let new = read_with(CodeName::Lammps2025, &path);
    let (a, b) = (&new.bodies[0], &new.bodies[1]);
    let r: f64 = a.radius * b.radius / (a.radius + b.radius);
    let k = (4e10f64 * 1.3e11).sqrt();
    let d = 3f64.sqrt();
    let law = new.contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k * r.sqrt()) < 1e-14);
    assert!(relative(law.damping, d) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.5, 0.0));
    // limit_damping of type 2's line: on in the 2025 pair, not in the 2021 one.
    assert!(law.clamp_attractive);
    let law = read_with(CodeName::Lammps, &path).contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k) < 1e-14);
    assert!(relative(law.damping, d) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.0, 0.0));
    assert!(!law.clamp_attractive);
}

/// limit_damping on one type's line: the 2025 pair takes it, the 2021 pair does not; and
/// coeff_restitution mixed in 2025 realises the geometric mean of the two e's exactly.
#[test]
fn limit_damping_and_coeff_restitution_reach_the_mixed_pair_as_each_build_has_it() {
    let tsuji = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential linear_nohistory 0 0 limit_damping\n\
pair_coeff 2 2 hertz/material 2e11 0.6 0.3 damping tsuji tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.ld", &tsuji)]);
    let new = read_with(CodeName::Lammps2025, &path);
    assert!(
        new.contacts[1]
            .law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
    );
    assert!(
        new.contacts[1]
            .traps
            .iter()
            .any(|t| t.starts_with("limit_damping is on in pair_coeff 1 1 only"))
    );
    let old = read_with(CodeName::Lammps, &path);
    assert!(
        !old.contacts[1]
            .law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
    );
    assert!(
        old.contacts[1]
            .traps
            .iter()
            .any(|t| t.starts_with("limit_damping of the lines does not reach the mixed pair"))
    );
    // The own pair 1 1 keeps its clamp in both.
    assert!(
        new.contacts[0]
            .law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
            && old.contacts[0]
                .law
                .dashpot()
                .expect("a spring–dashpot law")
                .clamp_attractive
    );

    let restitution = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping coeff_restitution tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz/material 2e11 0.4 0.3 damping coeff_restitution tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.cr", &restitution)]);
    let law = read_with(CodeName::Lammps2025, &path).contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    let cor = millimpact::solve::dashpot::accurate_metrics(&law, 2.0, 1e-12)
        .unwrap()
        .cor;
    assert!((cor - 0.6).abs() < 1e-9, "{cor}");
}

/// A mixed pair the 2021 build damps beyond critical (viscoelastic numbers run as a velocity
/// dashpot) never separates: its row says so, and no run is started for it.
#[test]
fn a_mixed_pair_that_never_separates_is_reported_not_run() {
    let sticky = two_types(
        "pair_coeff 1 1 hertz 4e10 5e8 damping viscoelastic tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz 1.3e11 8e8 damping viscoelastic tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.sticky", &sticky)]);
    let deck = read_with(CodeName::Lammps, &path);
    let zeta = deck.contacts[1]
        .law
        .dashpot()
        .expect("a spring–dashpot law")
        .never_separates()
        .unwrap();
    assert!(zeta > 1e5, "{zeta}");
    assert!(
        deck.contacts[1]
            .traps
            .iter()
            .any(|t| t.contains("the bodies never separate, COR 0")),
        "{:?}",
        deck.contacts[1].traps
    );
    let report = check_deck(
        CodeName::Lammps,
        &deck,
        (vec![2.0], "given".into()),
        &RecordedRuns::default(),
    )
    .unwrap();
    let row = &report.impacts[1];
    assert_eq!(row.pair, "1–2");
    assert_eq!(row.cor_law, 0.0);
    assert!(row.realised.cor.is_nan() && row.steps == 0);
    assert!(row.failure.as_deref().unwrap().starts_with("not run: the law these lines make the code integrate is a linear spring with a dashpot of damping ratio"), "{:?}", row.failure);
    // The own pairs went to the runner (here: none recorded).
    assert!(
        report.impacts[0]
            .failure
            .as_deref()
            .unwrap()
            .contains("no recorded run")
    );
    // In the 2025 build the pair stays viscoelastic Hertz, and separates.
    let law = read_with(CodeName::Lammps2025, &path).contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert_eq!(law.never_separates(), None);
}

/// `synchronized_verlet` is a flag and `heat area K` a model with one coefficient, as LAMMPS
/// reads them: a line that ends in either reads, with its contact model whole, and a line cut
/// short after `heat` ends the model at the line's end rather than past it.
#[test]
fn the_heat_model_and_synchronized_verlet_are_read_as_lammps_reads_them() {
    let dir = tempfile::tempdir().unwrap();
    let normal = "pair_coeff * * hertz/material 6.3e10 0.7 0.22 damping tsuji tangential linear_nohistory 0 0";
    for tail in [
        "synchronized_verlet",
        "heat area 5.0 synchronized_verlet",
        "synchronized_verlet heat none",
        "heat radius 2.0",
    ] {
        let path = dir.path().join("in.sync");
        std::fs::write(&path, two_types(&format!("{normal} {tail}\n"))).unwrap();
        let deck = read_with(CodeName::Lammps2025, &path);
        assert_eq!(deck.contacts.len(), 3, "{tail}");
        assert!(
            deck.transplant.common.iter().any(|l| l.ends_with(tail)),
            "{tail}: {:?}",
            deck.transplant.common
        );
    }
    let path = dir.path().join("in.cut");
    std::fs::write(&path, two_types(&format!("{normal} heat\n"))).unwrap();
    hide_codes();
    let _ = read_deck(&path, Some(CodeName::Lammps2025), &DeckOptions::default());
}
