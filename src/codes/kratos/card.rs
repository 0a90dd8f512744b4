//! Kratos' calibration card: the script lines that set its law, and the traps they avoid.

use crate::codes::{CalibrationCard, CodeSetup};
use crate::model::scene::SceneKind;

/// Kratos' card.
pub(crate) struct KratosCard;

impl CalibrationCard for KratosCard {
    fn setting_keys(&self, scene: SceneKind) -> &'static [&'static str] {
        match scene {
            SceneKind::RodEnd => &[
                "KN =",
                "GAMMA =",
                "SCHEME = \"",
                "\"NeighbourSearchFrequency\"",
                "= \"DEM_D_Linear_Custom_Constants\"",
                "K_NORMAL] =",
            ],
            SceneKind::BallPlate => &[
                "EN =",
                "WALL_E =",
                "WALL_NU =",
                "SCHEME = \"",
                "\"NeighbourSearchFrequency\"",
                "= \"DEM_D_Hertz_viscous_Coulomb\"",
            ],
            // No wall on a two-ball card: its WALL_E line would read 0e0.
            SceneKind::BallBall => &[
                "EN =",
                "SCHEME = \"",
                "\"NeighbourSearchFrequency\"",
                "= \"DEM_D_Hertz_viscous_Coulomb\"",
            ],
        }
    }

    fn traps(&self, setup: &CodeSetup) -> Vec<String> {
        let mut t: Vec<String> = vec![
            "scheme: set the translational integration scheme (and the properties proxies) in the particles' properties before creating any particle, else CreateSphericParticle segfaults (exit 139, no message)".into(),
            "Symplectic_Euler, not Forward_Euler: Forward_Euler gains energy (an elastic impact rebounds at 1.0056)".into(),
            "NeighbourSearchFrequency 1: the default 50 finds the wall contact only at step 48 (COR 0.711 for 0.694)".into(),
            "OMP_NUM_THREADS=1: the default two threads make a one-sphere loop 5–10× slower".into(),
        ];
        if setup.scene != SceneKind::RodEnd {
            t.push("COEFFICIENT_OF_RESTITUTION is not the COR: Thornton's fit with the clamped law realises another e; give the inverted en (EN above), as for YADE".into());
        } else {
            t.push("rod: DEM_D_Linear_Custom_Constants with K_NORMAL in the contact's sub-properties and DAMPING_GAMMA set to the clamped linear dashpot's ζ(e) after initialisation".into());
        }
        t.push("clamp: the laws never attract; the damping is chosen for the clamped law".into());
        t
    }
}
