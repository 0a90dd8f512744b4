//! The DEM codes' own laws ([`CodeLaw`]: their viscoelastic [`DashpotLaw`]s, and the paper's law
//! where a code has it built in), integrated two ways: stepped the way each code steps (to
//! reproduce its trajectory), and to near zero step error (to measure the model's own figures;
//! for the paper's law, its closed form).

use serde::{Deserialize, Serialize};

use super::steppers::{Dopri5, State};
use super::{SolveError, march};
use crate::model::exact::paper_impact;
use crate::model::law::{CodeLaw, ContactForce, DashpotLaw, PaperLaw};
use crate::model::trajectory::{CodeTrajectory, TrajectoryMetrics};

/// A contact force as a DEM code evaluates it within one step of its run: what the steppers
/// below call. A law whose force depends on the step (the paper's law as LIGGGHTS `model
/// paper` codes it, `paper_force_in_step`) says how; any other is its [`ContactForce`].
pub trait StepForce: ContactForce {
    /// Force, N (positive repulsive), at approach `y` (m) and approach rate `v` (m/s), in a
    /// step of `timestep` (s).
    fn force_in_step(&self, y: f64, v: f64, timestep: f64) -> f64 {
        let _ = timestep;
        self.force(y, v)
    }
}

impl StepForce for DashpotLaw {}

impl StepForce for CodeLaw {
    fn force_in_step(&self, y: f64, v: f64, timestep: f64) -> f64 {
        match self {
            CodeLaw::Dashpot(law) => law.force(y, v),
            CodeLaw::Paper(law) => paper_force_in_step(law, y, v, timestep),
        }
    }
}

/// The paper's force `C yⁿ (1 + η s)`, N, at approach `y` (m) and approach rate `v` (m/s), as
/// LIGGGHTS `model paper` (scripts/liggghts-paper/normal_model_paper.h) evaluates it in a step
/// of `timestep` (s), with the same operations in the same order.
///
/// The law is set-valued at `ẏ = 0` (a contact at rest may carry any force between
/// `C yⁿ (1 − η)` and `C yⁿ (1 + η)`), and one step cannot resolve the sign of a velocity
/// smaller than the change one step's jump between the branches makes,
/// `band = 2η C yⁿ Δt / M`: a plain sign flips the branch every step in a resting contact.
/// So `s` is the sign of `v` outside the band and `v / band` inside it: there the dissipative
/// force is `M v / (2Δt)`, which halves a lone contact's approach rate per step, and a contact
/// at rest carries its load on the elastic force `C yⁿ`. An impact meets the band only within
/// about a step of its turning point.
pub(crate) fn paper_force_in_step(law: &PaperLaw, y: f64, v: f64, timestep: f64) -> f64 {
    if y <= 0.0 {
        return 0.0;
    }
    let eta = law.loss_coefficient;
    let elastic = law.stiffness * y.powf(law.exponent);
    let band = 2.0 * eta * elastic * timestep / law.mass;
    // η = 0 (band 0) takes the first or second branch, both the elastic force.
    let branch = if v >= band {
        1.0 + eta
    } else if v <= -band {
        1.0 - eta
    } else {
        1.0 + eta * (v / band)
    };
    elastic * branch
}

impl CodeTrajectory {
    /// An empty trajectory with room for a run of `steps` steps; only a hint: a count beyond
    /// memory is left to grow as the steps come.
    fn for_steps(steps: u64) -> CodeTrajectory {
        let rows = usize::try_from(steps).map_or(0, |n| n.saturating_add(1).min(1 << 24));
        CodeTrajectory {
            time: Vec::with_capacity(rows),
            overlap: Vec::with_capacity(rows),
            approach_velocity: Vec::with_capacity(rows),
            normal_force: Vec::with_capacity(rows),
        }
    }
}

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

/// Step `law` (any force a code evaluates: a [`DashpotLaw`], a [`CodeLaw`]) from touching contact at approach speed `impact_velocity` (m/s) with a fixed
/// `timestep` (s) for `steps` steps, the way a DEM code does. Row 0 is the initial state; row
/// `k` is the state after `k` steps (for leap-frog the velocity is the half-step one, as the
/// code reports it). The force column is the force at that row's state, as the codes print it:
/// for velocity Verlet the force computed in the step that led to the row, for leap-frog the
/// one the next step kicks with (from the row's position and half-step velocity).
///
/// With velocity Verlet the force sees the half-step velocity, so a law whose force depends on
/// the sign of the velocity (the paper's) switches branch where the half-step velocity does,
/// within the band of `paper_force_in_step`, as LIGGGHTS `model paper` does from the `vn`
/// it is handed.
pub fn step_trajectory<L: StepForce + ?Sized>(
    law: &L,
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
pub fn step_trajectory_from<L: StepForce + ?Sized>(
    law: &L,
    impact_velocity: f64,
    timestep: f64,
    steps: u64,
    scheme: StepScheme,
    gap: f64,
) -> CodeTrajectory {
    let mut out = CodeTrajectory::for_steps(steps);
    let (mut y, mut v) = (-gap, impact_velocity);
    let mut force = match scheme {
        StepScheme::VelocityVerlet => 0.0,
        StepScheme::LeapFrog => law.force_in_step(y, v, timestep),
    };
    let h = timestep;
    let inverse_mass = 1.0 / law.mass();
    out.push_row(0.0, y, v, force);
    for k in 1..=steps {
        match scheme {
            StepScheme::VelocityVerlet => {
                let half = v - 0.5 * h * force * inverse_mass;
                y += h * half;
                force = law.force_in_step(y, half, h);
                v = half - 0.5 * h * force * inverse_mass;
            }
            StepScheme::LeapFrog => {
                // The force from the previous row's state kicks; the row then carries the force
                // of its own state (a row's force column is never one step behind its overlap).
                v -= h * force * inverse_mass;
                y += h * v;
                force = law.force_in_step(y, v, h);
            }
        }
        out.push_row(k as f64 * h, y, v, force);
    }
    out
}

/// One body on the line of centres (the z axis) as a code holds it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameBody {
    /// Height of its centre, m.
    pub height: f64,
    /// Velocity along z (up positive), m/s.
    pub velocity: f64,
    /// Mass, kg.
    pub mass: f64,
}

/// The start of a run in a code's own coordinates: a sphere above, and below it a second
/// sphere or a wall at height 0.
///
/// A code holds each body's absolute position, so each step rounds a position to an ulp of the
/// height (3.5e-18 m at 2 cm), not of the overlap (1e-20 m at 70 µm): over a thousand steps that
/// moves the figures by some 1e-12. Stepped in the same coordinates with the same operations,
/// the law repeats the code's rounding of the positions, and what is left are single roundings
/// of the force (a few 1e-16 per step).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CodeFrame {
    /// Distance of the centres at touch, m: the sum of the radii, the upper radius at a wall.
    pub reach: f64,
    /// The upper sphere (it moves down onto the other body).
    pub upper: FrameBody,
    /// The lower sphere; `None` for a wall, the plane z = 0.
    pub lower: Option<FrameBody>,
}

/// Step `law` by velocity Verlet in `frame`'s coordinates, for `steps` steps of `timestep` (s),
/// with the operations of LIGGGHTS's `fix nve/sphere` and of its wall and pair contact: per
/// body `v += (½Δt / m) f`, `z += Δt v`, then the overlap `reach − (z₁ − z₂)` (`reach − z₁` at
/// the wall: the wall's `r − (r − (r − z))` is that exactly, both near r) and the approach rate
/// `v₂ − v₁` from the half-step velocities, the force, and the second half kick. Rows as
/// [`step_trajectory`]'s: row 0 the start, then one per step with the full-step approach rate
/// and the force computed in that step.
pub(crate) fn step_in_frame<L: StepForce + ?Sized>(
    law: &L,
    frame: &CodeFrame,
    timestep: f64,
    steps: u64,
) -> CodeTrajectory {
    let mut out = CodeTrajectory::for_steps(steps);
    let h = timestep;
    // fix nve/sphere's dtf = 0.5 dt ftm2v (ftm2v = 1 in SI units), dtfm = dtf / m.
    let dtf = 0.5 * h;
    let wall = FrameBody {
        height: 0.0,
        velocity: 0.0,
        mass: f64::INFINITY,
    };
    let (mut upper, mut lower) = (frame.upper, frame.lower.unwrap_or(wall));
    let moves_lower = frame.lower.is_some();
    let overlap = |a: &FrameBody, b: &FrameBody| {
        if moves_lower {
            frame.reach - (a.height - b.height)
        } else {
            frame.reach - a.height
        }
    };
    let approach = |a: &FrameBody, b: &FrameBody| b.velocity - a.velocity;
    let mut force = 0.0;
    out.push_row(
        0.0,
        overlap(&upper, &lower),
        approach(&upper, &lower),
        force,
    );
    for k in 1..=steps {
        let kick = |body: &mut FrameBody, f: f64| {
            body.velocity += dtf / body.mass * f;
        };
        kick(&mut upper, force);
        upper.height += h * upper.velocity;
        if moves_lower {
            kick(&mut lower, -force);
            lower.height += h * lower.velocity;
        }
        let y = overlap(&upper, &lower);
        force = law.force_in_step(y, approach(&upper, &lower), h);
        kick(&mut upper, force);
        if moves_lower {
            kick(&mut lower, -force);
        }
        out.push_row(k as f64 * h, y, approach(&upper, &lower), force);
    }
    out
}

/// Step `law` by leap-frog in `frame`'s coordinates, for `steps` steps of `timestep` (s), with
/// the operations of YADE's `NewtonIntegrator` stepping a force that a hook between
/// `ForceResetter` and the integrator adds (`yade-paper`): the overlap `reach − (z₁ − z₂)`
/// (`reach − z₁` at the wall) and the approach rate `v₂ − v₁` from the positions `z_i` and the
/// half-step velocities `v_{i−½}`, the force, then per body `v += Δt (f / m)` and `z += v Δt`.
/// Rows as [`step_trajectory`]'s leap-frog rows: row `k` the position after `k` steps, the
/// half-step velocity that led to it and the force the next step kicks with.
///
/// A code whose bodies approach along +z (YADE's sphere below its plane) is the same frame
/// mirrored: every coordinate and velocity negated, which is exact, so the differences of
/// positions and velocities, the forces and the roundings are the code's own.
pub(crate) fn step_in_leap_frog_frame<L: StepForce + ?Sized>(
    law: &L,
    frame: &CodeFrame,
    timestep: f64,
    steps: u64,
) -> CodeTrajectory {
    let mut out = CodeTrajectory::for_steps(steps);
    let h = timestep;
    let (mut upper, mut lower) = (frame.upper, frame.lower);
    for k in 0..=steps {
        let y = match &lower {
            Some(lower) => frame.reach - (upper.height - lower.height),
            None => frame.reach - upper.height,
        };
        let rate = lower.as_ref().map_or(0.0, |l| l.velocity) - upper.velocity;
        let force = law.force_in_step(y, rate, h);
        out.push_row(k as f64 * h, y, rate, force);
        upper.velocity += h * (force / upper.mass);
        upper.height += upper.velocity * h;
        if let Some(lower) = &mut lower {
            lower.velocity += h * (-force / lower.mass);
            lower.height += lower.velocity * h;
        }
    }
    out
}

/// How a code steps its law: its scheme, and where it has one, its own coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CodeStepping {
    /// The scheme.
    pub scheme: StepScheme,
    /// The run's start in the code's own coordinates (stepped by `step_in_frame` for
    /// velocity Verlet, `step_in_leap_frog_frame` for leap-frog); `None`: from touch, in the
    /// coordinates of the relative motion.
    pub frame: Option<CodeFrame>,
}

impl CodeStepping {
    /// `law` stepped as the code steps it, from `impact_velocity` (m/s, used without a frame)
    /// for `steps` steps of `timestep` (s), started a further `gap` (m) away than the code's
    /// own start (a start phase: 0 for the run's own).
    pub fn trajectory<L: StepForce + ?Sized>(
        &self,
        law: &L,
        impact_velocity: f64,
        timestep: f64,
        steps: u64,
        gap: f64,
    ) -> CodeTrajectory {
        match (self.scheme, self.frame) {
            (StepScheme::VelocityVerlet, Some(frame)) => {
                let mut frame = frame;
                frame.upper.height += gap;
                step_in_frame(law, &frame, timestep, steps)
            }
            (StepScheme::LeapFrog, Some(frame)) => {
                let mut frame = frame;
                frame.upper.height += gap;
                step_in_leap_frog_frame(law, &frame, timestep, steps)
            }
            (scheme, None) => {
                step_trajectory_from(law, impact_velocity, timestep, steps, scheme, gap)
            }
        }
    }
}

/// The largest COR error, absolute, that velocity Verlet (with the force of
/// `paper_force_in_step` from the half-step velocity, as LIGGGHTS `model paper` takes it)
/// makes on the paper's `law` at step `timestep` (s) and speed `impact_velocity` (m/s): the
/// bound a run's realised COR keeps to `sqrt((1 − η)/(1 + η))`, whatever its start phase.
///
/// Each branch, `C yⁿ (1 ± η)`, is conservative: the steps lose energy at the turning point
/// alone, through two errors, with `F_{L,U} = C y_maxⁿ (1 ± η)` and `k = F_L Δt / (M v0)`:
///
/// - The band. Within `|ẏ| < w = 2η C y_maxⁿ Δt / M` the dissipative force is `M ẏ / (2Δt)`
///   instead of `η C yⁿ sign ẏ`, which dissipates less by `η M w² / 3` (the band crossed at the
///   deceleration `C y_maxⁿ / M`), raising the COR by `4η³ k² / (3 e (1 + η)²)`. The runs
///   measure up to 1.33 times that (the deceleration varies across the band): the term is
///   taken 4/3 times.
/// - The sampling. Where the band is narrower than one step's velocity change (`4η < 1`), the
///   step that straddles the turning point can still take one branch for up to a step past it,
///   as a plain sign would: an excess impulse `ΔF τ`, `τ ≤ Δt`, bounding the COR error by
///   `2η/(1 + η)² k² / e`. The band meets that step in part: the runs measure 0.19 to 0.44 of
///   it over every start phase (η ≤ 0.5, 300 to 3000 steps per contact): the term is taken
///   half.
///
/// Velocity Verlet's own second-order error on the smooth branches adds `(Δt / t_c)² / 10`
/// (`t_c` the contact time; measured at η = 0: 0.02 of `(Δt / t_c)²` for n = 1.5, 0.002 for
/// n = 1). All three fall as Δt²; the worst start phase reaches 0.38 to 0.96 of the sum.
pub fn paper_cor_step_error(law: &PaperLaw, impact_velocity: f64, timestep: f64) -> f64 {
    let exact = paper_impact(law, impact_velocity);
    let eta = law.loss_coefficient;
    let kick = exact.peak_force * timestep / (law.mass * impact_velocity);
    let loading_squared = (1.0 + eta) * (1.0 + eta);
    let band = 4.0 / 3.0 * (4.0 * eta.powi(3) / (3.0 * exact.cor * loading_squared)) * kick * kick;
    let sampling = 0.5 * (2.0 * eta / loading_squared) * kick * kick / exact.cor;
    let smooth = 0.1 * (timestep / exact.contact_time).powi(2);
    band + sampling + smooth
}

/// Figures of a code's own `law` at zero step error, at speed `impact_velocity` (m/s): a
/// [`DashpotLaw`] integrated by [`accurate_metrics`] at relative tolerance `rtol`, the paper's
/// law from its closed form ([`paper_impact`]; `rtol` is not needed), so that a code that has
/// the paper's law differs from it by no model at all.
pub fn own_law_metrics(
    law: &CodeLaw,
    impact_velocity: f64,
    rtol: f64,
) -> Result<TrajectoryMetrics, SolveError> {
    match law {
        CodeLaw::Dashpot(law) => accurate_metrics(law, impact_velocity, rtol),
        CodeLaw::Paper(law) => Ok(paper_impact(law, impact_velocity).metrics()),
    }
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
        ..TrajectoryMetrics::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::trajectory::trajectory_metrics;

    /// A law whose force is not a number anywhere (a missing modulus) never turns the body:
    /// the accurate solve says so instead of growing its step without end.
    #[test]
    fn a_law_without_force_never_turns_and_says_so() {
        let law = DashpotLaw {
            mass: 0.016,
            stiffness: f64::NAN,
            exponent: 1.5,
            damping: f64::NAN,
            damping_exponent: 0.25,
            clamp_attractive: true,
        };
        let error = accurate_metrics(&law, 1.0, 1e-12).expect_err("no contact end");
        assert!(
            matches!(error, crate::solve::SolveError::NoTurn { .. }),
            "{error}"
        );
    }

    fn paper(exponent: f64) -> CodeLaw {
        CodeLaw::Paper(PaperLaw {
            mass: 0.26,
            stiffness: if exponent > 1.0 { 2.0e10 } else { 5.6e8 },
            exponent,
            loss_coefficient: 0.7,
        })
    }

    fn relative(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// In a frame, a wall impact is the relative motion stepped from the same gap, and two
    /// spheres of mass 2M each are the relative motion of mass M: the same figures to the
    /// rounding of the absolute heights.
    #[test]
    fn a_frame_steps_the_relative_motion() {
        let v0 = 2.0;
        for exponent in [1.5, 1.0] {
            let law = paper(exponent);
            let peak = 1e-4;
            let dt = 1.3e-7;
            let steps = 2500;
            let gap = 1e-6 * v0 * dt;
            let relative_motion = trajectory_metrics(&step_trajectory_from(
                &law,
                v0,
                dt,
                steps,
                StepScheme::VelocityVerlet,
                gap,
            ))
            .unwrap();
            let wall = CodeFrame {
                reach: 0.02,
                upper: FrameBody {
                    height: 0.02 + gap,
                    velocity: -v0,
                    mass: 0.26,
                },
                lower: None,
            };
            let pair = CodeFrame {
                reach: 0.04,
                upper: FrameBody {
                    height: 0.02 + gap,
                    velocity: -0.5 * v0,
                    mass: 0.52,
                },
                lower: Some(FrameBody {
                    height: -0.02,
                    velocity: 0.5 * v0,
                    mass: 0.52,
                }),
            };
            for frame in [wall, pair] {
                let m = trajectory_metrics(&step_in_frame(&law, &frame, dt, steps)).unwrap();
                assert!(m.peak_deformation < 2.0 * peak, "{m:?}");
                for (a, b) in [
                    (m.cor, relative_motion.cor),
                    (m.peak_deformation, relative_motion.peak_deformation),
                    (m.contact_time, relative_motion.contact_time),
                ] {
                    assert!(relative(a, b) < 1e-10, "{a} vs {b}");
                }
            }
        }
    }

    /// A stepping with a frame steps in the frame by its scheme (velocity Verlet, leap-frog),
    /// with the start phase's gap added to the upper height; without one from touch.
    #[test]
    fn a_code_stepping_uses_its_frame_for_either_scheme() {
        let law = paper(1.5);
        let frame = CodeFrame {
            reach: 0.02,
            upper: FrameBody {
                height: 0.02,
                velocity: -2.0,
                mass: 0.26,
            },
            lower: None,
        };
        let gap = 3e-8;
        let with_frame = CodeStepping {
            scheme: StepScheme::VelocityVerlet,
            frame: Some(frame),
        };
        let moved = CodeFrame {
            upper: FrameBody {
                height: 0.02 + gap,
                ..frame.upper
            },
            ..frame
        };
        assert_eq!(
            with_frame.trajectory(&law, 2.0, 1e-7, 50, gap),
            step_in_frame(&law, &moved, 1e-7, 50)
        );
        let leap_frog = CodeStepping {
            scheme: StepScheme::LeapFrog,
            frame: Some(frame),
        };
        assert_eq!(
            leap_frog.trajectory(&law, 2.0, 1e-7, 50, gap),
            step_in_leap_frog_frame(&law, &moved, 1e-7, 50)
        );
        let from_touch = CodeStepping {
            scheme: StepScheme::LeapFrog,
            frame: None,
        };
        assert_eq!(
            from_touch.trajectory(&law, 2.0, 1e-7, 50, gap),
            step_trajectory_from(&law, 2.0, 1e-7, 50, StepScheme::LeapFrog, gap)
        );
    }

    /// Leap-frog in a frame is leap-frog of the relative motion but for the rounding of the
    /// absolute positions: a wall and two spheres, the paper's law at η = 0.7 (COR 0.42), whose
    /// band the turning point crosses.
    #[test]
    fn a_leap_frog_frame_steps_the_relative_motion() {
        let law = paper(1.5);
        let (mass, v0, h, steps) = (law.mass(), 2.0, 1e-7, 2500);
        let wall = CodeFrame {
            reach: 0.02,
            upper: FrameBody {
                height: 0.02,
                velocity: -v0,
                mass,
            },
            lower: None,
        };
        // Two equal spheres of twice the mass: the same reduced mass.
        let pair = CodeFrame {
            reach: 0.04,
            upper: FrameBody {
                height: 0.0,
                velocity: -v0 / 2.0,
                mass: 2.0 * mass,
            },
            lower: Some(FrameBody {
                height: -0.04,
                velocity: v0 / 2.0,
                mass: 2.0 * mass,
            }),
        };
        let motion = step_trajectory(&law, v0, h, steps, StepScheme::LeapFrog);
        let reference = trajectory_metrics(&motion).unwrap();
        for frame in [wall, pair] {
            let stepped = step_in_leap_frog_frame(&law, &frame, h, steps);
            assert_eq!(stepped.overlap.len(), motion.overlap.len());
            assert_eq!(stepped.overlap[0].to_bits(), 0f64.to_bits());
            let m = trajectory_metrics(&stepped).unwrap();
            assert!(relative(m.cor, reference.cor) < 1e-11, "{m:?}");
            assert!(
                relative(m.peak_deformation, reference.peak_deformation) < 1e-11,
                "{m:?}"
            );
            assert!(m.cor > 0.4 && m.cor < 0.43, "{m:?}");
        }
    }

    /// The paper's law's figures at zero step error are its closed form: a code that has the
    /// law differs from it by no model.
    #[test]
    fn the_papers_law_is_its_own_exact_figures() {
        let CodeLaw::Paper(law) = paper(1.5) else {
            unreachable!()
        };
        let m = own_law_metrics(&CodeLaw::Paper(law), 2.0, 1e-12).unwrap();
        assert_eq!(m, paper_impact(&law, 2.0).metrics());
    }

    /// No start phase takes the stepped COR further from the closed form than the predicted
    /// bound, which the worst phase reaches to within a factor of three (it is not loose) and
    /// falls 4× per halving of the step.
    #[test]
    fn the_predicted_step_error_bounds_every_start_phase() {
        for exponent in [1.5, 1.0] {
            for eta in [0.2, 0.7, 0.95] {
                let CodeLaw::Paper(law) = paper(exponent) else {
                    unreachable!()
                };
                let law = PaperLaw {
                    loss_coefficient: eta,
                    ..law
                };
                let v0 = 2.0;
                let exact = paper_impact(&law, v0);
                let dt = exact.contact_time / 1000.0;
                let worst = (0..32)
                    .map(|k| {
                        let gap = f64::from(k) / 32.0 * v0 * dt;
                        let t = step_trajectory_from(
                            &CodeLaw::Paper(law),
                            v0,
                            dt,
                            1100,
                            StepScheme::VelocityVerlet,
                            gap,
                        );
                        (trajectory_metrics(&t).unwrap().cor - exact.cor).abs()
                    })
                    .fold(0.0, f64::max);
                let bound = paper_cor_step_error(&law, v0, dt);
                assert!(
                    worst <= bound && worst > bound / 3.0,
                    "n={exponent} η={eta}: {worst:e} against {bound:e}"
                );
                let halved = paper_cor_step_error(&law, v0, 0.5 * dt);
                assert!((bound / halved - 4.0).abs() < 1e-9);
            }
        }
    }

    /// Leap-frog (YADE) and velocity Verlet (LIGGGHTS) step the paper's law through the same
    /// positions with the same forces (each force from `x_i` and `v_{i−½}`), and out of contact
    /// report the same velocity: the same COR to rounding at every start phase, so
    /// [`paper_cor_step_error`] bounds leap-frog's runs too.
    #[test]
    fn leap_frog_and_velocity_verlet_give_the_paper_law_one_cor() {
        for exponent in [1.5, 1.0] {
            for eta in [0.0, 0.35, 0.95] {
                let CodeLaw::Paper(law) = paper(exponent) else {
                    unreachable!()
                };
                let law = CodeLaw::Paper(PaperLaw {
                    loss_coefficient: eta,
                    ..law
                });
                let v0 = 2.0;
                let CodeLaw::Paper(plain) = law else {
                    unreachable!()
                };
                let dt = paper_impact(&plain, v0).contact_time / 300.0;
                for k in 0..8 {
                    let gap = f64::from(k) / 8.0 * v0 * dt;
                    let cor = |scheme| {
                        let t = step_trajectory_from(&law, v0, dt, 400, scheme, gap);
                        trajectory_metrics(&t).unwrap().cor
                    };
                    let (verlet, leap) =
                        (cor(StepScheme::VelocityVerlet), cor(StepScheme::LeapFrog));
                    assert!(
                        (verlet - leap).abs() < 1e-13,
                        "n={exponent} η={eta} phase {k}/8: {verlet:e} vs {leap:e}"
                    );
                }
            }
        }
    }

    /// Outside the band the step's force is the coded law's branch; inside it, linear in the
    /// approach rate from `C yⁿ (1 − η)` to `C yⁿ (1 + η)`, the elastic force at rest; η = 0
    /// is the elastic force at every rate.
    #[test]
    fn the_step_force_is_the_branch_outside_the_band_and_linear_within() {
        let law = PaperLaw {
            mass: 0.5,
            stiffness: 2.0,
            exponent: 1.0,
            loss_coefficient: 0.25,
        };
        let (y, dt) = (4.0, 0.1);
        // elastic 8 N, band 2 η 8 N Δt / M = 0.8 m/s
        let band = 0.8;
        for v in [band, 1.0, 50.0, -band, -1.0, -50.0] {
            let expected = law.force_as_coded(y, v);
            assert!(
                (paper_force_in_step(&law, y, v, dt) - expected).abs() < 1e-12,
                "{v}"
            );
        }
        assert!((paper_force_in_step(&law, y, 0.0, dt) - 8.0).abs() < 1e-12);
        assert!((paper_force_in_step(&law, y, 0.4, dt) - 9.0).abs() < 1e-12);
        assert!((paper_force_in_step(&law, y, -0.2, dt) - 7.5).abs() < 1e-12);
        assert!(paper_force_in_step(&law, 0.0, 1.0, dt).abs() < f64::MIN_POSITIVE);
        let elastic = PaperLaw {
            loss_coefficient: 0.0,
            ..law
        };
        for v in [-1.0, -1e-300, 0.0, 1e-300, 1.0] {
            assert!((paper_force_in_step(&elastic, y, v, dt) - 8.0).abs() < 1e-12);
        }
    }

    /// A body resting on the paper's contact under its weight (a steel ball of 5 mm on a
    /// plate, η = 0.3, Δt = 1 µs), stepped as LIGGGHTS steps it: with the step's force it
    /// settles and carries its weight to 1e-9 from step to step; with the plain sign the half-step
    /// velocity flips every step and the force alternates by about ±η of the weight.
    #[test]
    fn a_resting_contact_carries_its_weight_without_alternating() {
        let law = PaperLaw {
            mass: 4.084e-3,
            stiffness: 1.036e10,
            exponent: 1.5,
            loss_coefficient: 0.3,
        };
        let weight = law.mass * 9.81;
        let dt = 1e-6;
        let settle = |force: &dyn Fn(f64, f64) -> f64| -> (f64, f64) {
            // from touch at rest; y is the overlap, v the approach rate
            let (mut y, mut v, mut f) = (0.0_f64, 0.0_f64, 0.0_f64);
            let (mut lowest, mut highest) = (f64::INFINITY, 0.0_f64);
            for step in 0..200_000 {
                let half = v + 0.5 * dt * (weight - f) / law.mass;
                y += dt * half;
                f = force(y, half);
                v = half + 0.5 * dt * (weight - f) / law.mass;
                if step >= 199_000 {
                    lowest = lowest.min(f);
                    highest = highest.max(f);
                }
            }
            (lowest / weight, highest / weight)
        };
        let (low, high) = settle(&|y, v| paper_force_in_step(&law, y, v, dt));
        assert!(
            (low - 1.0).abs() < 1e-9 && (high - 1.0).abs() < 1e-9,
            "{low} {high}"
        );
        let (low, high) = settle(&|y, v| law.force_as_coded(y, v));
        assert!(low < 0.8 && high > 1.2, "{low} {high}");
    }
}
