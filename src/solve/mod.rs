//! Integrators of one impact: the paper's fixed-step RK4, RK4 with located events, an adaptive
//! Dormand–Prince pair with located events, velocity Verlet as DEM codes step, and the closed
//! forms.
//!
//! Every integrating method works on the dimensionless form of physics.md §3
//! (`y = δ0 Y`, `t = (δ0/v0) τ`), so that its conditioning does not depend on the units or the
//! scale of the case.

pub mod dashpot;
pub(crate) mod method;
pub mod paper;
pub(crate) mod series;
pub(crate) mod steppers;
pub mod tangential;

use serde::{Deserialize, Serialize};
use thiserror::Error;

pub use method::{CorErrorBound, Knob, Method, MethodDescriptor, Stepping, ToleranceRule};
use series::ContactSeries;
use steppers::{State, Stepper};

/// A failure of the integration itself (not of the input).
#[derive(Debug, Error, PartialEq)]
pub enum SolveError {
    /// The step budget ran out before the contact ended.
    #[error("{method}: no contact end after {steps} steps (step budget exhausted)")]
    StepBudget {
        /// Method name.
        method: &'static str,
        /// Steps taken.
        steps: u64,
    },
    /// The adaptive step fell below what the arithmetic can resolve.
    #[error("{method}: step size underflow at τ = {time}")]
    StepUnderflow {
        /// Method name.
        method: &'static str,
        /// Dimensionless time reached.
        time: f64,
    },
    /// The adaptive step grew without bound: nothing stops the bodies (a law whose force is
    /// zero or not a number everywhere), so the contact would never turn.
    #[error("{method}: the contact never turns (no force stops the bodies by τ = {time:e})")]
    NoTurn {
        /// Method name.
        method: &'static str,
        /// Dimensionless time reached.
        time: f64,
    },
    /// A fixed step in seconds beyond the method's stability limit for the case.
    #[error(
        "{method}: time step {timestep:e} s gives ω·Δt = {omega_dt:.4}, above the stability limit {limit} of the method (ω = {omega:e} rad/s); use Δt < {max_timestep:e} s"
    )]
    Unstable {
        /// Method name.
        method: &'static str,
        /// The step asked for, s.
        timestep: f64,
        /// The contact's angular frequency, rad/s.
        omega: f64,
        /// `ω Δt`.
        omega_dt: f64,
        /// The method's limit on `ω Δt`.
        limit: f64,
        /// The largest stable step, s.
        max_timestep: f64,
    },
}

/// Work counters of one run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Accepted steps (including event steps).
    pub steps: u64,
    /// Rejected adaptive steps.
    pub rejected: u64,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: u64,
}

/// Where a [`march`] stopped.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Crossing {
    /// Dimensionless time of the event.
    pub time: f64,
    /// State at the event.
    pub state: State,
    /// Which event function changed sign.
    pub event: usize,
}

/// Use the contact series instead of a step for the end of a power-law phase: the phase's
/// acceleration is `-k y^n` and its event 0 is `y = 0`.
#[derive(Clone, Debug)]
pub(crate) struct SeriesEnd<'a> {
    /// The series for the exponent.
    pub series: &'a ContactSeries,
    /// The stiffness factor `k`.
    pub k: f64,
}

/// Largest number of steps in one phase before the run is declared stuck.
pub(crate) const STEP_BUDGET: u64 = 200_000_000;

/// The event functions a [`march`] watches: it stops where one of them changes sign.
///
/// An array of functions (`&[&rate]`; for functions of several types, `&[&a as &dyn Fn(&State)
/// -> f64, &b]`) is checked with no allocation, and one of closures with no call through a
/// pointer either. A slice of any length works too, at the cost of a vector per step.
pub(crate) trait Events {
    /// The values of every event function at one state.
    type Values: AsRef<[f64]>;
    /// Every event function at `s`.
    fn values(&self, s: &State) -> Self::Values;
    /// Event function `i` at `s`.
    fn value(&self, i: usize, s: &State) -> f64;
}

impl<G: Fn(&State) -> f64, const N: usize> Events for [G; N] {
    type Values = [f64; N];
    #[inline]
    fn values(&self, s: &State) -> [f64; N] {
        std::array::from_fn(|i| self[i](s))
    }
    #[inline]
    fn value(&self, i: usize, s: &State) -> f64 {
        self[i](s)
    }
}

impl Events for [&dyn Fn(&State) -> f64] {
    type Values = Vec<f64>;
    fn values(&self, s: &State) -> Vec<f64> {
        self.iter().map(|g| g(s)).collect()
    }
    fn value(&self, i: usize, s: &State) -> f64 {
        self[i](s)
    }
}

/// Integrate `rhs` from `start` at time `t0` until one of `events` changes sign, locating that
/// instant on the step (the root of the event along a step of the method itself, by the
/// Illinois variant of regula falsi) and returning the state there. `observe` sees every
/// accepted state, the event state last.
///
/// Generic over the right-hand side, the method and the observer so that each phase compiles to
/// one loop with the law inlined into the method's stages; nothing is allocated per step.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn march<R, S, E, O>(
    rhs: &R,
    start: State,
    t0: f64,
    stepper: &mut S,
    events: &E,
    series_end: Option<SeriesEnd<'_>>,
    stats: &mut Stats,
    observe: &mut O,
) -> Result<Crossing, SolveError>
where
    R: Fn(&State) -> State + ?Sized,
    S: Stepper,
    E: Events + ?Sized,
    O: FnMut(f64, &State) + ?Sized,
{
    let rhs = |s: &State| rhs(s);
    let mut y = start;
    let mut t = t0;
    let mut fy = rhs(&y);
    stats.rhs_evaluations += 1;
    let mut h = stepper.first_step();
    let mut phase_steps = 0u64;
    let mut g_now = events.values(&y);
    loop {
        step_guard(phase_steps, t, h)?;
        // Near a non-smooth end the derivatives of y^n grow without bound and a one-step
        // method loses its order, however short its last step: the series takes over as soon
        // as the end is within the series' reach.
        if let Some(end) = series_end.as_ref()
            && y[1] < 0.0
            && end.series.within_reach_of_end(end.k, y[0], y[1], fy[1])
            && let Some((s, v)) = end.series.time_to_exit(end.k, y[0], y[1])
        {
            let state = State::new(0.0, -v);
            stats.steps += 1;
            observe(t + s, &state);
            return Ok(Crossing {
                time: t + s,
                state,
                event: 0,
            });
        }
        let trial = stepper.attempt(&rhs, &y, &fy, h);
        stats.rhs_evaluations += trial.rhs_evaluations;
        let g_next = events.values(&trial.state);
        let crossed = g_now
            .as_ref()
            .iter()
            .zip(g_next.as_ref())
            .position(|(&a, &b)| changes_sign(a, b));

        if trial.error > 1.0 || !trial.state.iter().all(|x| x.is_finite()) {
            stats.rejected += 1;
            h = stepper.next_step(h, trial.error.max(1.0)).min(0.5 * h);
            continue;
        }
        if let Some(event) = crossed {
            let g = |s: &State| events.value(event, s);
            let g_start = g_now.as_ref()[event];
            let (theta, state) = locate(&rhs, stepper, &y, &fy, h, g, g_start, stats);
            stats.steps += 1;
            let time = t + theta * h;
            observe(time, &state);
            return Ok(Crossing { time, state, event });
        }
        t += h;
        y = trial.state;
        fy = match trial.end_derivative {
            Some(f) => f,
            None => {
                stats.rhs_evaluations += 1;
                rhs(&y)
            }
        };
        g_now = g_next;
        stats.steps += 1;
        phase_steps += 1;
        observe(t, &y);
        h = stepper.next_step(h, trial.error);
    }
}

/// The checks a [`march`] makes before each step of `h` at time `t`, `phase_steps` into its
/// phase: the step budget, the step's underflow, and a step that overflows (it would be
/// rejected and halved from infinity forever).
pub(crate) fn step_guard(phase_steps: u64, t: f64, h: f64) -> Result<(), SolveError> {
    let method = "march";
    if phase_steps > STEP_BUDGET {
        Err(SolveError::StepBudget {
            method,
            steps: phase_steps,
        })
    } else if h <= t.abs().max(1.0) * 1e-15 {
        Err(SolveError::StepUnderflow { method, time: t })
    } else if !(t + h).is_finite() {
        Err(SolveError::NoTurn { method, time: t })
    } else {
        Ok(())
    }
}

/// Whether an event function going from `a` to `b` has crossed zero: `a != 0` and
/// `signum(a) != signum(b)` (a NaN on either side counts) or `b == 0`, with the signs compared
/// as bits.
#[inline]
pub(crate) fn changes_sign(a: f64, b: f64) -> bool {
    a != 0.0
        && (a.is_sign_negative() != b.is_sign_negative() || a.is_nan() || b.is_nan() || b == 0.0)
}

/// The fraction `θ` of the step `h` from `y` at which `g` vanishes along the method's own
/// step map, and the state there.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn locate<R: Fn(&State) -> State, S: Stepper>(
    rhs: &R,
    stepper: &mut S,
    y: &State,
    fy: &State,
    h: f64,
    g: impl Fn(&State) -> f64,
    g_start: f64,
    stats: &mut Stats,
) -> (f64, State) {
    let mut step_to = |theta: f64| {
        let attempt = stepper.attempt(rhs, y, fy, theta * h);
        stats.rhs_evaluations += attempt.rhs_evaluations;
        attempt.state
    };
    let (mut lo, mut g_lo) = (0.0f64, g_start);
    let mut state_hi = step_to(1.0);
    let (mut hi, mut g_hi) = (1.0f64, g(&state_hi));
    let mut best = (hi, state_hi);
    let mut side = 0i8;
    for _ in 0..200 {
        if g_hi == 0.0 || hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let theta = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        let theta = if !theta.is_finite() || theta <= lo || theta >= hi {
            0.5 * (lo + hi)
        } else {
            theta
        };
        let state = step_to(theta);
        let value = g(&state);
        if value == 0.0 {
            return (theta, state);
        }
        if value.signum() == g_lo.signum() {
            lo = theta;
            g_lo = value;
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        } else {
            hi = theta;
            g_hi = value;
            state_hi = state;
            best = (hi, state_hi);
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::steppers::{Dopri5, Rk4};
    use super::*;

    /// Free flight `y = 1 - t`: the root of `y` is at `t = 1` whatever the step.
    #[test]
    fn march_locates_an_event_inside_a_step() {
        let rhs = |s: &State| State::new(s[1], 0.0);
        let event = |s: &State| s[0];
        for h in [0.3, 0.07] {
            let mut stepper = Rk4::new(h);
            let mut stats = Stats::default();
            let crossing = march(
                &rhs,
                State::new(1.0, -1.0),
                0.0,
                &mut stepper,
                &[&event],
                None,
                &mut stats,
                &mut |_, _| {},
            )
            .unwrap();
            assert!((crossing.time - 1.0).abs() < 1e-14, "{}", crossing.time);
            assert_eq!(crossing.event, 0);
        }
    }

    /// The harmonic oscillator from rest at 1 turns (v = 0 → y extreme) at t = π exactly.
    #[test]
    fn adaptive_march_finds_the_turning_point_of_an_oscillator() {
        let rhs = |s: &State| State::new(s[1], -s[0]);
        let rate = |s: &State| s[1];
        let mut stepper = Dopri5::new(1e-12);
        let mut stats = Stats::default();
        let crossing = march(
            &rhs,
            State::new(0.0, 1.0),
            0.0,
            &mut stepper,
            &[&rate],
            None,
            &mut stats,
            &mut |_, _| {},
        )
        .unwrap();
        assert!((crossing.time - std::f64::consts::FRAC_PI_2).abs() < 1e-11);
        assert!((crossing.state[0] - 1.0).abs() < 1e-11);
        assert!(stats.rhs_evaluations > 0 && stats.steps > 0);
    }

    /// The bitwise sign test is `a != 0 && (signum(a) != signum(b) || b == 0)` on every pair
    /// of signed zeros, infinities, NaNs and ordinary values.
    #[test]
    fn sign_change_is_the_signum_test() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            1e-310,
            -1e-310,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        for a in values {
            for b in values {
                let by_signum = a != 0.0 && (a.signum() != b.signum() || b == 0.0);
                assert_eq!(changes_sign(a, b), by_signum, "{a} → {b}");
            }
        }
    }

    #[test]
    fn rk4_local_error_is_fifth_order() {
        let rhs = |s: &State| State::new(s[1], -s[0]);
        let error = |h: f64| {
            let y = State::new(0.0, 1.0);
            let next = steppers::rk4_step(&rhs, &y, &rhs(&y), h);
            (next[0] - h.sin()).abs()
        };
        let ratio = error(0.1) / error(0.05);
        assert!((ratio.log2() - 5.0).abs() < 0.1, "{}", ratio.log2());
    }
}
