//! Measure the COR error bounds of the methods that have one (`CorErrorBound` in
//! `src/solve/method.rs`): for each method, at resolutions across its measured range, the
//! largest relative COR error over 1001 loss coefficients on [0, 0.9999] and both exponents
//! (1: the rod, 1.5: the balls), beside the stored bound there.
//!
//! `cargo run --release --example cor_error_bounds`

use millimpact::analysis::precision::choice::{bound_of, largest_cor_error};
use millimpact::solve::{Knob, Method};

fn main() {
    let etas: Vec<f64> = (0..=1000).map(|i| 0.9999 * i as f64 / 1000.0).collect();
    let exponents = [1.0, 1.5];
    println!("| method | knob | largest COR error | bound | error / bound |");
    println!("|---|---|---|---|---|");
    for &method in Method::ALL {
        let Some(bound) = bound_of(method) else {
            continue;
        };
        let knob = method.descriptor().knob;
        // Twenty values spaced evenly in log between the coarsest and finest.
        let values: Vec<f64> = (0..=20)
            .map(|k| {
                let f = f64::from(k) / 20.0;
                let v = bound.coarsest.powf(1.0 - f) * bound.finest.powf(f);
                if knob == Knob::StepsPerPeriod {
                    v.round()
                } else {
                    v
                }
            })
            .collect();
        for value in values {
            let worst = largest_cor_error(method, value, &etas, &exponents);
            let limit = bound.at(knob, value);
            let knob_text = if knob == Knob::StepsPerPeriod {
                format!("{value} /period")
            } else {
                format!("rtol {value:.2e}")
            };
            println!(
                "| {method} | {knob_text} | {worst:.3e} | {limit:.3e} | {:.3} |",
                worst / limit
            );
        }
    }
}
