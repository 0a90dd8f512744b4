//! One impact of the paper's law by each method.

use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::series::ContactSeries;
use super::steppers::{Dopri5, Rk4, State, Stepper, rk4_step};
use super::{Method, SeriesEnd, SolveError, Stats, march};
use crate::model::case::ContactKind;
use crate::model::exact::{self, ImpactFigures, j_integral};
use crate::model::figures::{Exact, Figures, Quantity, quantity};
use crate::model::law::PaperLaw;

/// Call `$f` with the [`Power`] for exponent `$n` as its first argument, then `$args`. The
/// exponents are the scenes' exact 1 and 1.5 (`SpringModel::exponent`), so exact comparison
/// picks the specialised power; any other exponent takes the general one.
macro_rules! with_power {
    ($n:expr, $f:ident($($args:expr),* $(,)?)) => {
        #[allow(clippy::float_cmp)]
        if $n == 1.0 {
            $f(Linear, $($args),*)
        } else if $n == 1.5 {
            $f(Hertz, $($args),*)
        } else {
            $f(AnyExponent($n), $($args),*)
        }
    };
}

/// How to integrate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The method.
    pub method: Method,
    /// Fixed-step methods: steps per undamped period `T = 4 J(n) δ0 / v0`.
    pub steps_per_period: u32,
    /// Fixed-step methods: a step in seconds instead (checked against the stability limit).
    pub timestep: Option<f64>,
    /// Adaptive method: relative tolerance.
    pub rtol: f64,
    /// Unilateral or bilateral contact.
    pub contact: ContactKind,
    /// Bilateral contact: how many undamped periods to follow.
    pub periods: f64,
    /// Keep the trajectory.
    pub record: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            method: Method::Rk4Event,
            steps_per_period: 1000,
            timestep: None,
            rtol: 1e-12,
            contact: ContactKind::Unilateral,
            periods: 3.0,
            record: false,
        }
    }
}

/// One trajectory sample, SI units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Approach, m.
    pub y: f64,
    /// Approach rate, m/s.
    pub v: f64,
}

/// The result of one impact by one method.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// The figures (COR, peak, times, energy).
    pub figures: ImpactFigures,
    /// Work counters.
    pub stats: Stats,
    /// Wall time of the integration, s.
    pub wall_time: f64,
    /// The fixed step used, s (fixed-step methods).
    pub timestep: Option<f64>,
    /// The trajectory, when recorded.
    pub trajectory: Vec<Sample>,
    /// Bilateral contact: the speed at each passage through zero approach, m/s.
    pub crossing_speeds: Vec<f64>,
}

impl Outcome {
    /// The outcome of the closed forms alone: no steps, no trajectory.
    fn closed_form(figures: ImpactFigures, wall_time: f64) -> Outcome {
        Outcome {
            figures,
            stats: Stats::default(),
            wall_time,
            timestep: None,
            trajectory: Vec::new(),
            crossing_speeds: Vec::new(),
        }
    }
}

/// Trajectory samples drawn from each stretch the contact series carries.
const SERIES_SAMPLES: usize = 16;

/// The figures the dimensionless solve finds (the restitution time follows from two of them).
const SOLVED: u8 = quantity::COR
    | quantity::PEAK_DEFORMATION
    | quantity::PEAK_FORCE
    | quantity::CONTACT_TIME
    | quantity::COMPRESSION_TIME;

/// Dimensionless result.
#[derive(Clone, Debug, Default)]
struct Scaled {
    figures: Figures<f64, SOLVED>,
    stats: Stats,
    samples: Vec<(f64, f64, f64)>,
    crossing_speeds: Vec<f64>,
}

/// The stability limit of a fixed-step method on an undamped oscillator, as `ω Δt`.
pub fn stability_limit(method: Method) -> Option<f64> {
    method.stability_limit()
}

/// The contact's largest angular frequency, rad/s: that of the loading stiffness linearised at
/// the peak, `ω² = n C (1+η) y_max^(n-1) / M`.
pub fn angular_frequency(law: &PaperLaw, impact_velocity: f64) -> f64 {
    let n = law.exponent;
    let peak = exact::paper_impact(law, impact_velocity).peak_deformation;
    (n * law.stiffness * (1.0 + law.loss_coefficient) * peak.powf(n - 1.0) / law.mass).sqrt()
}

/// Integrate one impact of `law` at approach speed `impact_velocity` (m/s).
///
/// The paper's own method, fixed-step RK4 at 1000 steps per undamped period, ends the contact
/// at the first step with y < 0, so its contact time is late by up to one step (here the
/// half period falls on step 500, where y is zero to rounding, so it ends one step later):
///
/// ```
/// use millimpact::{Method, Settings, solve};
/// use millimpact::model::law::PaperLaw;
///
/// // A linear spring (n = 1) of 1 kg on 1 N/m without loss: the contact lasts half a period, π s.
/// let law = PaperLaw { mass: 1.0, stiffness: 1.0, exponent: 1.0, loss_coefficient: 0.0 };
/// let settings = Settings { method: Method::Rk4, ..Settings::default() };
/// let outcome = solve(&law, 1.0, &settings)?;
/// let step = outcome.timestep.unwrap();
/// assert!((step - 2.0 * std::f64::consts::PI / 1000.0).abs() < 1e-15);
/// let late = outcome.figures.contact_time - std::f64::consts::PI;
/// assert!(late >= 0.0 && late <= step * (1.0 + 1e-9), "{late} after {step}");
/// assert!((outcome.figures.cor - 1.0).abs() < 1e-9);
/// # Ok::<(), millimpact::solve::SolveError>(())
/// ```
pub fn solve(
    law: &PaperLaw,
    impact_velocity: f64,
    settings: &Settings,
) -> Result<Outcome, SolveError> {
    let started = Instant::now();
    let plan = match Plan::of(law, impact_velocity, settings)? {
        Planned::Integrate(plan) => plan,
        Planned::Exact(figures) => {
            return Ok(Outcome::closed_form(
                figures,
                started.elapsed().as_secs_f64(),
            ));
        }
    };
    let (n, eta, h) = (plan.exponent, plan.loss_coefficient, plan.step);
    let bilateral = settings.contact == ContactKind::Bilateral;
    let duration = settings.periods * plan.period;
    let scaled = match settings.method {
        Method::Rk4 | Method::Verlet => {
            fixed_step(n, eta, h, settings.method, bilateral, duration, settings)?
        }
        Method::Rk4Event => {
            let mut stepper = Rk4::new(h);
            phased(n, eta, &mut stepper, bilateral, duration, settings)?
        }
        Method::Dopri5 => {
            let mut stepper = Dopri5::new(settings.rtol);
            phased(n, eta, &mut stepper, bilateral, duration, settings)?
        }
        Method::Exact => unreachable!("handled by the plan"),
    };
    Ok(plan.outcome(scaled, started.elapsed().as_secs_f64()))
}

/// Refuse what [`solve`] would refuse before integrating: a step in seconds beyond the
/// method's stability limit for this impact.
pub(crate) fn check_step(
    law: &PaperLaw,
    impact_velocity: f64,
    settings: &Settings,
) -> Result<(), SolveError> {
    Plan::of(law, impact_velocity, settings).map(|_| ())
}

/// Impacts solved together: each item `(law, impact_velocity)` with the same `settings`, each
/// giving what [`solve`] gives it, bit for bit. rk4-event on a unilateral contact without a
/// trajectory steps `LANES` impacts at once, interleaved: one RK4 chain is a chain of
/// dependent operations that leaves most of the processor idle, and independent chains fill
/// it. Every other method runs them one after the other. An impact's `wall_time` is the
/// batch's divided among its impacts.
pub fn solve_many(
    items: &[(PaperLaw, f64)],
    settings: &Settings,
) -> Vec<Result<Outcome, SolveError>> {
    let lanes = settings.method == Method::Rk4Event
        && settings.contact == ContactKind::Unilateral
        && !settings.record;
    if !lanes {
        return items
            .iter()
            .map(|(law, v0)| solve(law, *v0, settings))
            .collect();
    }
    let started = Instant::now();
    let plans: Vec<Result<Planned, SolveError>> = items
        .iter()
        .map(|(law, v0)| Plan::of(law, *v0, settings))
        .collect();
    let mut scaled: Vec<Option<Result<Scaled, SolveError>>> =
        (0..items.len()).map(|_| None).collect();
    // Lanes share an exponent (the power is chosen at compile time): one pass per exponent.
    let mut exponents: Vec<u64> = plans
        .iter()
        .filter_map(|p| match p {
            Ok(Planned::Integrate(plan)) => Some(plan.exponent.to_bits()),
            _ => None,
        })
        .collect();
    exponents.sort_unstable();
    exponents.dedup();
    for bits in exponents {
        let n = f64::from_bits(bits);
        let (at, jobs): (Vec<usize>, Vec<(f64, f64)>) = plans
            .iter()
            .enumerate()
            .filter_map(|(i, p)| match p {
                Ok(Planned::Integrate(plan)) if plan.exponent.to_bits() == bits => {
                    Some((i, (plan.loss_coefficient, plan.step)))
                }
                _ => None,
            })
            .unzip();
        let results = rk4_event_lanes_of(n, &jobs);
        for (i, result) in at.into_iter().zip(results) {
            scaled[i] = Some(result);
        }
    }
    let wall_time = started.elapsed().as_secs_f64() / items.len().max(1) as f64;
    plans
        .into_iter()
        .zip(scaled)
        .map(|(plan, scaled)| match plan? {
            Planned::Exact(figures) => Ok(Outcome::closed_form(figures, wall_time)),
            Planned::Integrate(plan) => {
                let scaled = scaled.expect("every planned impact was stepped")?;
                Ok(plan.outcome(scaled, wall_time))
            }
        })
        .collect()
}

/// [`rk4_event_lanes`] with the power of exponent `n`.
fn rk4_event_lanes_of(n: f64, jobs: &[(f64, f64)]) -> Vec<Result<Scaled, SolveError>> {
    with_power!(n, rk4_event_lanes(n, jobs))
}

/// One impact made dimensionless: its scales, the step, and what the integrator needs.
#[derive(Clone, Copy, Debug)]
struct Plan {
    method: Method,
    impact_velocity: f64,
    mass: f64,
    stiffness: f64,
    exponent: f64,
    loss_coefficient: f64,
    y_scale: f64,
    t_scale: f64,
    /// The undamped period, dimensionless.
    period: f64,
    /// The fixed step, dimensionless (fixed-step methods).
    step: f64,
}

/// What an impact needs: integration, or the closed forms alone.
#[derive(Clone, Copy, Debug)]
enum Planned {
    Integrate(Plan),
    Exact(ImpactFigures),
}

impl Plan {
    fn of(law: &PaperLaw, v0: f64, settings: &Settings) -> Result<Planned, SolveError> {
        let y_scale = law.elastic_peak(v0);
        let t_scale = y_scale / v0;
        let (n, eta) = (law.exponent, law.loss_coefficient);
        let period = 4.0 * j_integral(n);
        let method = settings.method;
        if !method.integrates() {
            return Ok(Planned::Exact(exact::paper_impact(law, v0)));
        }
        let step = match settings.timestep {
            Some(dt) => {
                if let Some(limit) = stability_limit(method) {
                    let omega = angular_frequency(law, v0);
                    if omega * dt > limit {
                        return Err(SolveError::Unstable {
                            method: method.name(),
                            timestep: dt,
                            omega,
                            omega_dt: omega * dt,
                            limit,
                            max_timestep: limit / omega,
                        });
                    }
                }
                dt / t_scale
            }
            None => period / settings.steps_per_period as f64,
        };
        Ok(Planned::Integrate(Plan {
            method,
            impact_velocity: v0,
            mass: law.mass,
            stiffness: law.stiffness,
            exponent: n,
            loss_coefficient: eta,
            y_scale,
            t_scale,
            period,
            step,
        }))
    }

    /// The outcome of the dimensionless result `scaled`, in SI units.
    fn outcome(&self, mut scaled: Scaled, wall_time: f64) -> Outcome {
        let (n, v0, y_scale, t_scale) = (
            self.exponent,
            self.impact_velocity,
            self.y_scale,
            self.t_scale,
        );
        let force_scale = self.stiffness * y_scale.powf(n);
        let solved = &scaled.figures;
        let si = solved.map(|q, value| {
            value
                * match q {
                    Quantity::PeakDeformation => y_scale,
                    Quantity::PeakForce => force_scale,
                    Quantity::ContactTime | Quantity::CompressionTime => t_scale,
                    _ => 1.0,
                }
        });
        let cor = si.cor;
        let figures = ImpactFigures {
            figures: Exact {
                restitution_time: (solved.contact_time - solved.compression_time) * t_scale,
                ..si.select()
            },
            absorbed_energy: 0.5 * self.mass * v0 * v0 * (1.0 - cor * cor),
        };
        let trajectory = scaled
            .samples
            .drain(..)
            .map(|(t, y, v)| Sample {
                t: t * t_scale,
                y: y * y_scale,
                v: v * v0,
            })
            .collect();
        Outcome {
            figures,
            stats: scaled.stats,
            wall_time,
            timestep: self.method.is_fixed_step().then_some(self.step * t_scale),
            trajectory,
            crossing_speeds: scaled.crossing_speeds.iter().map(|s| s * v0).collect(),
        }
    }
}

/// `y^n` for `y >= 0`, in the cheapest exact-to-rounding form for the exponent: the right-hand
/// side evaluates it at every stage, and `powf` costs several times the rest of a stage.
trait Power: Copy {
    fn of(self, y: f64) -> f64;
    /// `k y^n`.
    #[inline]
    fn times(self, k: f64, y: f64) -> f64 {
        k * self.of(y)
    }
}

/// n = 1 (the rod): `y` itself, which is what `powf(y, 1)` returns.
#[derive(Clone, Copy)]
struct Linear;

/// n = 1.5 (Hertz): `y √y`, two correctly rounded operations, within an ulp of `powf`.
#[derive(Clone, Copy)]
struct Hertz;

/// Any other exponent: `powf`.
#[derive(Clone, Copy)]
struct AnyExponent(f64);

impl Power for Linear {
    #[inline]
    fn of(self, y: f64) -> f64 {
        y
    }
}

impl Power for Hertz {
    #[inline]
    fn of(self, y: f64) -> f64 {
        y * y.sqrt()
    }
    /// `(k y) √y`: `k y` is ready while the square root is still being taken, one
    /// multiplication fewer after it on the integrator's chain of dependent operations.
    #[inline]
    fn times(self, k: f64, y: f64) -> f64 {
        (k * y) * y.sqrt()
    }
}

impl Power for AnyExponent {
    #[inline]
    fn of(self, y: f64) -> f64 {
        y.powf(self.0)
    }
}

/// Dimensionless acceleration of the paper's law, `-((n+1)/2) |Y|^n sign(Y) (1 + η sign(Y V))`,
/// given `p = |Y|^n`; unilateral contact exerts nothing at `Y <= 0`.
#[inline]
fn paper_acceleration(p: f64, n: f64, eta: f64, bilateral: bool, y: f64, v: f64) -> f64 {
    if y == 0.0 || (!bilateral && y < 0.0) {
        return 0.0;
    }
    let direction = if y * v > 0.0 {
        1.0
    } else if y * v < 0.0 {
        -1.0
    } else {
        0.0
    };
    -0.5 * (n + 1.0) * p * y.signum() * (1.0 + eta * direction)
}

/// The paper's rk4 and velocity Verlet: a fixed step over the whole law, the contact end at the
/// first step past zero approach.
fn fixed_step(
    n: f64,
    eta: f64,
    h: f64,
    method: Method,
    bilateral: bool,
    duration: f64,
    settings: &Settings,
) -> Result<Scaled, SolveError> {
    with_power!(
        n,
        fixed_step_with(n, eta, h, method, bilateral, duration, settings)
    )
}

#[allow(clippy::too_many_arguments)]
fn fixed_step_with(
    power: impl Power,
    n: f64,
    eta: f64,
    h: f64,
    method: Method,
    bilateral: bool,
    duration: f64,
    settings: &Settings,
) -> Result<Scaled, SolveError> {
    // The acceleration at `s` given `p = |s[0]|^n`, and without it.
    let accel_with = |p: f64, s: &State| paper_acceleration(p, n, eta, bilateral, s[0], s[1]);
    let accel = |s: &State| accel_with(power.of(s[0].abs()), s);
    let rhs = |s: &State| State::new(s[1], accel(s));
    let force = |acceleration: f64| -acceleration / (0.5 * (n + 1.0));
    let mut out = Scaled::default();
    let mut y = State::new(0.0, 1.0);
    let mut t = 0.0;
    let mut a = accel(&y);
    let mut fy = rhs(&y);
    let mut first_end: Option<(f64, f64)> = None;
    let mut turning: Option<f64> = None;
    let record = settings.record;
    if record {
        out.samples.push((t, y[0], y[1]));
    }
    let mut steps = 0u64;
    let mut side = 1.0f64;
    loop {
        if steps > super::STEP_BUDGET {
            return Err(SolveError::StepBudget {
                method: method.name(),
                steps,
            });
        }
        let previous = y;
        // The acceleration at the new state: rk4's first stage of the next step, computed now;
        // Verlet's from the power its step has just taken.
        let acceleration = match method {
            Method::Rk4 => {
                y = rk4_step(&rhs, &y, &fy, h);
                fy = rhs(&y);
                out.stats.rhs_evaluations += 4;
                fy[1]
            }
            _ => {
                let half = y[1] + 0.5 * h * a;
                let position = y[0] + h * half;
                let p = power.of(position.abs());
                a = accel_with(p, &State::new(position, half));
                y = State::new(position, half + 0.5 * h * a);
                out.stats.rhs_evaluations += 1;
                accel_with(p, &y)
            }
        };
        t += h;
        steps += 1;
        if record {
            out.samples.push((t, y[0], y[1]));
        }
        if first_end.is_none() {
            out.figures.peak_deformation = out.figures.peak_deformation.max(y[0]);
            out.figures.peak_force = out.figures.peak_force.max(force(acceleration));
            if turning.is_none() && y[1] <= 0.0 {
                // The grid point of largest approach.
                turning = Some(if previous[0] >= y[0] { t - h } else { t });
            }
        }
        // A passage through zero approach: the state has left the side it was on. The side
        // starts as compression (ẏ(0) > 0), so a first step that lands at y < 0 (a step as long
        // as the contact) ends the contact too, instead of flying on forever.
        let crossed = if side > 0.0 { y[0] <= 0.0 } else { y[0] > 0.0 };
        if crossed {
            side = -side;
            if first_end.is_none() {
                first_end = Some((t, y[1].abs()));
            }
            if !bilateral {
                break;
            }
            out.crossing_speeds.push(y[1].abs());
        }
        if bilateral && first_end.is_some() && t >= duration {
            break;
        }
    }
    out.stats.steps = steps;
    let (end, speed) = first_end.expect("loop ends only after the first contact end");
    out.figures.cor = speed;
    out.figures.contact_time = end;
    out.figures.compression_time = turning.unwrap_or(end);
    Ok(out)
}

/// rk4-event and dopri5: each phase with its own smooth law (loading `1+η`, unloading `1-η`),
/// the turning point located on the step, the non-smooth ends by the contact series.
fn phased(
    n: f64,
    eta: f64,
    stepper: &mut impl Stepper,
    bilateral: bool,
    duration: f64,
    settings: &Settings,
) -> Result<Scaled, SolveError> {
    with_power!(
        n,
        phased_with(n, eta, stepper, bilateral, duration, settings)
    )
}

fn phased_with(
    power: impl Power,
    n: f64,
    eta: f64,
    stepper: &mut impl Stepper,
    bilateral: bool,
    duration: f64,
    settings: &Settings,
) -> Result<Scaled, SolveError> {
    let series = ContactSeries::for_exponent(n);
    let k_load = 0.5 * (n + 1.0) * (1.0 + eta);
    let k_unload = 0.5 * (n + 1.0) * (1.0 - eta);
    let load = move |s: &State| State::new(s[1], power.times(-k_load, s[0].max(0.0)));
    let unload = move |s: &State| State::new(s[1], power.times(-k_unload, s[0].max(0.0)));
    let rate = |s: &State| s[1];
    let approach = |s: &State| s[0];
    let mut out = Scaled::default();
    let record = settings.record;
    let (mut t, mut speed, mut sign) = (0.0f64, 1.0f64, 1.0f64);
    let mut samples = Vec::new();
    let mut first_contact = true;
    loop {
        // Bilateral half-cycles after the first mirror the first: the law is odd in y.
        let mut observe = |time: f64, s: &State| {
            if record {
                samples.push((time, sign * s[0], sign * s[1]));
            }
        };
        observe(t, &State::new(0.0, speed));
        // The series carries the start over a stretch fixed in τ, not in steps: the first
        // step of the method must begin where y^n is smooth on the scale of any step.
        let s0 = series.reach(k_load, speed);
        let (y0, v0) = series.advance(k_load, speed, s0);
        let start = State::new(y0, v0);
        out.stats.steps += 1;
        if record {
            // The series is exact over its stretch: sample it so the trajectory has no gap.
            for i in 1..SERIES_SAMPLES {
                let s = s0 * i as f64 / SERIES_SAMPLES as f64;
                let (y, v) = series.advance(k_load, speed, s);
                observe(t + s, &State::new(y, v));
            }
        }
        observe(t + s0, &start);
        stepper.set_phase_time_scale(1.0);
        let turn = march(
            &load,
            start,
            t + s0,
            stepper,
            &[&rate],
            None,
            &mut out.stats,
            &mut observe,
        )?;
        let peak = turn.state[0];
        // Unloading is slower by sqrt(k_load / k_unload) (the same peak, a softer spring): a
        // fixed step stays the same fraction of the phase's own period, so the work stays
        // bounded as η → 1 instead of growing like 1/e.
        stepper.set_phase_time_scale((k_load / k_unload).sqrt());
        let end = march(
            &unload,
            State::new(peak, 0.0),
            turn.time,
            stepper,
            &[&approach],
            Some(SeriesEnd {
                series: &series,
                k: k_unload,
            }),
            &mut out.stats,
            &mut observe,
        )?;
        let exit_speed = -end.state[1];
        if record && samples.len() >= 2 {
            // Fill the series' stretch before the exit, backwards from it, likewise.
            let exit = samples.pop().expect("the exit was recorded");
            let last_step = samples.last().expect("a step before the exit").0;
            let span = end.time - last_step;
            for i in (1..SERIES_SAMPLES).rev() {
                let s = span * i as f64 / SERIES_SAMPLES as f64;
                let (y, rate) = series.advance(k_unload, exit_speed, s);
                samples.push((end.time - s, sign * y, -sign * rate));
            }
            samples.push(exit);
        }
        if first_contact {
            out.figures = Figures {
                cor: exit_speed,
                peak_deformation: peak,
                peak_force: (1.0 + eta) * peak.powf(n),
                compression_time: turn.time,
                contact_time: end.time,
                ..Default::default()
            };
            first_contact = false;
        }
        if bilateral {
            out.crossing_speeds.push(exit_speed);
        }
        t = end.time;
        speed = exit_speed;
        sign = -sign;
        if !bilateral || t >= duration {
            break;
        }
    }
    out.samples = samples;
    Ok(out)
}

/// Impacts of rk4-event stepped together in interleaved lanes by [`solve_many`].
pub(crate) const LANES: usize = 4;

/// What a lane holds besides the state it steps: which impact, its factors and step, its
/// counters, and the turning point once found.
#[derive(Clone, Copy, Debug)]
struct LaneImpact {
    job: usize,
    eta: f64,
    k_load: f64,
    k_unload: f64,
    /// The stepper's step for the loading phase.
    base_step: f64,
    /// The stepper's step in the phase at hand.
    step: f64,
    /// Counters but for the steps of the phase at hand, which are added at its end.
    stats: Stats,
    turn_time: f64,
    peak: f64,
}

/// [`LANES`] impacts in flight, each in the state of `phased_with`'s marches one step at a
/// time. What every step reads and writes is held lane by lane in arrays (the RK4 stages of
/// all lanes are then plain arithmetic on arrays); the rest in [`LaneImpact`].
struct Lanes {
    active: [bool; LANES],
    unloading: [bool; LANES],
    /// The factor of the phase at hand (`k_load` or `k_unload`).
    k: [f64; LANES],
    /// The step the march tries next.
    h: [f64; LANES],
    y: [f64; LANES],
    v: [f64; LANES],
    /// The right-hand side at `(y, v)`: `(v, a)`.
    a: [f64; LANES],
    t: [f64; LANES],
    g_now: [f64; LANES],
    /// Steps taken in the phase at hand.
    phase_steps: [u64; LANES],
    impact: [LaneImpact; LANES],
}

/// rk4-event on unilateral contacts of exponent `n`, one impact per `(η, step)` of `jobs`,
/// [`LANES`] at a time: the same arithmetic as `phased` with an [`Rk4`] stepper, operation for
/// operation, so each result equals that of a single chain to the last bit. The RK4 stages of
/// every lane are computed side by side; what only one lane meets (the series at the ends, the
/// turning point and contact end located on the step, a refused step) is done for it alone
/// with the very functions the single chain uses.
fn rk4_event_lanes(
    power: impl Power,
    n: f64,
    jobs: &[(f64, f64)],
) -> Vec<Result<Scaled, SolveError>> {
    let series = ContactSeries::for_exponent(n);
    let mut results: Vec<Option<Result<Scaled, SolveError>>> =
        (0..jobs.len()).map(|_| None).collect();
    let idle = LaneImpact {
        job: usize::MAX,
        eta: 0.0,
        k_load: 0.0,
        k_unload: 0.0,
        base_step: 0.0,
        step: 0.0,
        stats: Stats::default(),
        turn_time: 0.0,
        peak: 0.0,
    };
    let mut lanes = Lanes {
        active: [false; LANES],
        unloading: [false; LANES],
        k: [0.0; LANES],
        h: [0.0; LANES],
        y: [0.0; LANES],
        v: [0.0; LANES],
        a: [0.0; LANES],
        t: [0.0; LANES],
        g_now: [0.0; LANES],
        phase_steps: [0; LANES],
        impact: [idle; LANES],
    };
    let mut next_job = 0;
    // The right-hand side of a phase with factor `k`, as `phased_with` writes it.
    let rhs_of = |k: f64| move |s: &State| State::new(s[1], power.times(-k, s[0].max(0.0)));
    loop {
        // Each lane: start an impact if it has none, then the checks a march makes before a
        // step; a lane whose impact ends there takes the next one.
        for l in 0..LANES {
            loop {
                if !lanes.active[l] {
                    if next_job == jobs.len() {
                        break;
                    }
                    let (eta, h) = jobs[next_job];
                    lanes.start(l, power, &series, n, eta, h, next_job);
                    next_job += 1;
                }
                match lanes.before_step(l, &series, n) {
                    None => break,
                    Some(result) => {
                        results[lanes.impact[l].job] = Some(result);
                        lanes.active[l] = false;
                    }
                }
            }
        }
        if !lanes.active.iter().any(|&a| a) {
            break;
        }
        // One RK4 step of every lane, side by side (an idle lane steps a harmless state), and
        // the acceleration at each step's end, which the march needs if the step is taken.
        let (y1, v1, a1) = lanes.rk4_step(power);
        for l in 0..LANES {
            if !lanes.active[l] {
                continue;
            }
            let g_next = if lanes.unloading[l] { y1[l] } else { v1[l] };
            let finite = y1[l].is_finite() && v1[l].is_finite();
            if finite && !super::changes_sign(lanes.g_now[l], g_next) {
                lanes.t[l] += lanes.h[l];
                lanes.y[l] = y1[l];
                lanes.v[l] = v1[l];
                lanes.a[l] = a1[l];
                lanes.g_now[l] = g_next;
                lanes.phase_steps[l] += 1;
                lanes.h[l] = lanes.impact[l].step;
                continue;
            }
            // A refused step, or an event inside this one.
            if !finite {
                let impact = &mut lanes.impact[l];
                impact.stats.rhs_evaluations += 3;
                impact.stats.rejected += 1;
                lanes.h[l] = impact.step.min(0.5 * lanes.h[l]);
                continue;
            }
            lanes.end_phase_steps(l);
            let impact = &mut lanes.impact[l];
            impact.stats.rhs_evaluations += 3;
            let rhs = rhs_of(lanes.k[l]);
            let mut stepper = Rk4::new(impact.step);
            let event = if lanes.unloading[l] { 0 } else { 1 };
            let (theta, located) = super::locate(
                &rhs,
                &mut stepper,
                &State::new(lanes.y[l], lanes.v[l]),
                &State::new(lanes.v[l], lanes.a[l]),
                lanes.h[l],
                |s: &State| s[event],
                lanes.g_now[l],
                &mut impact.stats,
            );
            impact.stats.steps += 1;
            let time = lanes.t[l] + theta * lanes.h[l];
            if lanes.unloading[l] {
                results[impact.job] = Some(Ok(impact.finish(n, time, located)));
                lanes.active[l] = false;
            } else {
                lanes.unload(l, power, time, located[0]);
            }
        }
    }
    results
        .into_iter()
        .map(|r| r.expect("every job ran in a lane"))
        .collect()
}

impl Lanes {
    /// Lane `l` at the start of an impact: the series over the first stretch, then the
    /// loading march's start (`phased_with` and `march`).
    #[allow(clippy::too_many_arguments)]
    fn start(
        &mut self,
        l: usize,
        power: impl Power,
        series: &ContactSeries,
        n: f64,
        eta: f64,
        h: f64,
        job: usize,
    ) {
        let k_load = 0.5 * (n + 1.0) * (1.0 + eta);
        let k_unload = 0.5 * (n + 1.0) * (1.0 - eta);
        let speed = 1.0;
        let s0 = series.reach(k_load, speed);
        let (y0, v0) = series.advance(k_load, speed, s0);
        let mut stats = Stats::default();
        // The series' stretch is a step; the march evaluates the right-hand side at its start.
        stats.steps += 1;
        stats.rhs_evaluations += 1;
        // Rk4::set_phase_time_scale(1.0): the step is the base step.
        let step = h * 1.0;
        self.active[l] = true;
        self.unloading[l] = false;
        self.k[l] = k_load;
        self.h[l] = step;
        self.y[l] = y0;
        self.v[l] = v0;
        self.a[l] = power.times(-k_load, y0.max(0.0));
        self.t[l] = s0;
        self.g_now[l] = v0;
        self.phase_steps[l] = 0;
        self.impact[l] = LaneImpact {
            job,
            eta,
            k_load,
            k_unload,
            base_step: h,
            step,
            stats,
            turn_time: 0.0,
            peak: 0.0,
        };
    }

    /// Add the steps of lane `l`'s phase so far to its counters (each took three evaluations
    /// in the step and one at its end).
    fn end_phase_steps(&mut self, l: usize) {
        let steps = std::mem::take(&mut self.phase_steps[l]);
        let stats = &mut self.impact[l].stats;
        stats.steps += steps;
        stats.rhs_evaluations += 4 * steps;
    }

    /// The turning point of lane `l` found at `time` with approach `peak`: the unloading
    /// march's start.
    fn unload(&mut self, l: usize, power: impl Power, time: f64, peak: f64) {
        let impact = &mut self.impact[l];
        impact.turn_time = time;
        impact.peak = peak;
        impact.step = impact.base_step * (impact.k_load / impact.k_unload).sqrt();
        impact.stats.rhs_evaluations += 1;
        self.unloading[l] = true;
        self.k[l] = impact.k_unload;
        self.h[l] = impact.step;
        self.y[l] = peak;
        self.v[l] = 0.0;
        self.a[l] = power.times(-impact.k_unload, peak.max(0.0));
        self.t[l] = time;
        self.g_now[l] = peak;
        self.phase_steps[l] = 0;
    }

    /// The checks `march` makes before each step of lane `l`: the step budget, the step's
    /// underflow, and in the unloading phase the series' reach of the contact end. `Some`
    /// when the impact ends here.
    fn before_step(
        &mut self,
        l: usize,
        series: &ContactSeries,
        n: f64,
    ) -> Option<Result<Scaled, SolveError>> {
        if let Err(e) = super::step_guard(self.phase_steps[l], self.t[l], self.h[l]) {
            return Some(Err(e));
        }
        if self.unloading[l]
            && self.v[l] < 0.0
            && series.within_reach_of_end(self.k[l], self.y[l], self.v[l], self.a[l])
            && let Some((s, v)) = series.time_to_exit(self.k[l], self.y[l], self.v[l])
        {
            self.end_phase_steps(l);
            let impact = &mut self.impact[l];
            impact.stats.steps += 1;
            return Some(Ok(impact.finish(n, self.t[l] + s, State::new(0.0, -v))));
        }
        None
    }

    /// One RK4 step (`rk4_step`, its operations in its order) of every lane, and the
    /// acceleration at each step's end: `(y, v, a)` there.
    #[inline]
    fn rk4_step(&self, power: impl Power) -> ([f64; LANES], [f64; LANES], [f64; LANES]) {
        let (h, k, y, v, a) = (&self.h, &self.k, &self.y, &self.v, &self.a);
        // The acceleration `power.times(-k, y.max(0))` of each lane.
        let accel = |at: &[f64; LANES]| -> [f64; LANES] {
            std::array::from_fn(|l| power.times(-k[l], at[l].max(0.0)))
        };
        let half: [f64; LANES] = std::array::from_fn(|l| 0.5 * h[l]);
        // k2 = f(y + h/2 k1), k1 = (v, a).
        let y2: [f64; LANES] = std::array::from_fn(|l| y[l] + half[l] * v[l]);
        let v2: [f64; LANES] = std::array::from_fn(|l| v[l] + half[l] * a[l]);
        let a2 = accel(&y2);
        // k3 = f(y + h/2 k2), k2 = (v2, a2).
        let y3: [f64; LANES] = std::array::from_fn(|l| y[l] + half[l] * v2[l]);
        let v3: [f64; LANES] = std::array::from_fn(|l| v[l] + half[l] * a2[l]);
        let a3 = accel(&y3);
        // k4 = f(y + h k3), k3 = (v3, a3).
        let y4: [f64; LANES] = std::array::from_fn(|l| y[l] + h[l] * v3[l]);
        let v4: [f64; LANES] = std::array::from_fn(|l| v[l] + h[l] * a3[l]);
        let a4 = accel(&y4);
        // y + h/6 (k1 + 2 k2 + 2 k3 + k4).
        let sixth: [f64; LANES] = std::array::from_fn(|l| h[l] / 6.0);
        let y_end: [f64; LANES] =
            std::array::from_fn(|l| y[l] + sixth[l] * (v[l] + 2.0 * v2[l] + 2.0 * v3[l] + v4[l]));
        let v_end: [f64; LANES] =
            std::array::from_fn(|l| v[l] + sixth[l] * (a[l] + 2.0 * a2[l] + 2.0 * a3[l] + a4[l]));
        let a_end = accel(&y_end);
        (y_end, v_end, a_end)
    }
}

impl LaneImpact {
    /// The figures of an impact that ended at `time` in `state` (`phased_with`).
    fn finish(&self, n: f64, time: f64, state: State) -> Scaled {
        Scaled {
            figures: Figures {
                cor: -state[1],
                peak_deformation: self.peak,
                peak_force: (1.0 + self.eta) * self.peak.powf(n),
                compression_time: self.turn_time,
                contact_time: time,
                ..Default::default()
            },
            stats: self.stats,
            samples: Vec::new(),
            crossing_speeds: Vec::new(),
        }
    }
}
