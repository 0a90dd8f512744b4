//! The check of `calibrate`'s recommended steps, run by the fast tier as a machine without the
//! DEM codes runs it (tests/calibrate_steps.rs) and by the live tier with the installed builds
//! probed (tests/calibrate_live.rs).

use millimpact::analysis::calibrate::{CalibrateOptions, calibrate, card};
use millimpact::model::exact;

/// The card's η and energies follow the closed forms, and its recommended step is that of the
/// fewest steps per contact that keep the COR within the tolerance: one step fewer does not.
pub fn a_cards_step_is_the_largest_within_the_tolerance() {
    let case = super::shipped("rod_end");
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
            let n = card_at.steps_per_contact.expect("a count is found");
            let tc = millimpact::codes::elastic_contact_time(&at);
            let coarse = card(card_at.code, &at, Some(tc / f64::from(n - 1)), tolerance).unwrap();
            let off = |r: &millimpact::analysis::compare::phase::Range| {
                (r.min - e).abs().max((r.max - e).abs()) / e
            };
            assert!(off(&fine.realised_band) <= tolerance, "{}", card_at.code);
            assert!(off(&coarse.realised_band) > tolerance, "{}", card_at.code);
        }
    }
}
