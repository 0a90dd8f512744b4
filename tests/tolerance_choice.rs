//! Accuracy as the input: the measured COR error bounds hold across their range, extremes of
//! the loss coefficient included. That the method and resolution chosen for a tolerance meet it
//! on every scene is a unit test of `analysis::precision::choice`.

use millimpact::analysis::precision::choice::{bound_of, largest_cor_error};
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
