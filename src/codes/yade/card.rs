//! YADE's calibration card: the script lines that set its law, the traps they avoid, and the
//! law a user gets who gives `en = e`.

use crate::codes::damping::thornton_damping_ratio;
use crate::codes::yade::Yade;
use crate::codes::{CalibrationCard, CodeSetup};
use crate::model::law::DashpotLaw;
use crate::model::scene::SceneKind;

/// YADE's card.
pub(crate) struct YadeCard;

impl CalibrationCard for YadeCard {
    fn setting_keys(&self, scene: SceneKind) -> &'static [&'static str] {
        match scene {
            SceneKind::RodEnd => &["KN =", "CN =", "damping=", "ViscElMat("],
            SceneKind::BallPlate => &[
                "EN =",
                "WALL_E =",
                "WALL_NU =",
                "damping=",
                "hertzian",
                "MindlinPhys(",
            ],
            // No wall on a two-ball card: its WALL_E line would read 0e0.
            SceneKind::BallBall => &["EN =", "damping=", "MindlinPhys("],
        }
    }

    fn traps(&self, setup: &CodeSetup) -> Vec<String> {
        let scene = setup.scene;
        let mut t = Vec::new();
        t.push("numerical damping: NewtonIntegrator(damping=0.2) is the default; set damping=0 (else an elastic impact rebounds at 0.8165)".into());
        if scene != SceneKind::RodEnd {
            t.push("en is not the COR: Thornton's fit with the clamped law realises another e; give the inverted en (EN above), not e".into());
            t.push("fit error: en cannot realise e between about 0.985 and 1".into());
        }
        if scene == SceneKind::BallPlate {
            t.push("wall radius: Ig2_Wall_Sphere_ScGeom gives the wall the sphere's radius (R* = R/2) unless hertzian=True".into());
            t.push("wall modulus: the wall's material is mixed into E*: give the plate's own (a rigid plate: E = 1e30)".into());
        }
        t.push(
            "clamp: YADE's laws never attract; the damping is chosen for the clamped law".into(),
        );
        t
    }

    fn law_at_its_word(&self, setup: &CodeSetup) -> Option<(&'static str, DashpotLaw)> {
        let mut law = Yade.dashpot_law(setup);
        law.damping = 2.0
            * thornton_damping_ratio(setup.target_restitution)
            * (1.5 * law.mass * law.stiffness).sqrt();
        Some(("en = e", law))
    }
}
