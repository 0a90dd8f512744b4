//! The tangential half of an oblique or spinning impact, integrated together with the normal
//! half by each method, and its closed forms.
//!
//! The normal motion does not feel the tangential force (a sphere's contact force acts through
//! its centre along the normal), but the tangential law feels the normal one twice: through
//! the Coulomb bound `μ |F_n|` and through a spring whose stiffness grows with the overlap. So
//! the state is `(y, ẏ, p, ξ)`: approach and its rate, the tangential impulse on the ball and
//! the spring's elongation, in the dimensionless form of the normal solver (lengths over the
//! elastic peak δ0, times over δ0/v0, forces over M* v0²/δ0).
//!
//! The law is LIGGGHTS' `tangential history` (see [`TangentialLaw`](crate::model::tangential::TangentialLaw)). In continuous time it is
//! an elastic–plastic spring: inside the bound, `ξ' = slip` and `F_t = −k_t ξ − γ_t slip`; on
//! the bound, `F_t = −σ μ |F_n|` with `σ = sign ξ` and `ξ = σ μ |F_n| / k_t`, and it stays on the
//! bound while the spring's force would grow at least as fast as the bound does. rk4-event and
//! dopri5 locate each change of regime, the turning point and the contact end on their step;
//! rk4 steps the history as a DEM code does, cutting it back to the bound after each step, and
//! verlet is the DEM codes' own scheme (the slip and the damping at the half step).

use nalgebra::Vector4;
use serde::Serialize;
use std::time::Instant;

use super::paper::Settings;
use super::{Method, SolveError, Stats};
use crate::model::case::Case;
use crate::model::exact::{self, j_integral};
use crate::model::tangential::{
    self, ClosedFormKind, Oblique, PlaneMotion, SLIP_FACTOR, TangentialBodies,
    TangentialClosedForm, TangentialSpring, effective_shear_modulus,
};

/// `(y, ẏ, p, ξ)`, dimensionless.
type State = Vector4<f64>;

/// Most steps an oblique impact may take.
const STEP_BUDGET: u64 = 50_000_000;
/// Most changes of the tangential regime in one contact before the run is declared stuck.
const MAX_SWITCHES: u32 = 10_000;

/// The result of integrating the tangential half of one impact.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ObliqueOutcome {
    /// The tangential impulse on the ball over the contact, N·s (along `t`).
    pub impulse: f64,
    /// The normal COR of this integration.
    pub restitution: f64,
    /// The ball's motion at separation.
    pub ball: PlaneMotion,
    /// The other ball's (ball–ball).
    pub other: Option<PlaneMotion>,
    /// The slip at first contact and at separation, m/s.
    pub slip_in: f64,
    /// See `slip_in`.
    pub slip_out: f64,
    /// Whether the force stayed on the Coulomb bound from first contact to separation.
    pub slid_throughout: bool,
    /// Changes between the spring inside the bound and sliding on it.
    pub regime_changes: u32,
    /// Kinetic energy of the tangential motion before and after, J.
    pub tangential_energy_in: f64,
    /// See `tangential_energy_in`.
    pub tangential_energy_out: f64,
    /// Work counters.
    pub stats: Stats,
    /// Wall time, s.
    pub wall_time: f64,
}

/// The regime of the tangential force.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Regime {
    /// The spring inside the Coulomb bound.
    Stick,
    /// On the bound, the force against `σ`.
    Slip(f64),
}

/// The dimensionless contact: the normal law's constants and the tangential law's.
#[derive(Clone, Copy, Debug)]
struct Contact {
    n: f64,
    eta: f64,
    mu: f64,
    slip0: f64,
    /// `k̂_t = stiffness_factor × y^stiffness_power`.
    stiffness_factor: f64,
    stiffness_power: f64,
    /// `2 ζ`: `γ̂_t = 2 ζ sqrt(k̂_t)`.
    two_zeta: f64,
}

impl Contact {
    fn of(case: &Case, oblique: &Oblique, slip: f64) -> Contact {
        let law = case.law();
        let v0 = case.impact_velocity;
        let n = law.exponent;
        let length = law.elastic_peak(v0);
        let time = length / v0;
        let (stiffness_factor, stiffness_power) = match oblique.law.spring {
            TangentialSpring::Mindlin => {
                let g = effective_shear_modulus(&case.scene).unwrap_or(f64::NAN);
                let r = case.scene.effective_radius().unwrap_or(f64::NAN);
                (8.0 * g * (r * length).sqrt() * time * time / law.mass, 0.5)
            }
            TangentialSpring::Linear { stiffness } => (stiffness * time * time / law.mass, 0.0),
            TangentialSpring::Proportional { ratio } => (ratio * 0.5 * (n + 1.0), n - 1.0),
        };
        Contact {
            n,
            eta: law.loss_coefficient,
            mu: oblique.friction_coefficient,
            slip0: slip / v0,
            stiffness_factor,
            stiffness_power,
            two_zeta: 2.0 * oblique.law.damping_ratio,
        }
    }

    /// Normal force at approach `y` on the branch `direction` (+1 loading, −1 unloading).
    #[inline]
    fn normal(&self, y: f64, direction: f64) -> f64 {
        if y <= 0.0 {
            0.0
        } else {
            0.5 * (self.n + 1.0) * y.powf(self.n) * (1.0 + self.eta * direction)
        }
    }

    #[inline]
    fn stiffness(&self, y: f64) -> f64 {
        if self.stiffness_power == 0.0 {
            self.stiffness_factor
        } else if y <= 0.0 {
            0.0
        } else {
            self.stiffness_factor * y.powf(self.stiffness_power)
        }
    }

    #[inline]
    fn slip(&self, s: &State) -> f64 {
        self.slip0 + SLIP_FACTOR * s[2]
    }

    /// The dashpot coefficient `γ̂ = 2 ζ sqrt(k̂)` at stiffness `k`.
    #[inline]
    fn damping(&self, k: f64) -> f64 {
        self.two_zeta * k.sqrt()
    }

    /// The tangential force inside the bound: spring and dashpot.
    #[inline]
    fn spring_force(&self, s: &State) -> f64 {
        let k = self.stiffness(s[0]);
        -k * s[3] - self.damping(k) * self.slip(s)
    }

    /// The smooth right-hand side of one regime on one branch.
    #[inline]
    fn rhs(&self, s: &State, direction: f64, regime: Regime) -> State {
        let f_n = self.normal(s[0], direction);
        let slip = self.slip(s);
        let (f_t, spring_rate) = match regime {
            Regime::Stick => (self.spring_force(s), slip),
            Regime::Slip(sigma) => (-sigma * self.mu * f_n, 0.0),
        };
        State::new(s[1], -f_n, f_t, spring_rate)
    }

    /// The regime's event function, positive while the regime holds: inside the bound, the
    /// margin `μ F_n − |k̂ ξ + γ̂ slip|`; on it, `y` times the excess of the trial force's rate
    /// (the spring following the slip, the dashpot the slip's rate) over the bound's:
    /// `σ k̂ slip y − μ F_n (n − κ) ẏ − σ (κ/2) γ̂ ẏ slip − (7/2) γ̂ μ F_n y`, κ the power of `k̂`
    /// in `y` (for γ̂ = 0 the first two terms).
    #[inline]
    fn regime_event(&self, s: &State, direction: f64, regime: Regime) -> f64 {
        let f_n = self.normal(s[0], direction);
        let k = self.stiffness(s[0]);
        let gamma = self.damping(k);
        let slip = self.slip(s);
        let kappa = self.stiffness_power;
        match regime {
            Regime::Stick => self.mu * f_n - (k * s[3] + gamma * slip).abs(),
            Regime::Slip(sigma) => {
                let y = s[0].max(0.0);
                sigma * k * slip * y
                    - self.mu * f_n * (self.n - kappa) * s[1]
                    - sigma * 0.5 * kappa * gamma * s[1] * slip
                    - SLIP_FACTOR * gamma * self.mu * f_n * y
            }
        }
    }

    /// The regime at first contact: on the bound when the spring's force, growing from zero
    /// with the slip, outgrows the bound's at a vanishing overlap.
    fn first_regime(&self) -> Regime {
        if self.slip0 == 0.0 || self.mu == 0.0 {
            return if self.mu == 0.0 && self.slip0 != 0.0 {
                Regime::Slip(self.slip0.signum())
            } else {
                Regime::Stick
            };
        }
        let y = 1e-8;
        let trial = self.stiffness(y) * self.slip0.abs() * y;
        if trial > self.mu * self.normal(y, 1.0) {
            Regime::Slip(self.slip0.signum())
        } else {
            Regime::Stick
        }
    }

    /// The regime at a jump of the bound (the turning point), with the spring cut back to the
    /// bound where it is beyond it: on the bound if the spring's trial rate leaves it, else
    /// inside it.
    fn settle(&self, s: &mut State, direction: f64, regime: Regime) -> Regime {
        let bound = self.mu * self.normal(s[0], direction);
        let trial = -self.spring_force(s);
        let sigma = match regime {
            Regime::Slip(sigma) => sigma,
            Regime::Stick if trial.abs() > bound => trial.signum(),
            Regime::Stick => return Regime::Stick,
        };
        self.enter(s, direction, Regime::Slip(sigma));
        if self.regime_event(s, direction, Regime::Slip(sigma)) >= 0.0 {
            Regime::Slip(sigma)
        } else {
            Regime::Stick
        }
    }

    /// Enter `regime` at state `s` on branch `direction`: on the bound, the spring sits on it.
    fn enter(&self, s: &mut State, direction: f64, regime: Regime) {
        if let Regime::Slip(sigma) = regime {
            let k = self.stiffness(s[0]);
            if k > 0.0 {
                let force = sigma * self.mu * self.normal(s[0], direction);
                s[3] = (force - self.damping(k) * self.slip(s)) / k;
            }
        }
    }
}

/// A one-step method on the four-component state.
trait Step4 {
    /// The state after a step `h` from `y` and an error norm (0 for a fixed step).
    fn step(&self, f: &dyn Fn(&State) -> State, y: &State, h: f64) -> (State, f64, u64);
    fn first(&self) -> f64;
    fn next(&self, h: f64, error: f64) -> f64;
}

struct FixedRk4(f64);

impl Step4 for FixedRk4 {
    fn step(&self, f: &dyn Fn(&State) -> State, y: &State, h: f64) -> (State, f64, u64) {
        let k1 = f(y);
        let k2 = f(&(y + 0.5 * h * k1));
        let k3 = f(&(y + 0.5 * h * k2));
        let k4 = f(&(y + h * k3));
        (y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4), 0.0, 4)
    }
    fn first(&self) -> f64 {
        self.0
    }
    fn next(&self, _h: f64, _error: f64) -> f64 {
        self.0
    }
}

struct DormandPrince(f64);

impl Step4 for DormandPrince {
    fn step(&self, f: &dyn Fn(&State) -> State, y: &State, h: f64) -> (State, f64, u64) {
        let k1 = f(y);
        let k2 = f(&(y + h * (k1 / 5.0)));
        let k3 = f(&(y + h * (3.0 / 40.0 * k1 + 9.0 / 40.0 * k2)));
        let k4 = f(&(y + h * (44.0 / 45.0 * k1 - 56.0 / 15.0 * k2 + 32.0 / 9.0 * k3)));
        let k5 = f(&(y + h
            * (19372.0 / 6561.0 * k1 - 25360.0 / 2187.0 * k2 + 64448.0 / 6561.0 * k3
                - 212.0 / 729.0 * k4)));
        let k6 = f(&(y + h
            * (9017.0 / 3168.0 * k1 - 355.0 / 33.0 * k2
                + 46732.0 / 5247.0 * k3
                + 49.0 / 176.0 * k4
                - 5103.0 / 18656.0 * k5)));
        let next = y + h
            * (35.0 / 384.0 * k1 + 500.0 / 1113.0 * k3 + 125.0 / 192.0 * k4 - 2187.0 / 6784.0 * k5
                + 11.0 / 84.0 * k6);
        let k7 = f(&next);
        let error = h
            * ((35.0 / 384.0 - 5179.0 / 57600.0) * k1
                + (500.0 / 1113.0 - 7571.0 / 16695.0) * k3
                + (125.0 / 192.0 - 393.0 / 640.0) * k4
                + (-2187.0 / 6784.0 + 92097.0 / 339200.0) * k5
                + (11.0 / 84.0 - 187.0 / 2100.0) * k6
                - 1.0 / 40.0 * k7);
        let norm = (0..4)
            .map(|i| error[i].abs() / (self.0 * (1.0f64).max(y[i].abs()).max(next[i].abs())))
            .fold(0.0, f64::max);
        (next, norm, 7)
    }
    fn first(&self) -> f64 {
        1e-3
    }
    fn next(&self, h: f64, error: f64) -> f64 {
        let factor = if error == 0.0 {
            5.0
        } else {
            (0.9 * error.powf(-0.2)).clamp(0.2, 5.0)
        };
        h * factor
    }
}

/// Integrate from `y` until one of `events` goes from positive to zero or below; the time
/// advanced, the state there and which event.
fn march4(
    method: &'static str,
    stepper: &dyn Step4,
    f: &dyn Fn(&State) -> State,
    events: &[&dyn Fn(&State) -> f64],
    mut y: State,
    stats: &mut Stats,
) -> Result<(f64, State, usize), SolveError> {
    let mut t = 0.0f64;
    let mut h = stepper.first();
    let mut g: Vec<f64> = events.iter().map(|e| e(&y)).collect();
    let mut steps = 0u64;
    loop {
        if steps > STEP_BUDGET {
            return Err(SolveError::StepBudget { method, steps });
        }
        if h <= 1e-15 * t.max(1.0) {
            return Err(SolveError::StepUnderflow { method, time: t });
        }
        if !(t + h).is_finite() {
            return Err(SolveError::NoTurn { method, time: t });
        }
        let (next, error, calls) = stepper.step(f, &y, h);
        stats.rhs_evaluations += calls;
        if error > 1.0 || !next.iter().all(|x| x.is_finite()) {
            stats.rejected += 1;
            h = stepper.next(h, error.max(1.0)).min(0.5 * h);
            continue;
        }
        let g_next: Vec<f64> = events.iter().map(|e| e(&next)).collect();
        let step = Step {
            stepper,
            f,
            y: &y,
            h,
        };
        // The earliest of the events that crossed on this step, located on the step itself.
        let mut first: Option<Crossing> = None;
        for (i, (&a, &b)) in g.iter().zip(&g_next).enumerate() {
            // A phase starts on the root of the event that began it (or at first contact, where
            // every force vanishes): an event that leaves such a start on the wrong side has
            // crossed at once, however small the start's rounding.
            let from_root = steps == 0 && a.abs() <= 1e-12 && b < 0.0;
            if (a > 0.0 && b <= 0.0) || from_root {
                let crossing = locate4(&step, events[i], (a, b), i, stats);
                if first.as_ref().is_none_or(|c| crossing.theta < c.theta) {
                    first = Some(crossing);
                }
            }
        }
        stats.steps += 1;
        steps += 1;
        if let Some(mut crossing) = first {
            // An event may cross and come back to zero within the step: the regime's margin
            // vanishes with the overlap where the contact ends (for a spring proportional to the
            // normal stiffness, both sides of the bound vanish as y^n), so past the contact's end
            // it reads zero, its located root lands on that flat zero after the end, and the
            // crossing before it is lost. Each other event is read once more just before the
            // earliest crossing; one already across there crossed earlier and is located there.
            for _ in 1..events.len() {
                let Some(earlier) = (0..events.len())
                    .filter(|&j| j != crossing.event && g[j] > 0.0)
                    .find_map(|j| crossed_before(&step, events[j], g[j], j, &crossing, stats))
                else {
                    break;
                };
                crossing = earlier;
            }
            return Ok((t + crossing.theta * h, crossing.state, crossing.event));
        }
        t += h;
        y = next;
        g = g_next;
        h = stepper.next(h, error);
    }
}

/// An event's root located on a step: the fraction of the step where it is reached, the state
/// there (on the side where the event has crossed), the last fraction found on the side where
/// it has not, and which event.
struct Crossing {
    theta: f64,
    state: State,
    before: f64,
    event: usize,
}

/// One step of a method from `y`, taken to any fraction of `h`: what locating an event steps.
#[derive(Clone, Copy)]
struct Step<'a> {
    stepper: &'a dyn Step4,
    f: &'a dyn Fn(&State) -> State,
    y: &'a State,
    h: f64,
}

impl Step<'_> {
    /// The state at the fraction `theta` of the step.
    fn to(&self, theta: f64, stats: &mut Stats) -> State {
        let (state, _, calls) = self.stepper.step(self.f, self.y, theta * self.h);
        stats.rhs_evaluations += calls;
        state
    }
}

/// Event `index`, positive (`g_start`) at the step's start, located on `[0, earliest.before]`
/// if it is already across at `earliest.before`, the last point found before the earliest
/// crossing.
fn crossed_before(
    step: &Step,
    event: &dyn Fn(&State) -> f64,
    g_start: f64,
    index: usize,
    earliest: &Crossing,
    stats: &mut Stats,
) -> Option<Crossing> {
    if earliest.before <= 0.0 {
        return None;
    }
    let g_before = event(&step.to(earliest.before, stats));
    if g_before > 0.0 {
        return None;
    }
    let scale = earliest.before;
    let part = Step {
        h: scale * step.h,
        ..*step
    };
    let within = locate4(&part, event, (g_start, g_before), index, stats);
    Some(Crossing {
        theta: within.theta * scale,
        before: within.before * scale,
        ..within
    })
}

/// Where `event` reaches zero on `step` (Illinois regula falsi on the method's own step), from
/// its values `(start, end)` at the step's ends.
fn locate4(
    step: &Step,
    event: &dyn Fn(&State) -> f64,
    (g_start, g_end): (f64, f64),
    index: usize,
    stats: &mut Stats,
) -> Crossing {
    let mut step_to = |theta: f64| step.to(theta, stats);
    let (mut lo, mut g_lo) = (0.0f64, g_start);
    let (mut hi, mut g_hi) = (1.0f64, g_end);
    let mut best = (1.0, step_to(1.0));
    let mut side = 0i8;
    for _ in 0..200 {
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let theta = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        let theta = if !theta.is_finite() || theta <= lo || theta >= hi {
            0.5 * (lo + hi)
        } else {
            theta
        };
        let state = step_to(theta);
        let value = event(&state);
        if value > 0.0 {
            lo = theta;
            g_lo = value;
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        } else {
            hi = theta;
            g_hi = value;
            best = (theta, state);
            if value == 0.0 {
                break;
            }
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        }
    }
    Crossing {
        theta: best.0,
        state: best.1,
        before: lo,
        event: index,
    }
}

/// The dimensionless result: the state at separation and the regime record.
struct Scaled {
    end: State,
    slid_throughout: bool,
    regime_changes: u32,
    stats: Stats,
}

/// rk4-event and dopri5: each branch and regime smooth, every change located.
fn phased(
    contact: &Contact,
    stepper: &dyn Step4,
    method: &'static str,
) -> Result<Scaled, SolveError> {
    let mut stats = Stats::default();
    let mut s = State::new(0.0, 1.0, 0.0, 0.0);
    let mut direction = 1.0;
    let mut regime = contact.first_regime();
    let mut slid_throughout = matches!(regime, Regime::Slip(_));
    let mut changes = 0u32;
    loop {
        if changes > MAX_SWITCHES {
            return Err(SolveError::StepBudget {
                method,
                steps: stats.steps,
            });
        }
        let f = |x: &State| contact.rhs(x, direction, regime);
        let normal = |x: &State| if direction > 0.0 { x[1] } else { x[0] };
        let tangential = |x: &State| contact.regime_event(x, direction, regime);
        let (_, at, which) = march4(method, stepper, &f, &[&normal, &tangential], s, &mut stats)?;
        s = at;
        if which == 0 {
            if direction < 0.0 {
                return Ok(Scaled {
                    end: s,
                    slid_throughout,
                    regime_changes: changes,
                    stats,
                });
            }
            // The turning point: the bound drops to the unloading branch; a spring beyond it
            // is cut back to it, and slides on only if its trial rate still leaves the bound.
            direction = -1.0;
            s[1] = s[1].min(0.0);
            let settled = contact.settle(&mut s, direction, regime);
            if settled != regime {
                changes += 1;
                if settled == Regime::Stick {
                    slid_throughout = false;
                }
            }
            regime = settled;
        } else {
            regime = match regime {
                Regime::Stick => {
                    let trial = -contact.spring_force(&s);
                    let sigma = if trial == 0.0 {
                        contact.slip(&s).signum()
                    } else {
                        trial.signum()
                    };
                    Regime::Slip(sigma)
                }
                Regime::Slip(sigma) => {
                    // The spring leaves the bound from where it sat on it.
                    slid_throughout = false;
                    contact.enter(&mut s, direction, Regime::Slip(sigma));
                    Regime::Stick
                }
            };
            changes += 1;
            contact.enter(&mut s, direction, regime);
        }
    }
}

/// The tangential force as a DEM code applies it at state `s` with normal force `f_n`: the
/// spring and dashpot, or the bound in their direction where they exceed it; and whether it is
/// on the bound.
#[inline]
fn bounded_force(contact: &Contact, s: &State, f_n: f64) -> (f64, bool) {
    let trial = contact.spring_force(s);
    let bound = contact.mu * f_n.abs();
    if trial.abs() > bound {
        (trial.signum() * bound, true)
    } else {
        (trial, false)
    }
}

/// rk4 and verlet: a fixed step, the history cut back to the bound after each step as a DEM
/// code does, the contact ended at the first step past zero approach.
fn fixed(contact: &Contact, h: f64, method: Method) -> Result<Scaled, SolveError> {
    let mut stats = Stats::default();
    let mut s = State::new(0.0, 1.0, 0.0, 0.0);
    let direction = |x: &State| {
        if x[1] > 0.0 {
            1.0
        } else if x[1] < 0.0 {
            -1.0
        } else {
            0.0
        }
    };
    let mut slid_throughout = true;
    let mut changes = 0u32;
    let mut was_on_bound: Option<bool> = None;
    let mut f_n = 0.0;
    let mut f_t = 0.0;
    // Whether there is any tangential force to speak of: a slip and a friction.
    let loaded = contact.mu > 0.0 && contact.slip0 != 0.0;
    let mut steps = 0u64;
    loop {
        if steps > STEP_BUDGET {
            return Err(SolveError::StepBudget {
                method: method.name(),
                steps,
            });
        }
        let on_bound = match method {
            Method::Rk4 => {
                let f = |x: &State| {
                    let f_n = contact.normal(x[0], direction(x));
                    let (f_t, _) = bounded_force(contact, x, f_n);
                    State::new(x[1], -f_n, f_t, contact.slip(x))
                };
                let (next, _, calls) = FixedRk4(h).step(&f, &s, h);
                stats.rhs_evaluations += calls;
                s = next;
                let f_n = contact.normal(s[0], direction(&s));
                cut_back(contact, &mut s, f_n)
            }
            _ => {
                let w_half = s[1] - 0.5 * h * f_n;
                let p_half = s[2] + 0.5 * h * f_t;
                let y = s[0] + h * w_half;
                let slip_half = contact.slip0 + SLIP_FACTOR * p_half;
                let xi = s[3] + h * slip_half;
                f_n = contact.normal(y, if w_half > 0.0 { 1.0 } else { -1.0 });
                let mut at = State::new(y, w_half, p_half, xi);
                let (force, on) = bounded_force(contact, &at, f_n);
                cut_back(contact, &mut at, f_n);
                f_t = force;
                stats.rhs_evaluations += 1;
                s = State::new(y, w_half - 0.5 * h * f_n, p_half + 0.5 * h * f_t, at[3]);
                on
            }
        };
        steps += 1;
        stats.steps += 1;
        if s[0] < 0.0 {
            break;
        }
        if loaded {
            if !on_bound {
                slid_throughout = false;
            }
            if was_on_bound.is_some_and(|was| was != on_bound) {
                changes += 1;
            }
            was_on_bound = Some(on_bound);
        }
    }
    Ok(Scaled {
        end: s,
        slid_throughout,
        regime_changes: changes,
        stats,
    })
}

/// Cut the spring back so that spring and dashpot meet the Coulomb bound `μ |f_n|`, as a DEM
/// code does after adding a step's slip; whether they were beyond it.
fn cut_back(contact: &Contact, s: &mut State, f_n: f64) -> bool {
    let (force, on_bound) = bounded_force(contact, s, f_n);
    let k = contact.stiffness(s[0]);
    if on_bound && k > 0.0 {
        s[3] = -(force + contact.damping(k) * contact.slip(s)) / k;
    }
    on_bound
}

/// Integrate the tangential half of the oblique `case` with `settings` (its method and knob,
/// as for the normal half), or take its closed form for the `exact` method (`None` when none
/// applies to the case).
pub fn solve_oblique(
    case: &Case,
    settings: &Settings,
) -> Result<Option<ObliqueOutcome>, SolveError> {
    let started = Instant::now();
    let Some(oblique) = case.oblique.as_ref() else {
        return Ok(None);
    };
    let Some(bodies) = TangentialBodies::of(&case.scene, oblique) else {
        return Ok(None);
    };
    let law = case.law();
    let v0 = case.impact_velocity;
    let slip_in = bodies.slip();
    let (impulse, restitution, slid, changes, stats) = if settings.method.integrates() {
        let contact = Contact::of(case, oblique, slip_in);
        let n = law.exponent;
        let length = law.elastic_peak(v0);
        let time = length / v0;
        let h = match settings.timestep {
            Some(dt) => dt / time,
            None => 4.0 * j_integral(n) / f64::from(settings.steps_per_period),
        };
        check_tangential_step(&contact, h, time, settings.method)?;
        let scaled = match settings.method {
            Method::Rk4Event => phased(&contact, &FixedRk4(h), "rk4-event")?,
            Method::Dopri5 => phased(&contact, &DormandPrince(settings.rtol), "dopri5")?,
            method => fixed(&contact, h, method)?,
        };
        (
            scaled.end[2] * law.mass * v0,
            -scaled.end[1],
            scaled.slid_throughout,
            scaled.regime_changes,
            scaled.stats,
        )
    } else {
        let Some(form) = closed_form(case) else {
            return Ok(None);
        };
        (
            form.impulse,
            exact::restitution(law.loss_coefficient),
            form.kind == ClosedFormKind::GrossSliding,
            0,
            Stats::default(),
        )
    };
    let (ball, other) = bodies.after(impulse);
    let after = TangentialBodies {
        ball: (bodies.ball.0, bodies.ball.1, ball),
        other: bodies.other.zip(other).map(|((m, r, _), o)| (m, r, o)),
    };
    Ok(Some(ObliqueOutcome {
        impulse,
        restitution,
        ball,
        other,
        slip_in,
        slip_out: after.slip(),
        slid_throughout: slid,
        regime_changes: changes,
        tangential_energy_in: TangentialBodies::energy(bodies.ball, bodies.other),
        tangential_energy_out: TangentialBodies::energy(after.ball, after.other),
        stats,
        wall_time: started.elapsed().as_secs_f64(),
    }))
}

/// Refuse a fixed step beyond the method's stability limit on the tangential spring: its
/// frequency `sqrt((7/2) k_t / M*)` at the largest overlap (the elastic peak, which the
/// dissipative law never exceeds) may exceed the normal one that the normal half was checked
/// against (the Mindlin spring's is about 1.7 times Hertz's for steel).
fn check_tangential_step(
    contact: &Contact,
    h: f64,
    time: f64,
    method: Method,
) -> Result<(), SolveError> {
    let Some(limit) = method.stability_limit() else {
        return Ok(());
    };
    let omega = (SLIP_FACTOR * contact.stiffness(1.0)).sqrt();
    if omega * h > limit {
        return Err(SolveError::Unstable {
            method: method.name(),
            timestep: h * time,
            omega: omega / time,
            omega_dt: omega * h,
            limit,
            max_timestep: limit / omega * time,
        });
    }
    Ok(())
}

/// The closed form that holds exactly for the oblique `case`, if one does: gross sliding
/// (when [`tangential::gross_sliding_holds`] says so) or the stick reversal
/// ([`tangential::stick_reversal_holds`]); `None` elsewhere (partial slip has none).
pub fn closed_form(case: &Case) -> Option<TangentialClosedForm> {
    closed_form_at(case, exact::restitution(case.law().loss_coefficient))
}

/// [`closed_form`] with its impulse taken at the normal COR `restitution`, as a code's run of
/// the case realised it (which form holds is decided at the case's own COR).
pub fn closed_form_at(case: &Case, restitution: f64) -> Option<TangentialClosedForm> {
    let oblique = case.oblique.as_ref()?;
    let bodies = TangentialBodies::of(&case.scene, oblique)?;
    let law = case.law();
    let v_n = case.impact_velocity;
    let e = exact::restitution(law.loss_coefficient);
    let slip = bodies.slip();
    let mu = oblique.friction_coefficient;
    if tangential::stick_reversal_holds(&oblique.law, law.loss_coefficient, mu, slip, v_n) {
        return Some(TangentialClosedForm {
            kind: ClosedFormKind::StickReversal,
            impulse: -2.0 * slip * law.mass / SLIP_FACTOR,
        });
    }
    let sliding = tangential::gross_sliding_holds(
        &oblique.law,
        mu,
        slip,
        v_n,
        e,
        law.loss_coefficient,
        law.stiffness,
        effective_shear_modulus(&case.scene)?,
        case.scene.effective_radius()?,
        law.exponent,
    )?;
    sliding.then(|| TangentialClosedForm {
        kind: ClosedFormKind::GrossSliding,
        impulse: tangential::gross_sliding_impulse(law.mass, v_n, restitution, mu, slip),
    })
}
