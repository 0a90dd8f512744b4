//! `calibrate` cards checked live: each code, set up as its card says, realises the COR the
//! card predicts (one case per code, to bound the time).

use std::path::Path;

use millimpact::analysis::calibrate::card;
use millimpact::analysis::store::{ReferenceOptions, run_reference};
use millimpact::codes::CodeName;
use millimpact::model::case::Case;
use millimpact::model::exact;

mod common;

#[test]
#[ignore = "live: runs LIGGGHTS, YADE and LAMMPS (bash scripts/test.sh)"]
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
            card.realised_cor, card.realised_band.min, card.realised_band.max, run.figures.cor
        );
        let slack = 1e-9;
        assert!(
            (run.figures.cor - card.realised_cor).abs() < 1e-7,
            "{code} on {name}: realised {} vs card {}",
            run.figures.cor,
            card.realised_cor
        );
        assert!(
            run.figures.cor >= card.realised_band.min - slack
                && run.figures.cor <= card.realised_band.max + slack,
            "{code}: {} outside {:?}",
            run.figures.cor,
            card.realised_band
        );
        assert!(
            (run.figures.cor - e).abs() < 1e-3 * e,
            "{code}: {} vs {e}",
            run.figures.cor
        );
    }
}

/// `calibrate`'s steps with the installed LAMMPS builds probed for the cards (the fast tier
/// checks them without the codes: tests/calibrate_steps.rs).
#[test]
#[ignore = "live: probes LAMMPS and LAMMPS 2025 (bash scripts/test.sh)"]
fn a_cards_step_is_the_largest_within_the_tolerance() {
    common::calibrate::a_cards_step_is_the_largest_within_the_tolerance();
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
