//! LIGGGHTS's calibration card: the input lines that set its law, and the traps they avoid.

use crate::codes::{CalibrationCard, CodeSetup};
use crate::model::scene::SceneKind;

/// LIGGGHTS's card.
pub(crate) struct LiggghtsCard;

impl CalibrationCard for LiggghtsCard {
    fn setting_keys(&self, _scene: SceneKind) -> &'static [&'static str] {
        &[
            "hard_particles",
            "pair_style",
            "wall/gran",
            "youngsModulus",
            "poissonsRatio",
            "coefficientRestitution",
            "property/global kn ",
            "gamman_abs",
        ]
    }

    fn traps(&self, setup: &CodeSetup) -> Vec<String> {
        let scene = setup.scene;
        let mut t = Vec::new();
        if scene == SceneKind::BallPlate {
            t.push("wall modulus: the wall's atom type's E and ν are mixed into E*: give the plate's own (a rigid plate: E = 1e30), and hard_particles yes for any E above 1e9 Pa".into());
        }
        t.push("limitForce off (the default): on cuts the attractive tail and raises the COR above the target (0.7128 for 0.6939)".into());
        if scene == SceneKind::RodEnd {
            t.push("rod: hooke/stiffness with absolute_damping on and gamman_abs from the linear dashpot's ζ(e); gamman is per mass".into());
        }
        t.push("touching counts as contact: start with a gap, or a linear dashpot pushes before the first step".into());
        t
    }

    fn clamp_setting(&self) -> Option<&'static str> {
        Some("limitForce")
    }
}
