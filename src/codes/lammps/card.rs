//! A LAMMPS build's calibration card: the input lines that set its law, the traps they avoid
//! in this build (as its probe found it), and the law a user gets who gives `damping tsuji`
//! the COR itself.

use crate::codes::lammps::Build;
use crate::codes::lammps::conventions::{TsujiFit, WallModulus, tsuji_alpha};
use crate::codes::{CalibrationCard, CodeSetup};
use crate::model::law::DashpotLaw;
use crate::model::scene::{SceneKind, SpringModel};

/// The card of one LAMMPS build.
pub(crate) struct LammpsCard(pub &'static Build);

impl CalibrationCard for LammpsCard {
    fn setting_keys(&self, _scene: SceneKind) -> &'static [&'static str] {
        &["pair_style", "pair_coeff", "wall/gran"]
    }

    fn traps(&self, setup: &CodeSetup) -> Vec<String> {
        let scene = setup.scene;
        let mut t = Vec::new();
        // The traps of the build as its probe found it (the setup's conventions), else as
        // the build was measured.
        let c = self.0.conventions(setup);
        if scene.spring() == SpringModel::Hertz {
            if c.coeff_restitution {
                t.push("damping coeff_restitution takes e itself, but runs e = 0 (NaN) and e > 1 (energy gain) without a word".into());
            }
            t.push(match c.tsuji_fit {
                TsujiFit::Polynomial => "damping tsuji takes e_in, not e: its fit is √2 short in this build, so e_in = e realises a higher COR (0.7734 for 0.6944)".into(),
                TsujiFit::Sqrt2Polynomial => "damping tsuji carries the √2 in this build: an e_in compensated for builds without it realises a lower COR (about 0.594 for 0.694)".into(),
            });
        }
        if let Some(trap) = mindlin_trap(setup) {
            t.push(trap);
        }
        if scene == SceneKind::BallPlate {
            t.push(match c.wall_modulus {
                WallModulus::HalfOverOneMinusNu => "wall modulus: fix wall/gran hertz/material reads E* = E/(2(1−ν)) in this build, not the plate's mix; give ν = 0 and E = 2E* of the pair".into(),
                WallModulus::HalfOverOneMinusNuSquared => "wall modulus: fix wall/gran hertz/material reads E* = E/(2(1−ν²)) (the particle's material on both sides), not the plate's mix; give ν = 0 and E = 2E* of the pair".into(),
            });
        }
        t.push(
            "limit_damping off (the default): on cuts the attractive tail and raises the COR"
                .into(),
        );
        if c.touching_is_contact {
            t.push("touching counts as contact: start a hair away".into());
        }
        t
    }

    fn law_at_its_word(&self, setup: &CodeSetup) -> Option<(&'static str, DashpotLaw)> {
        if setup.scene.spring() != SpringModel::Hertz {
            return None;
        }
        let mut law = self.0.law(setup);
        law.damping = tsuji_alpha(setup.target_restitution) * (law.mass * law.stiffness).sqrt();
        Some(("tsuji with e_in = e", law))
    }

    fn clamp_setting(&self) -> Option<&'static str> {
        Some("limit_damping")
    }
}

/// The shear modulus `G = E / (2(1 + ν))` of a material, Pa.
fn shear_modulus(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    youngs_modulus / (2.0 * (1.0 + poisson_ratio))
}

/// What the card's `ν = 0`, `E = 2E*` does to a `mindlin` tangential model (Hertz scenes): its
/// `G*` is formed from those numbers, `1/((2−ν1)/G1 + (2−ν2)/G2)` with `G = E/2` each side,
/// i.e. `E*/4`, not the materials' own `G*`; the trap names both and the `k_t = 8G*` that
/// restores it.
fn mindlin_trap(setup: &CodeSetup) -> Option<String> {
    if setup.scene.spring() != SpringModel::Hertz {
        return None;
    }
    let s = setup.sphere;
    let compliance = |e: f64, nu: f64| (2.0 - nu) / shear_modulus(e, nu);
    let mut sum = compliance(s.youngs_modulus, s.poisson_ratio?);
    match (setup.other_sphere, setup.plate_material) {
        (Some(o), _) => sum += compliance(o.youngs_modulus, o.poisson_ratio?),
        (None, Some((e, nu))) => sum += compliance(e, nu),
        // A rigid plate adds no compliance.
        (None, None) => {}
    }
    let materials = 1.0 / sum;
    let e_star = 0.75 * setup.stiffness / setup.pair_radius().sqrt();
    let card = e_star / 4.0;
    Some(format!(
        "tangential: the card gives ν = 0 and E = 2E* (E* = {e_star:.4e} Pa) so that every wall convention gives the normal stiffness; a `mindlin` tangential model with k_t NULL then forms G* = E*/4 = {card:.4e} Pa from them, not the materials' 1/((2−ν1)/G1 + (2−ν2)/G2) = {materials:.4e} Pa ({:+.1} %): with mindlin give k_t = 8G* = {:e} Pa explicitly",
        100.0 * (card / materials - 1.0),
        8.0 * materials
    ))
}
