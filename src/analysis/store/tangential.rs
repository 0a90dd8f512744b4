//! The tangential half of an oblique impact a code ran: the ball's motion along the plane and
//! its spin after the impact, against the closed form of the case at the normal COR the same
//! run realised (so the normal law's own difference is not charged to the tangential part).

use serde::{Deserialize, Serialize};

use crate::analysis::deck::tangential::{RELATIVE_TOLERANCE, tolerance};
use crate::codes::{CodeSetup, TangentialRun};
use crate::model::case::Case;
use crate::model::tangential::{ClosedFormKind, PlaneMotion, TangentialBodies};
use crate::model::trajectory::CodeTrajectory;
use crate::solve::Method;
use crate::solve::paper::Settings;
use crate::solve::tangential::{closed_form_at, solve_oblique};

/// An oblique impact's tangential figures in a code's run, beside the case's closed form.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CodeTangential {
    /// Coulomb's μ.
    pub friction_coefficient: f64,
    /// The ball's centre velocity along the plane at first contact, m/s.
    pub tangential_velocity: f64,
    /// Its spin at first contact, rad/s.
    pub angular_velocity: f64,
    /// Its centre velocity along the plane after the impact, as the code printed it, m/s.
    pub tangential_velocity_out: f64,
    /// Its spin after the impact, as the code printed it, rad/s.
    pub angular_velocity_out: f64,
    /// The closed form that holds for the case; `None` where none does (partial slip).
    pub closed_form: Option<ClosedFormKind>,
    /// The normal COR the closed form is taken at: the one the run realised.
    pub closed_form_restitution: f64,
    /// The closed form's velocity along the plane after the impact, m/s.
    pub tangential_velocity_closed_form: Option<f64>,
    /// The closed form's spin after the impact, rad/s.
    pub angular_velocity_closed_form: Option<f64>,
    /// The code's change of velocity along the plane less the closed form's, over the closed
    /// form's change.
    pub tangential_change_error: Option<f64>,
    /// The code's change of spin less the closed form's, over the closed form's change.
    pub spin_change_error: Option<f64>,
    /// The largest relative miss allowed, over the closed form's change: [`RELATIVE_TOLERANCE`]
    /// plus the friction an attractive tail carries in a code that bounds the tangential force
    /// by `μ |F_n|` ([`tolerance`]).
    pub allowed_change_error: Option<f64>,
    /// The case's own law (the paper's normal law and the case's tangential law) integrated
    /// by `dopri5`: the ball's velocity along the plane after the impact, m/s; what a
    /// partial-slip case, which has no closed form, is set beside. `None` in a record made
    /// before it was kept.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential_velocity_case_law: Option<f64>,
    /// The same law's spin after the impact, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angular_velocity_case_law: Option<f64>,
}

impl CodeTangential {
    /// The figures of a run of `case` (set up as `setup`) whose trajectory is `trajectory`,
    /// whose normal COR was `restitution` and which printed `motion`; `None` for a normal
    /// impact.
    pub fn of_run(
        case: &Case,
        setup: &CodeSetup,
        trajectory: &CodeTrajectory,
        restitution: f64,
        motion: &TangentialRun,
    ) -> Option<CodeTangential> {
        let friction = setup.oblique?.friction_coefficient;
        let mass = setup.pair_mass();
        let allowed = |change: f64| {
            tolerance(change, friction, mass, setup.timestep, trajectory) / change.abs()
        };
        let mut figures =
            Self::against_closed_form(case, setup, restitution, motion.ball, allowed)?;
        let case_law = solve_oblique(
            case,
            &Settings {
                method: Method::Dopri5,
                ..Settings::default()
            },
        )
        .ok()
        .flatten()
        .map(|outcome| outcome.ball);
        figures.tangential_velocity_case_law = case_law.map(|m| m.tangential_velocity);
        figures.angular_velocity_case_law = case_law.map(|m| m.angular_velocity);
        Some(figures)
    }

    /// The same figures taken again now from the stored motion, for `case` set up as `setup`
    /// at the run's COR `restitution`, with the allowed error and the case's own law as stored
    /// (the attractive tail the allowance holds was read from the run's trajectory, which a
    /// record does not keep).
    pub fn retaken(
        &self,
        case: &Case,
        setup: &CodeSetup,
        restitution: f64,
    ) -> Option<CodeTangential> {
        let out = PlaneMotion {
            tangential_velocity: self.tangential_velocity_out,
            angular_velocity: self.angular_velocity_out,
        };
        let stored_allowance = self.allowed_change_error.unwrap_or(f64::NAN);
        let mut now =
            Self::against_closed_form(case, setup, restitution, out, |_| stored_allowance)?;
        now.allowed_change_error = self.allowed_change_error;
        now.tangential_velocity_case_law = self.tangential_velocity_case_law;
        now.angular_velocity_case_law = self.angular_velocity_case_law;
        Some(now)
    }

    /// The motion `out` a run of `case` left, against the closed form at the COR
    /// `restitution` it realised; `allowed` gives the allowed relative error from the closed
    /// form's change of velocity along the plane.
    fn against_closed_form(
        case: &Case,
        setup: &CodeSetup,
        restitution: f64,
        out: PlaneMotion,
        allowed: impl Fn(f64) -> f64,
    ) -> Option<CodeTangential> {
        let oblique = setup.oblique?;
        let bodies = TangentialBodies::of(&case.scene, case.oblique.as_ref()?)?;
        let form = closed_form_at(case, restitution);
        let closed = form.map(|c| bodies.after(c.impulse).0);
        let start = oblique.ball;
        let change_error = |value: fn(&PlaneMotion) -> f64| {
            closed.map(|c| (value(&out) - value(&c)) / (value(&c) - value(&start)).abs())
        };
        Some(CodeTangential {
            friction_coefficient: oblique.friction_coefficient,
            tangential_velocity: start.tangential_velocity,
            angular_velocity: start.angular_velocity,
            tangential_velocity_out: out.tangential_velocity,
            angular_velocity_out: out.angular_velocity,
            closed_form: form.map(|c| c.kind),
            closed_form_restitution: restitution,
            tangential_velocity_closed_form: closed.map(|c| c.tangential_velocity),
            angular_velocity_closed_form: closed.map(|c| c.angular_velocity),
            tangential_change_error: change_error(|m| m.tangential_velocity),
            spin_change_error: change_error(|m| m.angular_velocity),
            allowed_change_error: closed
                .map(|c| allowed(c.tangential_velocity - start.tangential_velocity)),
            tangential_velocity_case_law: None,
            angular_velocity_case_law: None,
        })
    }

    /// Whether the code misses the closed form by more than allowed, in either figure (a
    /// NaN it printed is a miss); `false` where no closed form holds.
    pub fn missed(&self) -> bool {
        let Some(allowed) = self.allowed_change_error else {
            return false;
        };
        [self.tangential_change_error, self.spin_change_error]
            .into_iter()
            .flatten()
            .any(|e| e.is_nan() || e.abs() > allowed)
    }

    /// The figure's largest miss and what is allowed, in words.
    pub fn verdict(&self) -> String {
        match (
            self.tangential_change_error,
            self.spin_change_error,
            self.allowed_change_error,
        ) {
            (Some(v), Some(w), Some(allowed)) => format!(
                "tangential: change of v_t {} and of ω {} of the closed form's (at the run's COR {:.6}), allowed {:.2e} ({:.0e} and the attractive tail's friction): {}",
                crate::output::signed(v),
                crate::output::signed(w),
                self.closed_form_restitution,
                allowed,
                RELATIVE_TOLERANCE,
                if self.missed() { "missed" } else { "met" }
            ),
            _ => "tangential: no closed form holds for this case (partial slip); the code's motion is set beside the case's own law, whose normal force is the paper's, not the code's: a difference here is of law as much as of the code".to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::{CodeName, prepare_with};
    use crate::model::tangential::gross_sliding_impulse;

    fn held_out(name: &str) -> Case {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("cases/oblique")
            .join(format!("{name}.toml"));
        Case::load(&path).unwrap()
    }

    /// A run that leaves with the closed form's motion meets it exactly; one that changes the
    /// velocity along the plane by 2 % more misses, and one whose force pulled at the end is
    /// allowed the friction of that pull.
    #[test]
    fn a_run_is_held_to_the_closed_form_at_its_own_cor() {
        let case = held_out("ball_plate_sliding");
        let setup = prepare_with(
            CodeName::Lammps.driver(),
            &case,
            Some(200),
            None,
            false,
            None,
        )
        .unwrap();
        let e = 0.8;
        let pushing = CodeTrajectory {
            time: vec![0.0, 1.0, 2.0],
            overlap: vec![0.0, 1.0, 0.0],
            approach_velocity: vec![1.0, 0.0, -1.0],
            normal_force: vec![0.0, 5.0, 0.0],
        };
        let bodies = TangentialBodies::of(&case.scene, case.oblique.as_ref().unwrap()).unwrap();
        let impulse = gross_sliding_impulse(setup.pair_mass(), 1.2, e, 0.3, bodies.slip());
        let exact = bodies.after(impulse).0;
        let run = |motion: PlaneMotion, trajectory: &CodeTrajectory| {
            CodeTangential::of_run(
                &case,
                &setup,
                trajectory,
                e,
                &TangentialRun {
                    ball: motion,
                    partner: None,
                },
            )
            .unwrap()
        };
        let met = run(exact, &pushing);
        assert_eq!(met.closed_form, Some(ClosedFormKind::GrossSliding));
        assert!(
            met.tangential_change_error.unwrap().abs() < 1e-14,
            "{met:?}"
        );
        assert!(met.spin_change_error.unwrap().abs() < 1e-14, "{met:?}");
        assert!((met.allowed_change_error.unwrap() - RELATIVE_TOLERANCE).abs() < 1e-15);
        assert!(!met.missed());
        let more = bodies.after(1.02 * impulse).0;
        let missed = run(more, &pushing);
        assert!(
            (missed.tangential_change_error.unwrap() + 0.02).abs() < 1e-12,
            "{missed:?}"
        );
        assert!(missed.missed());
        // A pull of impulse P lets the bound carry 2 μ P more.
        let pull = 0.01 * impulse.abs() / 0.3;
        let pulling = CodeTrajectory {
            normal_force: vec![0.0, 5.0, -pull / setup.timestep],
            ..pushing
        };
        let allowed = run(more, &pulling);
        assert!(!allowed.missed(), "{allowed:?}");
        // The case's own law is set beside the run.
        assert!(met.tangential_velocity_case_law.is_some_and(f64::is_finite));
        // Taken again from the stored motion, the figures are the ones stored, the allowance
        // from the trajectory (which a record does not keep) included.
        assert_eq!(allowed.retaken(&case, &setup, e), Some(allowed.clone()));
    }
}
