//! `millimpact stability`: the extreme-case grid and the fixed-step stability limits.

mod common;

use common::{millimpact, shipped};
use millimpact::analysis::stability::{self, ETA_MAX};
use millimpact::model::case::Case;
use millimpact::model::case::ContactKind;
use millimpact::solve::paper::{self, Settings};
use millimpact::solve::{Method, SolveError};
use serde_json::Value;

/// The whole grid through the command line: exit 0, the documented shape, every rk4-event and
/// dopri5 case within 1e-9, every run finite and bounded, and COR → 0 as η → 1.
#[test]
fn every_grid_case_passes() {
    let out = millimpact()
        .args(["stability", "--format", "json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let doc: Value = serde_json::from_slice(&out).unwrap();
    let cases = doc["cases"].as_array().unwrap();
    assert!(cases.len() >= 4 * 200, "{} runs", cases.len());
    for c in cases {
        let method = c["method"].as_str().unwrap();
        let pass = c["pass"].as_bool().unwrap();
        assert!(pass, "{method} fails {}", c["case"]);
        assert!(c["finite"].as_bool().unwrap() && c["bounded_work"].as_bool().unwrap());
        if method == "rk4-event" || method == "dopri5" {
            for key in ["cor_error", "peak_deformation_error", "contact_time_error"] {
                let e = c[key].as_f64().unwrap();
                assert!(e <= 1e-9, "{method} {}: {key} = {e}", c["case"]);
            }
            let cor = c["cor"].as_f64().unwrap();
            assert!((0.0..=1.0).contains(&cor));
        }
        if c["loss_coefficient"].as_f64().unwrap() == ETA_MAX {
            // e(0.999999) = 7.07e-4; even verlet's wrong-signed half step stays below 1e-2.
            let cor = c["cor"].as_f64().unwrap();
            assert!(cor < 1e-2, "{method} {}: COR {cor} at η → 1", c["case"]);
        }
    }
    // The grid spans what it claims.
    let span = |key: &str| {
        let v: Vec<f64> = cases.iter().filter_map(|c| c[key].as_f64()).collect();
        (
            v.iter().cloned().fold(f64::MAX, f64::min),
            v.iter().cloned().fold(f64::MIN, f64::max),
        )
    };
    assert_eq!(span("youngs_modulus"), (1e5, 1e15));
    assert_eq!(span("impact_velocity"), (1e-8, 1e3));
    assert_eq!(span("loss_coefficient"), (0.0, ETA_MAX));
    assert_eq!(span("aspect_ratio"), (1.0, 1000.0));
    assert!((span("mass_ratio").0 / 1e-6 - 1.0).abs() < 1e-9);
    let size = span("size");
    assert!(size.0 <= 1e-6 && size.1 >= 1.0);
}

fn bilateral_rod() -> Case {
    let mut case = shipped("rod_end");
    case = case.with_loss_coefficient(0.0);
    case.contact = ContactKind::Bilateral;
    case
}

/// Just below the limit the solver runs and the oscillation stays bounded over 100 periods;
/// just above it the solver refuses with `Unstable` and the method's own step map grows.
// The limit is carried through the error unchanged.
#[allow(clippy::float_cmp)]
#[test]
fn stability_limit_just_below_and_just_above() {
    let case = bilateral_rod();
    let law = case.law();
    let omega = paper::angular_frequency(&law, case.impact_velocity);
    for (method, limit) in [(Method::Rk4, 2.0 * 2f64.sqrt()), (Method::Verlet, 2.0)] {
        assert_eq!(paper::stability_limit(method), Some(limit));
        let at = |factor: f64| Settings {
            method,
            timestep: Some(factor * limit / omega),
            contact: ContactKind::Bilateral,
            periods: 100.0,
            ..Settings::default()
        };
        let below = paper::solve(&law, case.impact_velocity, &at(0.999)).unwrap();
        assert!(below.crossing_speeds.len() > 100);
        for s in &below.crossing_speeds {
            assert!(
                s.is_finite() && *s <= 1.01 * case.impact_velocity,
                "{}: {s}",
                method.name()
            );
        }
        match paper::solve(&law, case.impact_velocity, &at(1.001)) {
            Err(SolveError::Unstable { limit: l, .. }) => assert_eq!(l, limit),
            other => panic!("{}: expected Unstable, got {other:?}", method.name()),
        }
        // The verdict is the arithmetic's, not just the check's: the step map itself. Below the
        // limit RK4 decays and Verlet keeps a modified energy (an ellipse in (y, v), so the
        // largest |(y, v)| of two windows differ by a little).
        assert!(stability::step_map_growth(method, 0.999 * limit) <= 1.5);
        assert!(stability::step_map_growth(method, 1.001 * limit) > 10.0);
    }
}

/// 2√2, not 2.78: an undamped oscillator's eigenvalues are imaginary, and RK4's region meets
/// the imaginary axis at 2√2 (2.78 is where it meets the real axis).
#[test]
fn rk4_limit_is_on_the_imaginary_axis() {
    let limit = 2.0 * 2f64.sqrt();
    assert!(stability::step_map_growth(Method::Rk4, 0.999 * limit) < 1.0);
    // At 2.78 < 2√2 the oscillator decays rather than grows.
    assert!(stability::step_map_growth(Method::Rk4, 2.78) < 1.0);
    assert!(stability::step_map_growth(Method::Rk4, 1.001 * limit) > 1.0);
}

#[test]
fn limit_checks_report_both_sides() {
    let checks = stability::limit_checks();
    assert_eq!(checks.len(), 4);
    for c in &checks {
        let below = c.omega_dt < c.limit;
        assert_eq!(c.bounded, below, "{c:?}");
        assert_eq!(c.solver == stability::SolverVerdict::Ran, below, "{c:?}");
    }
}
