//! The tangential row of a deck's wall: one oblique impact in gross sliding, run with the wall's
//! own lines, against Coulomb's closed form.
//!
//! The impact is the pair's normal impact at the deck's first speed `v_n` with the ball's centre
//! moving along the plane at `s0 = 14 μ v_n`, twice the rigid-body bound `(7/2) μ (1+e) v_n` at
//! `e = 1`: the contact slides throughout, whatever the normal law, so the tangential impulse
//! is `μ` times the normal one, `μ (1+e) M* v_n`, against the slip
//! ([`crate::model::tangential::gross_sliding_impulse`]). `e` is the normal COR the same run
//! realised (read from its trajectory), so the normal law's own step error is not charged to
//! the tangential part.

use serde::Serialize;
use thiserror::Error;

use super::ImpactRun;
use crate::codes::CodeError;
pub use crate::codes::TangentialRun;
use crate::codes::deck::{Partner, TANGENTIAL_LINE, TypeRef, UserDeck};
use crate::model::law::ContactForce;
use crate::model::tangential::{PlaneMotion, TangentialBodies, gross_sliding_impulse};
use crate::model::trajectory::{CodeTrajectory, TrajectoryError, trajectory_metrics};

/// The slip of the oblique impact over `μ v_n`: twice the rigid-body bound of gross sliding,
/// `(7/2) μ (1+e) v_n`, at `e = 1`.
pub const SLIP_OVER_FRICTION: f64 = 14.0;

/// The part of the closed form's change of tangential velocity a row may miss by beyond the
/// attractive tail (see [`tolerance`]). In gross sliding a code's tangential force is μ times
/// its normal force at every step, so the step itself costs nothing: the discrete impulses are
/// in the ratio μ, and the normal one is `(1+e) M* v_n` with the run's own `e`. What is left is
/// the history spring's start from zero: it reaches the Coulomb bound within the first steps
/// of the contact, where the closed form has the bound from the first instant. The builds
/// whose friction is right miss by 0.3 % or less in the measurements
/// (`docs/src/commands/deck.md`); the LAMMPS 2025 classic walls, dashpot off, by 50 to 100 %.
pub const RELATIVE_TOLERANCE: f64 = 1e-2;

/// The tangential row of one wall (of a ball against it): the oblique impact in gross sliding
/// against Coulomb's closed form.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DeckTangentialImpact {
    /// The two types (a type and `"wall"`).
    pub types: [TypeRef; 2],
    /// The pair as labelled in the tables.
    pub pair: String,
    /// The run's name (its key among recorded runs).
    pub run: String,
    /// The wall's name.
    pub wall: Option<String>,
    /// The tangential model as the lines write it.
    pub tangential_model: String,
    /// The tangential damping the lines set that the run turned off (`dampflag 1`, `damping
    /// coefficient 1.0`): the closed form is Coulomb's bound reached throughout, which a
    /// damped history spring lags by what its build decides; `None` where the lines set none.
    pub tangential_damping_off: Option<String>,
    /// Coulomb's μ of the lines.
    pub friction_coefficient: f64,
    /// Normal approach speed, m/s (the deck's first impact speed).
    pub impact_velocity: f64,
    /// The ball's centre velocity along the plane at the start, m/s (`14 μ v_n`).
    pub tangential_velocity: f64,
    /// The normal COR this run realised (read from its trajectory).
    pub cor_realised: f64,
    /// The ball's centre velocity along the plane after the impact, as the code gives it, m/s.
    pub tangential_velocity_out: f64,
    /// The ball's spin after the impact, as the code gives it, rad/s (positive: rolling
    /// towards the initial tangential velocity).
    pub angular_velocity_out: f64,
    /// The same from Coulomb sliding throughout with the run's own COR, m/s.
    pub tangential_velocity_closed_form: f64,
    /// The same, rad/s.
    pub angular_velocity_closed_form: f64,
    /// The change of the tangential velocity the code gives less the closed form's, m/s.
    pub difference: f64,
    /// What the difference may be (see [`tolerance`]), m/s.
    pub tolerance: f64,
    /// Whether the code misses the closed form by more than the tolerance.
    pub failed: bool,
    /// Why the run failed, if it did (its figures are then NaN).
    pub failure: Option<String>,
}

/// The tolerance of a row, m/s: [`RELATIVE_TOLERANCE`] of the closed form's change `change`
/// (m/s), plus the friction the attractive tail of a damped law carries where the code bounds
/// the tangential force by `μ |F_n|` rather than `μ F_n` (`μ ∫ (|F_n| − F_n) dt / M*` from the
/// run's own force column, `timestep` apart; zero for a force that never pulls).
pub fn tolerance(
    change: f64,
    friction: f64,
    mass: f64,
    timestep: f64,
    trajectory: &CodeTrajectory,
) -> f64 {
    let pull: f64 = trajectory
        .normal_force
        .iter()
        .map(|f| (-f).max(0.0))
        .sum::<f64>()
        * timestep;
    RELATIVE_TOLERANCE * change.abs() + friction * 2.0 * pull / mass
}

/// What the oblique impact of one wall needs from the plan and the deck.
pub(crate) struct ObliqueRow<'a> {
    /// The deck.
    pub deck: &'a UserDeck,
    /// The contact.
    pub contact: usize,
    /// Its label.
    pub pair: String,
    /// Its run's key.
    pub run: String,
    /// Normal speed, m/s.
    pub velocity: f64,
    /// Tangential speed at the start, m/s.
    pub tangential_velocity: f64,
}

/// Why an oblique impact gives no figures.
#[derive(Debug, Error)]
enum ObliqueFailure<'a> {
    /// The code's run failed (its log kept where the error says).
    #[error(transparent)]
    Run(&'a CodeError),
    /// Its trajectory does not read as an impact.
    #[error("the run's trajectory: {0}")]
    Trajectory(#[from] TrajectoryError),
    /// It printed no motion after its steps.
    #[error(
        "the run printed no `{TANGENTIAL_LINE}` line (the ball's tangential velocity and spin)"
    )]
    NoMotion,
}

impl ObliqueRow<'_> {
    /// The row of the run `run` (its trajectory and printed motion) or of its failure.
    pub(crate) fn row(&self, run: Result<&ImpactRun, &CodeError>) -> DeckTangentialImpact {
        let c = &self.deck.contacts[self.contact];
        let friction = c.friction.as_ref();
        let mu = friction.map_or(0.0, |f| f.coefficient);
        let body = &self.deck.bodies[c.body];
        let mass = ContactForce::mass(&c.law);
        let nan = f64::NAN;
        let mut row = DeckTangentialImpact {
            types: c.types,
            pair: self.pair.clone(),
            run: self.run.clone(),
            wall: match c.partner {
                Partner::Wall(w) => Some(self.deck.walls[w].name.clone()),
                Partner::Body(_) => None,
            },
            tangential_model: friction.map_or(String::new(), |f| f.model.clone()),
            tangential_damping_off: friction.and_then(|f| f.damping.clone()),
            friction_coefficient: mu,
            impact_velocity: self.velocity,
            tangential_velocity: self.tangential_velocity,
            cor_realised: nan,
            tangential_velocity_out: nan,
            angular_velocity_out: nan,
            tangential_velocity_closed_form: nan,
            angular_velocity_closed_form: nan,
            difference: nan,
            tolerance: nan,
            failed: false,
            failure: None,
        };
        let read = run.map_err(ObliqueFailure::Run).and_then(|run| {
            let metrics = trajectory_metrics(&run.trajectory)?;
            let motion = run.tangential.ok_or(ObliqueFailure::NoMotion)?;
            Ok((&run.trajectory, metrics.cor, motion))
        });
        let (trajectory, cor, motion) = match read {
            Ok(read) => read,
            Err(e) => {
                row.failure = Some(e.to_string());
                return row;
            }
        };
        let bodies = TangentialBodies {
            ball: (
                body.mass,
                body.radius,
                PlaneMotion {
                    tangential_velocity: self.tangential_velocity,
                    angular_velocity: 0.0,
                },
            ),
            other: None,
        };
        let impulse = gross_sliding_impulse(mass, self.velocity, cor, mu, bodies.slip());
        let (closed, _) = bodies.after(impulse);
        let change = closed.tangential_velocity - self.tangential_velocity;
        row.cor_realised = cor;
        row.tangential_velocity_out = motion.ball.tangential_velocity;
        row.angular_velocity_out = motion.ball.angular_velocity;
        row.tangential_velocity_closed_form = closed.tangential_velocity;
        row.angular_velocity_closed_form = closed.angular_velocity;
        row.difference = motion.ball.tangential_velocity - closed.tangential_velocity;
        row.tolerance = tolerance(change, mu, mass, self.deck.timestep, trajectory);
        // A NaN the code printed (a force it could not form) is a miss, not a pass.
        row.failed = row.difference.abs().is_nan() || row.difference.abs() > row.tolerance;
        row
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::float_cmp)] // a printed number reads back exactly
    fn the_printed_line_reads_as_the_motions() {
        let log = "Loop time of 0.1\nMILLIMPACT_TANGENTIAL 2.09071450474401 1136.60686906998\n";
        let run = TangentialRun::from_log(log, "MILLIMPACT_TANGENTIAL").unwrap();
        assert_eq!(run.ball.tangential_velocity, 2.09071450474401);
        assert_eq!(run.ball.angular_velocity, 1136.60686906998);
        assert!(run.partner.is_none());
        let pair =
            TangentialRun::from_log("MILLIMPACT_TANGENTIAL 1 2 -3 4\n", "MILLIMPACT_TANGENTIAL")
                .unwrap();
        assert_eq!(pair.partner.unwrap().tangential_velocity, -3.0);
        assert!(
            TangentialRun::from_log("MILLIMPACT_TANGENTIAL 1 x\n", "MILLIMPACT_TANGENTIAL")
                .is_none()
        );
        assert!(TangentialRun::from_log("nothing\n", "MILLIMPACT_TANGENTIAL").is_none());
    }

    /// A force that never pulls adds no tail; one that pulls adds twice its impulse times μ.
    #[test]
    fn the_tolerance_counts_the_pulling_tail() {
        let t = |forces: Vec<f64>| CodeTrajectory {
            time: (0..forces.len()).map(|k| k as f64).collect(),
            overlap: vec![0.0; forces.len()],
            approach_velocity: vec![0.0; forces.len()],
            normal_force: forces,
        };
        let pushing = tolerance(1.0, 0.5, 2.0, 0.1, &t(vec![0.0, 4.0, 1.0, 0.0]));
        assert!((pushing - RELATIVE_TOLERANCE).abs() < 1e-15);
        let pulling = tolerance(1.0, 0.5, 2.0, 0.1, &t(vec![0.0, 4.0, -1.0, 0.0]));
        assert!((pulling - pushing - 0.5 * 2.0 * 0.1 / 2.0).abs() < 1e-15);
    }
}
