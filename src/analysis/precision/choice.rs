//! Accuracy as the input: from a COR tolerance to the cheapest method and resolution known to
//! meet it, by the measured bounds of [`CorErrorBound`].
//!
//! Each method with a bound gets the coarsest resolution whose bound, times a margin to spare
//! (`MARGIN`), is at most the tolerance; the cheapest of them is chosen by its work: the
//! right-hand-side evaluations of one impact at that resolution, weighted by the method's cost
//! per evaluation.
//! In the solver's dimensionless form an impact depends on the exponent and η alone, so one
//! choice holds for every case of every scene and every loss coefficient.

use crate::analysis::run::MIN_RTOL;
use crate::analysis::source::Resolution;
use crate::model::exact;
use crate::model::law::PaperLaw;
use crate::solve::paper::{self, Settings};
use crate::solve::{CorErrorBound, Knob, Method};

/// The bound is held to the tolerance with this factor to spare: the bound is the largest
/// error measured on a grid of loss coefficients and resolutions, and a point between them may
/// lie a little above it.
pub(crate) const MARGIN: f64 = 1.25;

/// Largest tolerance asked for: a relative COR error of 1 says nothing.
pub(crate) const MAX_TOLERANCE: f64 = 1.0;

/// A method and resolution chosen for a COR tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// The relative COR error asked for.
    pub tolerance: f64,
    /// The method chosen.
    pub method: Method,
    /// Its resolution.
    pub resolution: Resolution,
    /// The measured bound on the COR error there (at most `tolerance / MARGIN`).
    pub bound: f64,
    /// The runner-up, and its work relative to the choice's.
    pub runner_up: Option<(Method, Resolution, f64)>,
}

/// A tolerance no method is known to meet, or that is not a tolerance.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{allowed}")]
pub(crate) struct ToleranceRefused {
    /// What is allowed.
    pub allowed: String,
}

/// What a tolerance may be: a number in (smallest, 1), the smallest being what the finest
/// resolution of the best-bounded method meets with the margin.
pub(crate) fn allowed_tolerances() -> String {
    format!(
        "a relative COR error in [{:.1e}, {MAX_TOLERANCE}) (the smallest any method is known to meet)",
        smallest_tolerance()
    )
}

/// The smallest tolerance any method is known to meet.
pub(crate) fn smallest_tolerance() -> f64 {
    Method::ALL
        .iter()
        .filter_map(|m| {
            let bound = m.descriptor().cor_error_bound?;
            Some(bound.at(m.descriptor().knob, bound.finest) * MARGIN)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The coarsest resolution of `method` whose bound with the margin meets `tolerance`, and that
/// bound; `None` if even its finest does not.
pub(crate) fn resolution_for(method: Method, tolerance: f64) -> Option<(Resolution, f64)> {
    let descriptor = method.descriptor();
    let bound = descriptor.cor_error_bound?;
    let knob = descriptor.knob;
    let meets = |value: f64| bound.at(knob, value) * MARGIN <= tolerance;
    match knob {
        Knob::StepsPerPeriod => {
            let (mut lo, mut hi) = (to_steps(bound.coarsest)?, to_steps(bound.finest)?);
            if !meets(f64::from(hi)) {
                return None;
            }
            // The bound falls with N: the least N that meets it, by bisection.
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if meets(f64::from(mid)) {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            Some((
                Resolution::StepsPerPeriod(lo),
                bound.at(knob, f64::from(lo)),
            ))
        }
        Knob::Rtol => {
            if !meets(bound.finest) {
                return None;
            }
            // The bound rises with rtol: the largest rtol that meets it, by bisection in
            // log rtol, then rounded down to two significant digits so that it reads as it is.
            let (mut lo, mut hi) = (bound.finest.ln(), bound.coarsest.ln());
            if meets(bound.coarsest) {
                lo = hi;
            }
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if meets(mid.exp()) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let largest = lo.exp();
            let unit = 10f64.powf(largest.log10().floor() - 1.0);
            let mut rtol = two_digits((largest / unit).floor() * unit);
            for _ in 0..3 {
                if meets(rtol) {
                    break;
                }
                rtol = two_digits(rtol - unit);
            }
            (rtol >= bound.finest.max(MIN_RTOL) && meets(rtol))
                .then(|| (Resolution::Rtol(rtol), bound.at(knob, rtol)))
        }
        Knob::None => None,
    }
}

fn to_steps(value: f64) -> Option<u32> {
    crate::model::count::round_count(value).and_then(|n| u32::try_from(n).ok())
}

/// `x` to two significant digits (by its decimal text, so that it prints as it is).
fn two_digits(x: f64) -> f64 {
    format!("{x:.1e}").parse().unwrap_or(x)
}

/// The work of one impact by `method` at `resolution`: its right-hand-side evaluations on the
/// balls' exponent at η = 0.5, weighted by the method's cost per evaluation.
pub(crate) fn work(method: Method, resolution: Resolution) -> f64 {
    let Some(bound) = method.descriptor().cor_error_bound else {
        return f64::INFINITY;
    };
    let law = PaperLaw {
        mass: 1.0,
        stiffness: 1.0,
        exponent: 1.5,
        loss_coefficient: 0.5,
    };
    let mut settings = Settings {
        method,
        ..Settings::default()
    };
    match resolution {
        Resolution::StepsPerPeriod(n) => settings.steps_per_period = n,
        Resolution::Rtol(r) => settings.rtol = r,
        Resolution::StepsPerContact(_) => return f64::INFINITY,
    }
    match paper::solve(&law, 1.0, &settings) {
        Ok(outcome) => outcome.stats.rhs_evaluations as f64 * bound.evaluation_cost,
        Err(_) => f64::INFINITY,
    }
}

/// The cheapest method and resolution known to meet a relative COR error of `tolerance`.
pub(crate) fn choose(tolerance: f64) -> Result<Choice, ToleranceRefused> {
    let refuse = || ToleranceRefused {
        allowed: allowed_tolerances(),
    };
    if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < MAX_TOLERANCE) {
        return Err(refuse());
    }
    let mut candidates: Vec<(Method, Resolution, f64, f64)> = Method::ALL
        .iter()
        .filter_map(|&m| {
            let (resolution, bound) = resolution_for(m, tolerance)?;
            Some((m, resolution, bound, work(m, resolution)))
        })
        .collect();
    candidates.sort_by(|a, b| a.3.total_cmp(&b.3));
    let (method, resolution, bound, cost) = *candidates.first().ok_or_else(refuse)?;
    Ok(Choice {
        tolerance,
        method,
        resolution,
        bound,
        runner_up: candidates.get(1).map(|&(m, r, _, c)| (m, r, c / cost)),
    })
}

impl Choice {
    /// The sentence a command prints: what was chosen and why.
    pub(crate) fn sentence(&self) -> String {
        let mut text = format!(
            "COR tolerance {:e}: {} at {} (measured COR error at most {:.1e} over η in [0, 1) \
             for every scene)",
            self.tolerance,
            self.method,
            resolution_text(self.resolution),
            self.bound
        );
        if let Some((m, r, ratio)) = self.runner_up {
            text += &format!(
                "; {m} would need {} at {ratio:.1}× the work",
                resolution_text(r)
            );
        }
        text
    }
}

/// A resolution in words.
pub(crate) fn resolution_text(resolution: Resolution) -> String {
    match resolution {
        Resolution::StepsPerPeriod(n) => format!("{n} steps per period"),
        Resolution::Rtol(r) => format!("rtol {r:e}"),
        Resolution::StepsPerContact(n) => format!("{n} steps per contact"),
    }
}

/// The largest relative COR error of `method` at knob value `value` over `etas` and
/// `exponents`, against the closed form: what a [`CorErrorBound`] is measured from and checked
/// against.
pub fn largest_cor_error(method: Method, value: f64, etas: &[f64], exponents: &[f64]) -> f64 {
    let mut settings = Settings {
        method,
        ..Settings::default()
    };
    match method.descriptor().knob {
        Knob::StepsPerPeriod => {
            settings.steps_per_period = to_steps(value).unwrap_or(settings.steps_per_period)
        }
        Knob::Rtol => settings.rtol = value,
        Knob::None => {}
    }
    let mut worst = 0.0f64;
    for &exponent in exponents {
        for &eta in etas {
            let law = PaperLaw {
                mass: 1.0,
                stiffness: 1.0,
                exponent,
                loss_coefficient: eta,
            };
            let exact = exact::restitution(eta);
            let error = match paper::solve(&law, 1.0, &settings) {
                Ok(o) => ((o.figures.cor - exact) / exact).abs(),
                Err(_) => f64::INFINITY,
            };
            worst = worst.max(error);
        }
    }
    worst
}

/// The bound of `method`, if it has one.
pub fn bound_of(method: Method) -> Option<CorErrorBound> {
    method.descriptor().cor_error_bound
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::analysis::run::{IntegrationOptions, run_case};
    use crate::model::case::Case;
    use crate::solve::Knob;

    /// `count` loss coefficients on [0, 0.9999], then the extremes and the tail where
    /// rk4-event's error is largest.
    fn etas(count: usize) -> Vec<f64> {
        let mut v: Vec<f64> = (0..count)
            .map(|i| 0.9999 * i as f64 / (count - 1) as f64)
            .collect();
        v.extend([0.999, 0.9995, 0.99999, 1.0 - 1e-8]);
        v
    }

    /// For each scene's case and tolerances from 1e-3 to the smallest allowed, the chosen
    /// method and resolution run through `run_case` (what a sweep runs) meet the tolerance at
    /// every η.
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

    /// At 1e-10 the choice is rk4-event a little above the 458 steps per period the worst η
    /// needs (the margin), and dopri5 is the runner-up at more work.
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

    #[test]
    fn what_is_not_a_tolerance_is_refused() {
        for bad in [0.0, -1e-10, f64::NAN, f64::INFINITY, 1.0, 2.0, 1e-20] {
            assert!(choose(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_finer_tolerance_never_asks_for_less_work() {
        let mut last = 0.0;
        for k in 2..=13 {
            let c = choose(10f64.powi(-k)).unwrap();
            let w = work(c.method, c.resolution);
            assert!(w >= last, "1e-{k}: {w} < {last}");
            last = w;
        }
    }

    #[test]
    fn rtol_is_rounded_down_to_two_digits_and_meets_the_bound() {
        let (r, bound) = resolution_for(Method::Dopri5, 1e-10).unwrap();
        let Resolution::Rtol(r) = r else {
            panic!("{r:?}")
        };
        assert_eq!(format!("{r:e}"), "2.8e-10");
        assert!(bound * MARGIN <= 1e-10);
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
}
