//! The fixed-step stability limits: the solver's refusal just above them, and the methods' own
//! step maps on both sides.

use std::path::Path;

use super::*;

/// The shipped rod, undamped and bilateral: a linear oscillator whose eigenvalues `±iω` lie on
/// the imaginary axis.
fn bilateral_rod() -> Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/rod_end.toml");
    let mut case = Case::load(&path)
        .unwrap_or_else(|e| panic!("rod_end: {e}"))
        .with_loss_coefficient(0.0);
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
        assert!(step_map_growth(method, 0.999 * limit) <= 1.5);
        assert!(step_map_growth(method, 1.001 * limit) > 10.0);
    }
}

/// 2√2, not 2.78: an undamped oscillator's eigenvalues are imaginary, and RK4's region meets
/// the imaginary axis at 2√2 (2.78 is where it meets the real axis).
#[test]
fn rk4_limit_is_on_the_imaginary_axis() {
    let limit = 2.0 * 2f64.sqrt();
    assert!(step_map_growth(Method::Rk4, 0.999 * limit) < 1.0);
    // At 2.78 < 2√2 the oscillator decays rather than grows.
    assert!(step_map_growth(Method::Rk4, 2.78) < 1.0);
    assert!(step_map_growth(Method::Rk4, 1.001 * limit) > 1.0);
}

#[test]
fn limit_checks_report_both_sides() {
    let checks = limit_checks();
    assert_eq!(checks.len(), 4);
    for c in &checks {
        let below = c.omega_dt < c.limit;
        assert_eq!(c.bounded, below, "{c:?}");
        assert_eq!(c.solver == SolverVerdict::Ran, below, "{c:?}");
    }
}
