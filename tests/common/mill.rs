//! The mill's recorded runs and a small plan, shared by the mill's tests.

use std::path::Path;
use std::time::Duration;

use millimpact::analysis::mill::{MillOptions, MillReport, report_from_folders};
use millimpact::codes::liggghts::mill::{MillDeck, MillLaw, MillPlan};

use super::root;

/// The shipped example mill, relative to the crate's root.
pub const EXAMPLE: &str = "examples/mill/in.mill";

/// What the recorded runs were run with: `millimpact mill examples/mill/in.mill --time 0.05
/// --spectra-time 0.0003 --contact-every 10 --keep DIR`.
pub fn recorded_options() -> MillOptions {
    MillOptions {
        time: Some(0.05),
        spectra_time: Some(0.0003),
        contact_every: 10,
        timeout: Duration::from_secs(60),
        ..MillOptions::defaults()
    }
}

/// The comparison of the runs recorded in `tests/data/mill/` (in the crate's root as the
/// working folder, as the deck's paths are relative to it).
pub fn recorded() -> MillReport {
    std::env::set_current_dir(root()).unwrap();
    let deck = MillDeck::read(Path::new(EXAMPLE)).unwrap();
    let data = root().join("tests/data/mill");
    report_from_folders(
        &deck,
        &recorded_options(),
        &[
            (
                MillLaw::Hertz,
                0,
                "liggghts".into(),
                data.join("hertz-seed0"),
            ),
            (
                MillLaw::Paper,
                0,
                "liggghts-paper".into(),
                data.join("paper-seed0"),
            ),
        ],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// A plan of 1000 rotation steps, the last 200 recorded every 5.
pub fn small_plan() -> MillPlan {
    MillPlan {
        rotation_steps: 1000,
        spectra_steps: 200,
        contact_every: 5,
        print_every: 10,
        position_every: 100,
        seed: 0,
    }
}
