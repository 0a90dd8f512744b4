//! `calibrate` cards checked live: each code, set up as its card says, realises the COR the
//! card predicts (one case per code, to bound the time).

use std::path::Path;

use millimpact::analysis::calibrate::card;
use millimpact::analysis::store::{ReferenceOptions, run_reference};
use millimpact::codes::CodeName;
use millimpact::model::case::Case;
use millimpact::model::exact;

#[test]
fn each_code_set_up_as_its_card_says_realises_the_predicted_cor() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let e = 0.8;
    for (code, name) in [
        (CodeName::Liggghts, "ball_plate"),
        (CodeName::Yade, "ball_ball"),
        (CodeName::Lammps, "rod_end"),
    ] {
        let case = Case::load(&root.join("cases").join(format!("{name}.toml")))
            .unwrap()
            .with_loss_coefficient(exact::loss_coefficient(e));
        let card = card(code, &case, None, 1e-3).unwrap();
        assert!(card.unsupported.is_none(), "{code}: {:?}", card.unsupported);
        assert!(!card.settings.is_empty(), "{code}: a card has settings");
        let run = run_reference(code, &case, &ReferenceOptions::default()).unwrap();
        for line in &card.settings {
            assert!(
                run.input.contains(line.as_str()),
                "{code}: the run's input has `{line}`"
            );
        }
        // The card's step is the one the run is given: the same number, not a near one.
        #[allow(clippy::float_cmp)]
        {
            assert_eq!(run.timestep, card.timestep, "{code}");
        }
        eprintln!(
            "{code} on {name}: card {:.9} [{:.9}, {:.9}], run {:.9}",
            card.realised_cor, card.realised_band.min, card.realised_band.max, run.cor
        );
        let slack = 1e-9;
        assert!(
            (run.cor - card.realised_cor).abs() < 1e-7,
            "{code} on {name}: realised {} vs card {}",
            run.cor,
            card.realised_cor
        );
        assert!(
            run.cor >= card.realised_band.min - slack && run.cor <= card.realised_band.max + slack,
            "{code}: {} outside {:?}",
            run.cor,
            card.realised_band
        );
        assert!((run.cor - e).abs() < 1e-3 * e, "{code}: {} vs {e}", run.cor);
    }
}

/// The card's η and energies follow the closed forms, and its recommended step is the
/// largest of the ladder that keeps the COR within the tolerance: the next larger one does not.
#[test]
fn a_cards_step_is_the_largest_within_the_tolerance() {
    use millimpact::analysis::calibrate::{CalibrateOptions, calibrate};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let case = Case::load(&root.join("cases/rod_end.toml")).unwrap();
    let tolerance = 1e-4;
    let c = calibrate(
        &case,
        &CalibrateOptions {
            restitutions: vec![0.8, 0.85],
            timestep: None,
            tolerance,
        },
    )
    .unwrap();
    let law = case.law();
    let energy = 0.5 * law.mass * case.impact_velocity.powi(2);
    for t in &c.targets {
        let e = t.restitution;
        assert!((exact::restitution(t.loss_coefficient) - e).abs() < 1e-15);
        assert!((t.absorbed_energy - energy * (1.0 - e * e)).abs() < 1e-12 * energy);
        for card_at in &t.cards {
            let h = card_at.timestep_for_tolerance.expect("a step is found");
            let at = case.with_loss_coefficient(t.loss_coefficient);
            let fine = card(card_at.code, &at, Some(h), tolerance).unwrap();
            let coarse = card(card_at.code, &at, Some(2.0 * h), tolerance).unwrap();
            let off = |r: &millimpact::analysis::compare::phase::Range| {
                (r.min - e).abs().max((r.max - e).abs()) / e
            };
            assert!(off(&fine.realised_band) <= tolerance, "{}", card_at.code);
            assert!(off(&coarse.realised_band) > tolerance, "{}", card_at.code);
        }
    }
}

#[test]
fn a_cor_outside_zero_to_one_is_refused_in_one_line_with_exit_2() {
    for args in [
        vec!["calibrate", "--cor", "1.5"],
        vec!["calibrate", "--cor-range", "0.85:0.8"],
        vec!["calibrate", "--cor", "0.8", "--tolerance", "-1"],
    ] {
        let out = assert_cmd::Command::cargo_bin("millimpact")
            .unwrap()
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(&args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(out.stdout.is_empty(), "{args:?}: no partial output");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
    }
}
