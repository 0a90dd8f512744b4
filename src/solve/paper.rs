//! One impact of the paper's law by each method.

use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::series::ContactSeries;
use super::steppers::{Dopri5, Rk4, State, Stepper, rk4_step};
use super::{Method, SeriesEnd, SolveError, Stats, march};
use crate::model::case::ContactKind;
use crate::model::exact::{self, ImpactFigures, j_integral};
use crate::model::law::PaperLaw;

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

/// Trajectory samples drawn from each stretch the contact series carries.
const SERIES_SAMPLES: usize = 16;

/// Dimensionless result.
#[derive(Default)]
struct Scaled {
    cor: f64,
    peak: f64,
    peak_force: f64,
    compression_time: f64,
    contact_time: f64,
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
    let v0 = impact_velocity;
    let y_scale = law.elastic_peak(v0);
    let t_scale = y_scale / v0;
    let (n, eta) = (law.exponent, law.loss_coefficient);
    let period = 4.0 * j_integral_for(n);
    let method = settings.method;
    if !method.integrates() {
        let figures = exact::paper_impact(law, v0);
        return Ok(Outcome {
            figures,
            stats: Stats::default(),
            wall_time: started.elapsed().as_secs_f64(),
            timestep: None,
            trajectory: Vec::new(),
            crossing_speeds: Vec::new(),
        });
    }
    let h = match settings.timestep {
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
    let bilateral = settings.contact == ContactKind::Bilateral;
    let duration = settings.periods * period;
    let mut scaled = match method {
        Method::Rk4 | Method::Verlet => {
            fixed_step(n, eta, h, method, bilateral, duration, settings)?
        }
        Method::Rk4Event => {
            let mut stepper = Rk4::new(h);
            phased(n, eta, &mut stepper, bilateral, duration, settings)?
        }
        Method::Dopri5 => {
            let mut stepper = Dopri5::new(settings.rtol);
            phased(n, eta, &mut stepper, bilateral, duration, settings)?
        }
        Method::Exact => unreachable!("handled above"),
    };
    let wall_time = started.elapsed().as_secs_f64();
    let cor = scaled.cor;
    let force_scale = law.stiffness * y_scale.powf(n);
    let figures = ImpactFigures {
        cor,
        peak_deformation: scaled.peak * y_scale,
        peak_force: scaled.peak_force * force_scale,
        compression_time: scaled.compression_time * t_scale,
        restitution_time: (scaled.contact_time - scaled.compression_time) * t_scale,
        contact_time: scaled.contact_time * t_scale,
        absorbed_energy: 0.5 * law.mass * v0 * v0 * (1.0 - cor * cor),
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
    Ok(Outcome {
        figures,
        stats: scaled.stats,
        wall_time,
        timestep: method.is_fixed_step().then_some(h * t_scale),
        trajectory,
        crossing_speeds: scaled.crossing_speeds.iter().map(|s| s * v0).collect(),
    })
}

/// [`j_integral`] (two gamma functions), remembered per thread for the last exponent asked for.
fn j_integral_for(n: f64) -> f64 {
    thread_local! {
        static LAST: std::cell::Cell<Option<(u64, f64)>> = const { std::cell::Cell::new(None) };
    }
    LAST.with(|last| match last.get() {
        Some((bits, j)) if bits == n.to_bits() => j,
        _ => {
            let j = j_integral(n);
            last.set(Some((n.to_bits(), j)));
            j
        }
    })
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
            out.peak = out.peak.max(y[0]);
            out.peak_force = out.peak_force.max(force(acceleration));
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
    out.cor = speed;
    out.contact_time = end;
    out.compression_time = turning.unwrap_or(end);
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
            out.cor = exit_speed;
            out.peak = peak;
            out.peak_force = (1.0 + eta) * peak.powf(n);
            out.compression_time = turn.time;
            out.contact_time = end.time;
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

/// The closed-form figures, for comparison with a run.
pub fn exact_figures(law: &PaperLaw, impact_velocity: f64) -> ImpactFigures {
    exact::paper_impact(law, impact_velocity)
}
