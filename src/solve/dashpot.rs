//! The DEM codes' own viscoelastic laws ([`DashpotLaw`]), integrated two ways: stepped the way
//! each code steps (to reproduce its trajectory), and to near zero step error (to measure the
//! model's own figures).

use serde::{Deserialize, Serialize};

use super::steppers::{Dopri5, State};
use super::{SolveError, march};
use crate::model::law::DashpotLaw;
use crate::model::trajectory::{CodeTrajectory, TrajectoryMetrics};

/// How a DEM code advances one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StepScheme {
    /// Velocity Verlet (LAMMPS and LIGGGHTS `fix nve/sphere`): half kick, drift, force from the
    /// new position and the half-step velocity, half kick.
    VelocityVerlet,
    /// Leap-frog (YADE's NewtonIntegrator): force from the current position and the velocity of
    /// the previous half step, kick, drift.
    LeapFrog,
}

/// Step `law` from touching contact at approach speed `impact_velocity` (m/s) with a fixed
/// `timestep` (s) for `steps` steps, the way a DEM code does. Row 0 is the initial state; row
/// `k` is the state after `k` steps (for leap-frog the velocity is the half-step one, as the
/// code reports it). The force column is the force at that row's state, as the codes print it:
/// for velocity Verlet the force computed in the step that led to the row, for leap-frog the
/// one the next step kicks with (from the row's position and half-step velocity).
pub fn step_trajectory(
    law: &DashpotLaw,
    impact_velocity: f64,
    timestep: f64,
    steps: u64,
    scheme: StepScheme,
) -> CodeTrajectory {
    step_trajectory_from(law, impact_velocity, timestep, steps, scheme, 0.0)
}

/// [`step_trajectory`] started `gap` (m) before touch instead of at touch: with
/// `gap = φ v0 Δt`, `φ ∈ [0, 1)`, the first contact falls at the fraction `1 − φ` of a step
/// (the start phase), the one thing a fixed-step run's figures depend on besides the step.
pub fn step_trajectory_from(
    law: &DashpotLaw,
    impact_velocity: f64,
    timestep: f64,
    steps: u64,
    scheme: StepScheme,
    gap: f64,
) -> CodeTrajectory {
    // Only a hint: a count beyond memory is left to grow as the steps come.
    let capacity = usize::try_from(steps).map_or(0, |n| n.saturating_add(1).min(1 << 24));
    let mut out = CodeTrajectory {
        time: Vec::with_capacity(capacity),
        overlap: Vec::with_capacity(capacity),
        approach_velocity: Vec::with_capacity(capacity),
        normal_force: Vec::with_capacity(capacity),
    };
    let (mut y, mut v) = (-gap, impact_velocity);
    let mut force = match scheme {
        StepScheme::VelocityVerlet => 0.0,
        StepScheme::LeapFrog => law.force(y, v),
    };
    let h = timestep;
    let inverse_mass = 1.0 / law.mass;
    let mut push = |k: u64, y: f64, v: f64, f: f64| {
        out.time.push(k as f64 * h);
        out.overlap.push(y);
        out.approach_velocity.push(v);
        out.normal_force.push(f);
    };
    push(0, y, v, force);
    for k in 1..=steps {
        match scheme {
            StepScheme::VelocityVerlet => {
                let half = v - 0.5 * h * force * inverse_mass;
                y += h * half;
                force = law.force(y, half);
                v = half - 0.5 * h * force * inverse_mass;
            }
            StepScheme::LeapFrog => {
                // The force from the previous row's state kicks; the row then carries the force
                // of its own state (a row's force column is never one step behind its overlap).
                v -= h * force * inverse_mass;
                y += h * v;
                force = law.force(y, v);
            }
        }
        push(k, y, v, force);
    }
    out
}

/// Figures of `law`'s impact at speed `impact_velocity` (m/s), integrated with error control at
/// relative tolerance `rtol`, with the largest force, the turning point (end of compression),
/// the force's first return to zero (force-based contact end) and the overlap's return to zero
/// (overlap-based contact end) located on the step as events.
pub fn accurate_metrics(
    law: &DashpotLaw,
    impact_velocity: f64,
    rtol: f64,
) -> Result<TrajectoryMetrics, SolveError> {
    let n = law.exponent;
    let m = law.damping_exponent;
    let y_scale = law.elastic_peak(impact_velocity);
    let t_scale = y_scale / impact_velocity;
    let k = 0.5 * (n + 1.0);
    let d = law.damping * impact_velocity * y_scale.powf(m - n) / law.stiffness;
    let clamp = law.clamp_attractive;
    let force = move |s: &State| -> f64 {
        let y = s[0].max(0.0);
        let f = y.powf(n) + d * y.powf(m) * s[1];
        if clamp { f.max(0.0) } else { f }
    };
    let rhs = move |s: &State| State::new(s[1], -k * force(s));
    let mut stats = super::Stats::default();
    let mut observe = |_t: f64, _s: &State| {};
    let mut stepper = Dopri5::new(rtol);
    // The largest force comes before the turning point (the dashpot pushes while the bodies
    // approach), where dF/dτ = n Y^(n-1) V + d (m Y^(m-1) V² + Y^m A) vanishes; the largest
    // overlap is at V = 0. Both are located, not read off the steps.
    let force_rate = move |s: &State| -> f64 {
        let (y, v) = (s[0], s[1]);
        if y <= 0.0 {
            return 1.0;
        }
        let a = -k * force(s);
        // A linear dashpot (m = 0) has no y^(m-1) term, which would be 0 · ∞ at tiny y.
        let dashpot_growth = if m == 0.0 {
            0.0
        } else {
            m * y.powf(m - 1.0) * v * v
        };
        n * y.powf(n - 1.0) * v + d * (dashpot_growth + y.powf(m) * a)
    };
    let rate = |s: &State| s[1];
    let top = march(
        &rhs,
        State::new(0.0, 1.0),
        0.0,
        &mut stepper,
        &[&force_rate as &dyn Fn(&State) -> f64, &rate],
        None,
        &mut stats,
        &mut observe,
    )?;
    let peak_force = force(&top.state);
    let turn = if top.event == 0 && top.state[1] > 0.0 {
        march(
            &rhs,
            top.state,
            top.time,
            &mut stepper,
            &[&rate],
            None,
            &mut stats,
            &mut observe,
        )?
    } else {
        top
    };
    let peak = turn.state[0];
    let event_exit = |s: &State| s[0];
    // The force first returns to zero before the overlap closes: the dashpot cancels the spring
    // while the bodies separate. Unclamped, the force then attracts until the overlap is zero;
    // clamped, separation is final there, since the force would stay attractive while the
    // overlap shrinks at constant speed, and the bodies fly apart until the overlap is zero.
    let event_force = |s: &State| {
        let y = s[0].max(0.0);
        y.powf(n) + d * y.powf(m) * s[1]
    };
    let crossing = march(
        &rhs,
        turn.state,
        turn.time,
        &mut stepper,
        &[&event_force as &dyn Fn(&State) -> f64, &event_exit],
        None,
        &mut stats,
        &mut observe,
    )?;
    let force_end = crossing.time;
    let end = if clamp {
        let (t, s) = (crossing.time, crossing.state);
        let free_flight = if s[0] > 0.0 { s[0] / -s[1] } else { 0.0 };
        (t + free_flight, s[1])
    } else if crossing.event == 0 && crossing.state[0] > 0.0 {
        let exit = march(
            &rhs,
            crossing.state,
            crossing.time,
            &mut stepper,
            &[&event_exit],
            None,
            &mut stats,
            &mut observe,
        )?;
        (exit.time, exit.state[1])
    } else {
        (crossing.time, crossing.state[1])
    };
    Ok(TrajectoryMetrics {
        cor: -end.1,
        peak_deformation: peak * y_scale,
        peak_force: peak_force * law.stiffness * y_scale.powf(n),
        contact_time: end.0 * t_scale,
        force_contact_time: force_end * t_scale,
        compression_time: turn.time * t_scale,
    })
}
