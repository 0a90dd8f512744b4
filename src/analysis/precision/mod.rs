//! `millimpact precision`: error against run time for each method and each DEM code, the
//! work–precision picture of one impact.
//!
//! Each method is swept over its accuracy knob (steps per undamped period for the fixed-step
//! methods, the relative tolerance for dopri5) and each DEM code over its time step. A point
//! records the relative errors of COR, peak deformation and contact time, the right-hand-side
//! (force) evaluations and the run time. The errors of a method are taken against the closed
//! forms; those of a DEM code against that code's own law integrated at zero step error, so
//! that a code's point measures its step error only, not the difference between its damped
//! Hertz and the paper's law (that is `compare`'s business).
//!
//! Timing: a method's point is the median of `--repeats` timed batches after one warm-up run;
//! a batch repeats the impact until it lasts about a millisecond, because one impact takes
//! microseconds and the clock's resolution and the scheduler's noise are of that order. The
//! errors come from the warm-up run, outside the timed part. A DEM code's point is the median
//! process wall time (and the code's own loop time) of at most three runs after one warm-up
//! run of the code.

pub mod choice;
#[cfg(test)]
mod tests;

use std::collections::BTreeMap;
use std::hint::black_box;
use std::time::{Duration, Instant};

use serde::Serialize;
use thiserror::Error;

use super::run::relative_errors;
use super::source::Source;
use super::store::{CodeLawError, code_metrics, own_law_exact};
use crate::codes::{self, CodeError, CodeName, RunOptions, SetupError};
use crate::model::case::Case;
use crate::model::count::{ceil_count, round_count};
use crate::model::exact;
use crate::model::figures::{Checked, suffix};
use crate::model::law::PaperLaw;
use crate::output::invocation::Invocation;
use crate::output::{Section, Summary, seconds};
use crate::solve::paper::{self, Settings};
use crate::solve::{Knob, Method, SolveError, Stats};

/// Errors below this are at the rounding floor of double precision for these figures (a few
/// hundred ulps of an O(1) quantity after thousands of steps): such points say nothing about
/// the order and are left out of its fit.
pub(crate) const ROUNDING_FLOOR: f64 = 1e-12;

/// Fixed-step points coarser than this many steps per period are left out of the order fit:
/// below it the leading error term does not yet dominate (the step is a sizeable fraction of
/// the compression phase).
pub(crate) const ASYMPTOTIC_STEPS_PER_PERIOD: f64 = 32.0;

/// A batch of repeated impacts is timed for at least this long.
const BATCH_TIME: Duration = Duration::from_millis(1);

/// Largest number of timed runs of a DEM code per point (each run is ~0.4 s).
pub(crate) const CODE_REPEATS: u32 = 3;

/// One point of the work–precision diagram.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct WorkPrecisionPoint {
    /// The method or code.
    pub source: Source,
    /// What was swept.
    pub knob: SweepKnob,
    /// The knob's value.
    pub value: f64,
    /// |relative error| of the checked quantities (`cor_error`, …).
    #[serde(flatten, serialize_with = "suffix::error")]
    pub error: Checked,
    /// The largest of the three errors (what the diagram plots).
    pub max_error: f64,
    /// Right-hand-side (force) evaluations; a DEM code evaluates the force once per step.
    pub rhs_evaluations: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Median run time of one impact, s (for a code, the process wall time).
    pub time_s: f64,
    /// A DEM code's own loop time, median, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub loop_time_s: Option<f64>,
    /// The step in seconds (fixed-step methods and codes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub timestep_s: Option<f64>,
}

/// Observed orders of one source, per checked quantity (`None` where fewer than three points
/// lie in the asymptotic range).
pub(crate) type QuantityOrders = Checked<Option<f64>>;

/// What a work–precision sweep varies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum SweepKnob {
    /// A fixed-step method's steps per undamped period.
    StepsPerPeriod,
    /// An adaptive method's relative tolerance.
    Rtol,
    /// A DEM code's steps per elastic contact time.
    StepsPerContact,
}

impl SweepKnob {
    /// How a value of this knob reads in a sentence.
    pub(crate) fn sentence(self, value: f64) -> String {
        match self {
            SweepKnob::Rtol => format!("rtol {value:.0e}"),
            SweepKnob::StepsPerContact => format!("{value} steps/contact"),
            SweepKnob::StepsPerPeriod => format!("{value} steps/period"),
        }
    }

    /// How a value of this knob reads in a table cell.
    pub(crate) fn cell(self, value: f64) -> String {
        match self {
            SweepKnob::Rtol => format!("rtol {value:.0e}"),
            SweepKnob::StepsPerPeriod => format!("{value} /period"),
            SweepKnob::StepsPerContact => format!("{value} /contact"),
        }
    }

    /// The knob's step: `1/value` for steps, the tolerance itself for rtol.
    fn step(self, value: f64) -> f64 {
        match self {
            SweepKnob::Rtol => value,
            SweepKnob::StepsPerPeriod | SweepKnob::StepsPerContact => 1.0 / value,
        }
    }
}

/// A point named by its source and knob value, as the targets quote it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct NamedPoint {
    /// The method or code.
    pub source: Source,
    /// What was swept.
    pub knob: SweepKnob,
    /// The knob's value.
    pub value: f64,
    /// The quoted figure: a time (s) or an error.
    pub figure: f64,
}

/// The two cost targets of the issue, measured in one run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct Targets {
    /// The cheapest method point with COR error ≤ 1e-10 (figure: time, s).
    pub best_at_1e_10: Option<NamedPoint>,
    /// The cheapest DEM-code point (figure: time, s).
    pub fastest_code: Option<NamedPoint>,
    /// `best_at_1e_10` time over `fastest_code` time.
    pub cost_ratio: Option<f64>,
    /// Whether that ratio is at most 1/10,000.
    pub cost_ratio_met: Option<bool>,
    /// The smallest COR error any method reached (figure: the error).
    pub best_cor_error: Option<NamedPoint>,
    /// Whether it is at most 1e-12.
    pub cor_1e_12_met: Option<bool>,
}

/// Everything `millimpact precision` reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct PrecisionReport {
    /// Case name.
    pub case: String,
    /// Every point, by source then knob.
    pub points: Vec<WorkPrecisionPoint>,
    /// The observed order of each fixed-step method and each code: that of the contact time,
    /// the slowest-converging figure (see [`ORDER_NOTES`]).
    pub orders: BTreeMap<String, f64>,
    /// The observed order per quantity.
    pub orders_by_quantity: BTreeMap<String, QuantityOrders>,
    /// The order of the error's upper envelope per quantity (see [`envelope_orders`]).
    pub envelope_orders: BTreeMap<String, QuantityOrders>,
    /// dopri5: slope of log(error) against log(rtol) (1 means the error is proportional to
    /// the tolerance).
    pub tolerance_slopes: BTreeMap<String, QuantityOrders>,
    /// The cost targets.
    pub targets: Targets,
    /// Why the orders are what they are.
    pub notes: Vec<&'static str>,
    /// The command that reproduces the report.
    pub command: String,
}

/// What a note about orders is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum NoteSubject {
    /// One method.
    Method(Method),
    /// Every DEM code.
    Codes,
}

/// Why each method converges at the order it does; printed with the reports that sweep it.
pub(crate) const ORDER_NOTES: [(NoteSubject, &str); 6] = [
    (
        NoteSubject::Method(Method::Rk4Event),
        "rk4-event: the contact time converges at order 4, RK4's own order: the turning point and \
     the contact end are located on the step, and series cover the non-smooth y^n at the ends.",
    ),
    (
        NoteSubject::Method(Method::Rk4Event),
        "rk4-event: COR and peak deformation converge at order 5 (superconvergence): both are fixed \
     by the energy, at the turning point (peak) and at exit (COR), and RK4's energy error on an \
     oscillator is O(h^6) per step (its stability function matches exp(iz) to z^4 and |R(iz)|^2 \
     = 1 - z^6/72 + z^8/576), so O(h^5) over a phase; the phase (time) error is only O(h^4).",
    ),
    (
        NoteSubject::Method(Method::Rk4),
        "rk4 (the paper's): the contact ends at the first step past y = 0 with no event location, \
     so the exit time is late by a fraction of a step that depends on where the grid falls: a \
     staircase in N whose bound (the error envelope) is order 1, and whose least-squares fit is \
     lower still, dragged down by lucky alignments. The sign(ẏ) switch at the turning point \
     falls inside a step, where the force jumps by 2ηCy^n and RK4's stages straddle it, and the \
     exit velocity is taken from the step past zero: its COR error jumps by an order of \
     magnitude between neighbouring N (erratic), trending at about order 2 at best.",
    ),
    (
        NoteSubject::Method(Method::Verlet),
        "verlet: second order at best (the symplectic half kick, energy O(h^2)); the half-step \
     velocity switches the damping sign at the wrong instant and the contact end is the first \
     step past zero, so its contact time converges at order 1, like the paper's rk4.",
    ),
    (
        NoteSubject::Method(Method::Dopri5),
        "dopri5: its error follows its tolerance (slope ≈ 1 in log rtol), the mark of a well-tuned \
     controller; its order is not a slope against a fixed step.",
    ),
    (
        NoteSubject::Codes,
        "DEM codes (errors against each code's own damped law at zero step error): order 1 in \
     peak deformation and contact time, because velocity Verlet and leap-frog evaluate the \
     dashpot c y^m ẏ with the velocity of the half step, which lags by h/2 (a first-order \
     error in a velocity-dependent force); their cost is dominated by starting the process.",
    ),
];

/// Steps per period for the fixed-step sweeps: 19 values from 8 to 20000, geometric.
pub(crate) fn steps_per_period_sweep() -> Vec<u32> {
    let (lo, hi, count) = (8.0f64, 20000.0f64, 19);
    (0..count)
        .map(|k| {
            let n = round_count(lo * (hi / lo).powf(f64::from(k) / f64::from(count - 1)));
            n.and_then(|n| u32::try_from(n).ok())
                .expect("8 to 20000 steps per period")
        })
        .collect()
}

/// Relative tolerances for the dopri5 sweep: 1e-3 to 1e-14, one per decade.
pub(crate) fn rtol_sweep() -> Vec<f64> {
    (3..=14).map(|k| 10f64.powi(-k)).collect()
}

/// Steps per (elastic) contact time for a DEM code: five values from 20 to 2000, geometric.
pub(crate) fn code_steps_sweep() -> Vec<u32> {
    vec![20, 63, 200, 632, 2000]
}

/// The |relative error| of each checked quantity of `value` against `reference`.
fn absolute_errors(value: &Checked, reference: &Checked) -> Checked {
    relative_errors(value, reference).map(|_, e| e.abs())
}

/// A point's plotted error: the largest of its errors.
fn max_error(error: &Checked) -> f64 {
    error.iter().map(|(_, e)| *e).fold(0.0, f64::max)
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// Why a precision sweep could not be made; each variant names the method or the code.
#[derive(Debug, Error)]
pub enum PrecisionError {
    /// A method failed at one setting of its knob.
    #[error("{method} at {at}")]
    Method {
        /// The method.
        method: Method,
        /// The setting, in words (`rtol 1e-6`).
        at: String,
        /// Why.
        source: SolveError,
    },
    /// A method without a knob has no sweep.
    #[error("precision: {method} has no knob to sweep")]
    NoKnob {
        /// The method.
        method: Method,
    },
    /// A code's run could not be set up at a resolution.
    #[error("{code}: setting up {steps_per_contact} steps per contact")]
    Setup {
        /// The code.
        code: CodeName,
        /// The resolution.
        steps_per_contact: u32,
        /// Why.
        source: SetupError,
    },
    /// The code's own law could not be integrated, or its trajectory gives no figures.
    #[error(transparent)]
    Law(#[from] CodeLawError),
    /// The code failed to run, or its output could not be read.
    #[error(transparent)]
    Code(#[from] CodeError),
}

/// A study that could not be made is a method's, a code's or its set-up's failure.
impl crate::error::Blame for PrecisionError {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// One point of `method` on `law` at speed `v0` with `settings`: errors from a warm-up run,
/// then the median of `repeats` timed batches.
pub(crate) fn method_point(
    law: &PaperLaw,
    v0: f64,
    settings: &Settings,
    knob: SweepKnob,
    value: f64,
    repeats: u32,
) -> Result<WorkPrecisionPoint, PrecisionError> {
    let exact = exact::paper_impact(law, v0);
    let started = Instant::now();
    let warm = paper::solve(law, v0, settings).map_err(|source| PrecisionError::Method {
        method: settings.method,
        at: knob.sentence(value),
        source,
    })?;
    let single = started.elapsed().max(Duration::from_nanos(50));
    // A run faster than the clock resolves would ask for an unbounded batch: capped.
    let batch = ceil_count(BATCH_TIME.as_secs_f64() / single.as_secs_f64())
        .unwrap_or(u64::MAX)
        .clamp(1, 100_000);
    let mut times: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let t0 = Instant::now();
            for _ in 0..batch {
                // The result is not needed, only the work: keep the optimiser from dropping it.
                let _ = black_box(paper::solve(black_box(law), black_box(v0), settings));
            }
            t0.elapsed().as_secs_f64() / batch as f64
        })
        .collect();
    let error = absolute_errors(&warm.figures.select(), &exact.select());
    let Stats {
        steps,
        rhs_evaluations,
        ..
    } = warm.stats;
    Ok(WorkPrecisionPoint {
        source: Source::Method(settings.method),
        knob,
        value,
        error,
        max_error: max_error(&error),
        rhs_evaluations,
        steps,
        time_s: median(&mut times),
        loop_time_s: None,
        timestep_s: warm.timestep,
    })
}

/// The sweep of one method on `case`.
pub(crate) fn method_sweep(
    case: &Case,
    method: Method,
    repeats: u32,
) -> Result<Vec<WorkPrecisionPoint>, PrecisionError> {
    let law = case.law();
    let base = Settings {
        method,
        contact: case.contact,
        ..Settings::default()
    };
    let (knob, settings): (SweepKnob, Vec<(f64, Settings)>) = match method.descriptor().knob {
        Knob::Rtol => (
            SweepKnob::Rtol,
            rtol_sweep()
                .into_iter()
                .map(|rtol| (rtol, Settings { rtol, ..base }))
                .collect(),
        ),
        Knob::StepsPerPeriod => (
            SweepKnob::StepsPerPeriod,
            steps_per_period_sweep()
                .into_iter()
                .map(|n| {
                    (
                        f64::from(n),
                        Settings {
                            steps_per_period: n,
                            ..base
                        },
                    )
                })
                .collect(),
        ),
        Knob::None => return Err(PrecisionError::NoKnob { method }),
    };
    settings
        .iter()
        .map(|(value, s)| method_point(&law, case.impact_velocity, s, knob, *value, repeats))
        .collect()
}

/// The sweep of one DEM code on `case` over `steps_per_contact`, `repeats` timed runs per point
/// (at most [`CODE_REPEATS`]) after one warm-up run of the code. A missing binary, a crash or
/// an unparsable output is an error.
pub(crate) fn code_sweep(
    case: &Case,
    code: CodeName,
    steps_per_contact: &[u32],
    repeats: u32,
) -> Result<Vec<WorkPrecisionPoint>, PrecisionError> {
    let driver = code.driver();
    let options = RunOptions::default();
    let repeats = repeats.clamp(1, CODE_REPEATS);
    let mut points = Vec::new();
    let mut warmed = false;
    for &spc in steps_per_contact {
        let setup = codes::prepare(driver, case, Some(spc), None, false).map_err(|source| {
            PrecisionError::Setup {
                code,
                steps_per_contact: spc,
                source,
            }
        })?;
        let reference = own_law_exact(code, &driver.law(&setup), setup.impact_velocity, 1e-13)?;
        if !warmed {
            // The first start of a code pays for loading its libraries from disk.
            codes::run_code(driver, &setup, &options)?;
            warmed = true;
        }
        let mut walls = Vec::new();
        let mut loops = Vec::new();
        let mut last = None;
        for _ in 0..repeats {
            let run = codes::run_code(driver, &setup, &options)?;
            walls.push(run.wall_time);
            if let Some(l) = run.loop_time {
                loops.push(l);
            }
            last = Some(run);
        }
        let run = last.expect("at least one run");
        let metrics = code_metrics(code, &run.trajectory)?;
        let error = absolute_errors(&metrics.select(), &reference.select());
        points.push(WorkPrecisionPoint {
            source: Source::Code(code),
            knob: SweepKnob::StepsPerContact,
            value: spc as f64,
            error,
            max_error: max_error(&error),
            rhs_evaluations: setup.steps,
            steps: setup.steps,
            time_s: median(&mut walls),
            loop_time_s: (!loops.is_empty()).then(|| median(&mut loops)),
            timestep_s: Some(setup.timestep),
        });
    }
    Ok(points)
}

/// Least-squares slope of `ln y` against `ln x`, over at least three points.
pub(crate) fn log_slope(pairs: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = pairs
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if logs.len() < 3 {
        return None;
    }
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The observed orders of one source's points: the slope of log(error) against log(step),
/// the step being `1/value` for steps per period or contact, over the points in the asymptotic
/// range (error above `ROUNDING_FLOOR`; for a method, at least
/// `ASYMPTOTIC_STEPS_PER_PERIOD` steps per period). For dopri5 the slope against `rtol`.
pub(crate) fn observed_orders(points: &[WorkPrecisionPoint]) -> QuantityOrders {
    let usable = |p: &&WorkPrecisionPoint| {
        p.knob != SweepKnob::StepsPerPeriod || p.value >= ASYMPTOTIC_STEPS_PER_PERIOD
    };
    let step = |p: &WorkPrecisionPoint| p.knob.step(p.value);
    QuantityOrders::from_fn(|q| {
        let pairs: Vec<(f64, f64)> = points
            .iter()
            .filter(usable)
            .map(|p| (step(p), *p.error.get(q)))
            .filter(|&(_, error)| error >= ROUNDING_FLOOR)
            .collect();
        log_slope(&pairs)
    })
}

/// The orders of the error bound: the same fit as [`observed_orders`] applied to the upper
/// envelope of the error (at each step, the largest error at that step or any finer one).
///
/// Where the error is a staircase in the step (an exit detected at the first step past zero is
/// late by a fraction of a step that depends on where the grid falls), a least-squares fit of
/// the raw errors is dragged down by lucky alignments; the envelope measures how the worst case
/// shrinks, which is what the order of a method promises.
pub(crate) fn envelope_orders(points: &[WorkPrecisionPoint]) -> QuantityOrders {
    let mut sorted: Vec<WorkPrecisionPoint> = points.to_vec();
    // Finest first: steps per period or contact descending, rtol ascending.
    sorted.sort_by(|a, b| {
        if a.knob == SweepKnob::Rtol {
            a.value.total_cmp(&b.value)
        } else {
            b.value.total_cmp(&a.value)
        }
    });
    let mut worst: Checked = Checked::splat(0.0);
    for p in &mut sorted {
        worst = worst.map(|q, w| w.max(*p.error.get(q)));
        p.error = worst;
    }
    observed_orders(&sorted)
}

fn targets(points: &[WorkPrecisionPoint]) -> Targets {
    let is_code = |p: &WorkPrecisionPoint| matches!(p.source, Source::Code(_));
    let named = |p: &WorkPrecisionPoint, figure: f64| NamedPoint {
        source: p.source,
        knob: p.knob,
        value: p.value,
        figure,
    };
    let cheapest = |it: &mut dyn Iterator<Item = &WorkPrecisionPoint>| {
        it.min_by(|a, b| a.time_s.total_cmp(&b.time_s))
            .map(|p| named(p, p.time_s))
    };
    let best_at_1e_10 = cheapest(
        &mut points
            .iter()
            .filter(|p| !is_code(p) && p.error.cor <= 1e-10),
    );
    let fastest_code = cheapest(&mut points.iter().filter(|p| is_code(p)));
    let cost_ratio = match (&best_at_1e_10, &fastest_code) {
        (Some(b), Some(c)) => Some(b.figure / c.figure),
        _ => None,
    };
    let best_cor_error = points
        .iter()
        .filter(|p| !is_code(p))
        .min_by(|a, b| a.error.cor.total_cmp(&b.error.cor))
        .map(|p| named(p, p.error.cor));
    Targets {
        cost_ratio_met: cost_ratio.map(|r| r <= 1e-4),
        cor_1e_12_met: best_cor_error.as_ref().map(|b| b.figure <= 1e-12),
        best_at_1e_10,
        fastest_code,
        cost_ratio,
        best_cor_error,
    }
}

/// Sweep `methods` and `codes` on `case` and assemble the report.
pub(crate) fn precision_report(
    case: &Case,
    methods: &[Method],
    code_names: &[CodeName],
    repeats: u32,
    code_steps: &[u32],
) -> Result<PrecisionReport, PrecisionError> {
    let mut points = Vec::new();
    for &method in methods {
        points.extend(method_sweep(case, method, repeats)?);
    }
    for &code in code_names {
        points.extend(code_sweep(case, code, code_steps, repeats)?);
    }
    let mut orders = BTreeMap::new();
    let mut orders_by_quantity = BTreeMap::new();
    let mut tolerance_slopes = BTreeMap::new();
    let mut envelopes = BTreeMap::new();
    for (source, own) in crate::analysis::groups(&points, |p| p.source) {
        let own: Vec<WorkPrecisionPoint> = own.into_iter().cloned().collect();
        let q = observed_orders(&own);
        let source = source.name();
        if own[0].knob == SweepKnob::Rtol {
            tolerance_slopes.insert(source.to_string(), q);
            continue;
        }
        if let Some(order) = q.contact_time {
            orders.insert(source.to_string(), order);
        }
        orders_by_quantity.insert(source.to_string(), q);
        envelopes.insert(source.to_string(), envelope_orders(&own));
    }
    // Only the notes about the sources swept.
    let notes = ORDER_NOTES
        .iter()
        .filter(|(subject, _)| {
            points.iter().any(|p| match (subject, p.source) {
                (NoteSubject::Method(m), Source::Method(swept)) => *m == swept,
                (NoteSubject::Codes, Source::Code(_)) => true,
                _ => false,
            })
        })
        .map(|(_, note)| *note)
        .collect();
    let method_names: Vec<&str> = methods.iter().map(|m| m.name()).collect();
    let code_list: Vec<&str> = code_names.iter().map(|c| c.name()).collect();
    let command = Invocation::new("precision")
        .arg(case.path.display())
        .option_if(
            "--methods",
            (!method_names.is_empty()).then(|| method_names.join(",")),
        )
        .option_if(
            "--codes",
            (!code_list.is_empty()).then(|| code_list.join(",")),
        )
        .to_string();
    Ok(PrecisionReport {
        case: case.name.clone(),
        targets: targets(&points),
        points,
        orders,
        orders_by_quantity,
        envelope_orders: envelopes,
        tolerance_slopes,
        notes,
        command,
    })
}

fn opt(x: Option<f64>) -> String {
    x.map_or_else(|| "n/a".to_string(), |v| format!("{v:.2}"))
}

const HEADERS: [&str; 9] = [
    "source",
    "knob",
    "COR error",
    "peak error",
    "contact-time error",
    "rhs evals",
    "time",
    "code loop time",
    "step (s)",
];

fn rows(report: &PrecisionReport) -> Vec<Vec<String>> {
    report
        .points
        .iter()
        .map(|p| {
            let mut row = vec![p.source.to_string(), p.knob.cell(p.value)];
            row.extend(p.error.iter().map(|(_, e)| format!("{e:.2e}")));
            row.extend([
                p.rhs_evaluations.to_string(),
                seconds(p.time_s),
                p.loop_time_s.map_or_else(String::new, seconds),
                p.timestep_s
                    .map_or_else(String::new, |s| format!("{s:.3e}")),
            ]);
            row
        })
        .collect()
}

/// A row of the orders table: the source, what the slope is against, the order of each
/// quantity, and the last cell.
fn order_row(source: &str, against: &str, orders: &QuantityOrders, last: String) -> Vec<String> {
    let mut row = vec![source.to_string(), against.to_string()];
    row.extend(orders.iter().map(|(_, order)| opt(*order)));
    row.push(last);
    row
}

fn order_rows(report: &PrecisionReport) -> Vec<Vec<String>> {
    let mut out: Vec<Vec<String>> = report
        .orders_by_quantity
        .iter()
        .flat_map(|(source, q)| {
            let envelope = report
                .envelope_orders
                .get(source)
                .copied()
                .unwrap_or_default();
            [
                order_row(
                    source,
                    "log step",
                    q,
                    opt(report.orders.get(source).copied()),
                ),
                order_row(source, "log step, error envelope", &envelope, String::new()),
            ]
        })
        .collect();
    for (source, q) in &report.tolerance_slopes {
        out.push(order_row(source, "log rtol", q, String::new()));
    }
    out
}

const ORDER_HEADERS: [&str; 6] = [
    "source",
    "slope against",
    "COR",
    "peak",
    "contact time",
    "order (contact time)",
];

fn target_lines(t: &Targets) -> Vec<String> {
    let mut lines = Vec::new();
    match (&t.best_at_1e_10, &t.fastest_code, t.cost_ratio) {
        (Some(b), Some(c), Some(r)) => lines.push(format!(
            "cost: cheapest impact at COR error ≤ 1e-10 is {} at {} ({}); fastest DEM-code run is \
             {} at {} ({}); ratio {:.2e} (target ≤ 1e-4: {})",
            b.source,
            b.knob.sentence(b.value),
            seconds(b.figure),
            c.source,
            c.knob.sentence(c.value),
            seconds(c.figure),
            r,
            if r <= 1e-4 { "met" } else { "NOT met" }
        )),
        (Some(b), _, _) => lines.push(format!(
            "cost: cheapest impact at COR error ≤ 1e-10 is {} at {} ({}); no DEM code swept",
            b.source,
            b.knob.sentence(b.value),
            seconds(b.figure)
        )),
        _ => lines.push("cost: no method reached COR error ≤ 1e-10".to_string()),
    }
    if let Some(b) = &t.best_cor_error {
        lines.push(format!(
            "best COR error: {:.2e} by {} at {} (target ≤ 1e-12: {})",
            b.figure,
            b.source,
            b.knob.sentence(b.value),
            if b.figure <= 1e-12 { "met" } else { "NOT met" }
        ));
    }
    lines
}

/// A point as one flat CSV row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct PointRecord {
    /// The method or code.
    pub source: Source,
    /// What was swept.
    pub knob: SweepKnob,
    /// The knob's value.
    pub value: f64,
    /// |relative error| of the checked quantities (`cor_error`, …).
    #[serde(flatten, serialize_with = "suffix::error")]
    pub error: Checked,
    /// Right-hand-side (force) evaluations.
    pub rhs_evaluations: u64,
    /// Steps.
    pub steps: u64,
    /// Median run time, s.
    pub time_s: f64,
    /// A code's own loop time, s.
    pub loop_time_s: Option<f64>,
    /// The fixed step, s.
    pub timestep_s: Option<f64>,
}

impl PrecisionReport {
    /// The points of each source as `(largest relative error, run time in s)`, in sweep order:
    /// the series of the work–precision diagram.
    pub(crate) fn series(&self) -> Vec<(String, Vec<(f64, f64)>)> {
        crate::analysis::groups(&self.points, |p| p.source)
            .into_iter()
            .map(|(source, points)| {
                let points = points.iter().map(|p| (p.max_error, p.time_s)).collect();
                (source.to_string(), points)
            })
            .collect()
    }
}

impl Summary for PrecisionReport {
    type Record = PointRecord;

    /// The source and the knob.
    fn key_columns(&self) -> usize {
        2
    }

    fn records(&self) -> Vec<PointRecord> {
        self.points
            .iter()
            .map(|p| PointRecord {
                source: p.source,
                knob: p.knob,
                value: p.value,
                error: p.error,
                rhs_evaluations: p.rhs_evaluations,
                steps: p.steps,
                time_s: p.time_s,
                loop_time_s: p.loop_time_s,
                timestep_s: p.timestep_s,
            })
            .collect()
    }

    fn sections(&self) -> Vec<Section> {
        let mut points = Section::new(
            Some(format!("Work–precision, case {}", self.case)),
            &HEADERS,
        );
        points.rows = rows(self);
        let mut orders = Section::new(
            Some("Observed orders (slope of log error)".to_string()),
            &ORDER_HEADERS,
        );
        orders.rows = order_rows(self);
        orders.notes = target_lines(&self.targets)
            .into_iter()
            .chain(self.notes.iter().map(|n| n.to_string()))
            .map(|line| format!("- {line}"))
            .collect();
        vec![points, orders]
    }

    fn footer(&self) -> Vec<String> {
        vec![format!("reproduce: {}", self.command)]
    }
}
