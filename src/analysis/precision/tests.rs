//! The observed orders of the methods, the log-slope fit behind them, the sweeps' ranges, and
//! the refusal of a method with no knob.

use std::path::Path;

use super::*;

/// A shipped case, read as the command line reads it.
fn shipped(name: &str) -> Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cases")
        .join(format!("{name}.toml"));
    Case::load(&path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn rk4_event_converges_at_order_4_in_contact_time_and_5_in_cor_and_peak() {
    for name in ["ball_plate", "rod_end"] {
        let points: Vec<WorkPrecisionPoint> =
            method_sweep(&shipped(name), Method::Rk4Event, 1).unwrap();
        let q = observed_orders(&points);
        let time = q.contact_time.unwrap();
        assert!(
            (time - 4.0).abs() <= 0.3,
            "{name}: contact-time order {time}"
        );
        // Superconvergence: COR and peak come from the energy, whose error is O(h^5).
        let cor = q.cor.unwrap();
        let peak = q.peak_deformation.unwrap();
        assert!((cor - 5.0).abs() <= 0.5, "{name}: COR order {cor}");
        assert!((peak - 5.0).abs() <= 0.5, "{name}: peak order {peak}");
    }
}

#[test]
fn paper_rk4_and_verlet_are_first_order_in_contact_time() {
    let c = shipped("ball_plate");
    for method in [Method::Rk4, Method::Verlet] {
        let points = method_sweep(&c, method, 1).unwrap();
        // The bound on a staircase error: its upper envelope.
        let envelope = envelope_orders(&points).contact_time.unwrap();
        assert!(
            (envelope - 1.0).abs() <= 0.3,
            "{}: contact-time envelope order {envelope}",
            method.name()
        );
    }
}

#[test]
fn log_slope_recovers_a_power_law() {
    let pairs: Vec<(f64, f64)> = (1..8)
        .map(|k| (1.0 / k as f64, 3.0 / (k as f64).powi(4)))
        .collect();
    let slope = log_slope(&pairs).unwrap();
    assert!((slope - 4.0).abs() < 1e-12);
    assert_eq!(log_slope(&pairs[..2]), None);
}

#[test]
fn sweeps_span_the_documented_ranges() {
    let n = steps_per_period_sweep();
    assert_eq!((n[0], *n.last().unwrap()), (8, 20000));
    let r = rtol_sweep();
    assert_eq!((r[0], *r.last().unwrap()), (1e-3, 1e-14));
    let c = code_steps_sweep();
    assert_eq!(c.len(), 5);
    assert!(c[0] >= 15 && *c.last().unwrap() <= 2500);
}

#[test]
fn a_method_without_a_knob_has_no_precision_sweep() {
    let case = shipped("ball_plate");
    match method_sweep(&case, Method::Exact, 1) {
        Err(PrecisionError::NoKnob { method }) => assert_eq!(method, Method::Exact),
        other => panic!("expected NoKnob, got {other:?}"),
    }
}
