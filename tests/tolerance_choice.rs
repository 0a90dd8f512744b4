//! Accuracy as the input: the measured COR error bounds hold, and the method and resolution
//! chosen for a tolerance meet it on every scene at every loss coefficient, extremes included.

use std::path::Path;

use millimpact::analysis::precision::choice::{
    MARGIN, bound_of, choose, largest_cor_error, smallest_tolerance,
};
use millimpact::analysis::run::{IntegrationOptions, run_case};
use millimpact::analysis::source::Resolution;
use millimpact::model::case::Case;
use millimpact::solve::{Knob, Method};

fn etas(count: usize) -> Vec<f64> {
    let mut v: Vec<f64> = (0..count)
        .map(|i| 0.9999 * i as f64 / (count - 1) as f64)
        .collect();
    // The extremes and the tail where rk4-event's error is largest.
    v.extend([0.999, 0.9995, 0.99999, 1.0 - 1e-8]);
    v
}

/// Every measured point lies under its bound (without the margin), on a grid of resolutions
/// other than the one the bound was measured on.
#[test]
fn the_bounds_hold_across_their_range() {
    let etas = etas(301);
    let mut checked = Vec::new();
    for &method in Method::ALL {
        let Some(bound) = bound_of(method) else {
            continue;
        };
        checked.push(method);
        let knob = method.descriptor().knob;
        for k in 0..=16 {
            let f = (f64::from(k) + 0.37) / 17.0;
            let mut value = bound.coarsest.powf(1.0 - f) * bound.finest.powf(f);
            if knob == Knob::StepsPerPeriod {
                value = value.round();
            }
            let worst = largest_cor_error(method, value, &etas, &[1.0, 1.5]);
            let limit = bound.at(knob, value);
            assert!(
                worst <= limit,
                "{method} at {value}: COR error {worst:e} above its bound {limit:e}"
            );
        }
    }
    // The tolerance choice picks among the methods with a bound: both must have been checked.
    assert!(
        checked.contains(&Method::Rk4Event) && checked.contains(&Method::Dopri5),
        "methods with a measured bound: {checked:?}"
    );
}

/// For each scene's case and tolerances from 1e-3 to the smallest allowed, the chosen method
/// and resolution run through `run_case` (what a sweep runs) meet the tolerance at every η.
#[test]
fn the_choice_meets_the_tolerance_on_every_scene() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
    let cases: Vec<Case> = ["ball_plate", "ball_ball", "rod_end"]
        .iter()
        .map(|n| Case::load(&root.join(format!("{n}.toml"))).unwrap())
        .collect();
    let mut tolerances = vec![
        1e-3, 1e-5, 1e-7, 1e-8, 1e-9, 1e-10, 3e-11, 1e-11, 1e-12, 1e-13,
    ];
    tolerances.push(smallest_tolerance());
    let grid = etas(401);
    for tolerance in tolerances {
        let choice = choose(tolerance).unwrap();
        assert!(choice.bound * MARGIN <= tolerance);
        let options = IntegrationOptions {
            method: choice.method,
            steps_per_period: Resolution::steps_per_period(Some(choice.resolution)),
            rtol: Resolution::rtol(Some(choice.resolution)),
            ..IntegrationOptions::default()
        };
        for case in &cases {
            for &eta in &grid {
                let at = case.with_loss_coefficient(eta);
                let settings = options.settings(&at, false).unwrap();
                let (report, _) = run_case(&at, &settings).unwrap();
                assert!(
                    report.error.cor.abs() <= tolerance,
                    "{}: η = {eta}, tolerance {tolerance:e}: {} gives COR error {:e}",
                    case.name,
                    choice.sentence(),
                    report.error.cor
                );
            }
        }
    }
}

/// At 1e-10 the choice is rk4-event a little above the 458 steps per period the worst η needs
/// (the margin), and dopri5 is the runner-up at more work.
#[test]
fn at_1e_10_rk4_event_is_chosen() {
    let choice = choose(1e-10).unwrap();
    assert_eq!(choice.method, Method::Rk4Event);
    let Resolution::StepsPerPeriod(n) = choice.resolution else {
        panic!("{:?}", choice.resolution)
    };
    assert!((458..=520).contains(&n), "{n}");
    let (runner, _, ratio) = choice.runner_up.unwrap();
    assert_eq!(runner, Method::Dopri5);
    assert!(ratio > 1.0);
    assert!(
        choice
            .sentence()
            .contains(&format!("rk4-event at {n} steps per period"))
    );
}
