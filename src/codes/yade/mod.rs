//! The YADE driver (YADE 2023.02a, `yade -n -x impact.py`).
//!
//! The scene is built by the Python template `scripts/yade/impact.py`: one sphere moving along
//! an axis towards a second sphere or a wall, no gravity, no friction, translations across the
//! axis and all rotations blocked, `NewtonIntegrator(damping=0)` (its default numerical damping
//! is 0.2), `O.dt` set to the setup's step and exactly `setup.steps` iterations. A `PyRunner`
//! placed between the contact law and the integrator writes one row per iteration.
//!
//! What the installed version really integrates, as measured (see
//! `reference/yade/CONVENTIONS.md` for the runs and numbers):
//!
//! - Ball scenes: `Ip2_FrictMat_FrictMat_MindlinPhys(en=e)` with
//!   `Law2_ScGeom_MindlinPhys_Mindlin`: `F = k y^1.5 + c y^0.25 ẏ`, `k = (4/3) E* sqrt(R*)`,
//!   `c = 2 β_n sqrt(1.5 M k)` with `β_n` from Thornton et al. (2013) Eq. (B6)–(B7) (a fit
//!   made for the clamped law), and the total force clamped at zero (never attractive). `M` is
//!   the reduced mass of two balls, or the ball's own mass at a wall.
//! - The wall: `Ig2_Wall_Sphere_ScGeom(hertzian=True)` gives the wall a radius of `1e8 R`, so
//!   `R* = R (1 - 1e-8)` (the default `hertzian=False` gives `R* = R/2`). The wall's material is
//!   mixed into `E*`; a rigid plate is a wall of Young's modulus [`RIGID_WALL_MODULUS`].
//! - Rod end: `ViscElMat` with explicit `kn`, `cn` (no masses involved, so the wall-mass
//!   substitution of the `tc`/`en` form does not apply) and `Law2_ScGeom_ViscElPhys_Basic`:
//!   `F = k y + c ẏ`, clamped at zero. `c` is chosen so that the clamped law realises the target
//!   restitution.
//! - Oblique impacts ([`CodeSetup::oblique`], ball on a plate): the ball also moves along x and
//!   turns about y, the materials carry `frictionAngle = atan(μ)`, the Mindlin law runs without
//!   its shear dashpot, and the motion along the plane is printed after the steps (see
//!   `oblique.rs` for the law and what it cannot render).
//! - Stepping: leap-frog; the force of iteration `i` sees the position `x_i` and the half-step
//!   velocity `v_{i-1/2}`; the initial velocity is `v_{-1/2}`.

pub(crate) mod batch;
pub(crate) mod card;
pub mod deck;
pub(crate) mod dump;
mod objects;
mod oblique;
pub mod paper;
mod reading;
mod viscel;

pub(crate) use paper::YadePaper;

use std::path::Path;

pub use super::damping::{
    clamped_linear_damping_ratio, hertz_input_restitution, thornton_damping_ratio,
};
use super::parse::{ParseError, log_value, parse_csv_columns};
use super::template::{exact_number, fill_template};
use super::{
    BatchRunner, CalibrationCard, CodeDriver, CodeError, CodeSetup, ParsedRun, RenderedInput,
};
use crate::codes::damping::{
    clamped_hertz_law, clamped_linear_law, fit_restitution, hertz_input_or_target,
    refuse_for_clamped_law, rod_damping_ratio,
};
use crate::codes::script_values::{body_values, reported};
use crate::model::law::{CodeLaw, DashpotLaw};
use crate::model::scene::{SceneKind, pair_radius};
use crate::model::trajectory::CodeTrajectory;
use crate::solve::dashpot::StepScheme;

/// The Python template of one impact.
const TEMPLATE: &str = include_str!("impact.py");

/// The name of the rendered script in the scratch directory.
const SCRIPT: &str = "impact.py";

/// The trajectory file the script writes.
pub(crate) const TRAJECTORY_FILE: &str = super::parse::CSV_TRAJECTORY_FILE;

/// Young's modulus given to the wall that stands for a rigid plate, Pa. YADE mixes the wall's
/// material into `E*`; at this value the wall's share of the compliance, about
/// `(1-ν²)E_ball / E_wall ≈ 1e-19` for steel, is below double precision.
pub const RIGID_WALL_MODULUS: f64 = super::setup::RIGID_WALL_MODULUS;

/// The radius `Ig2_Wall_Sphere_ScGeom(hertzian=True)` gives the wall, in sphere radii.
pub(crate) const HERTZIAN_WALL_RADIUS_FACTOR: f64 = 1e8;

/// The YADE driver.
pub struct Yade;

/// Effective modulus and radius YADE uses for a ball scene.
fn hertz_parameters(setup: &CodeSetup) -> (f64, f64) {
    let modulus = setup.mixed_modulus();
    let r1 = setup.sphere.radius;
    let r2 = match (setup.scene, setup.other_sphere) {
        (SceneKind::BallBall, Some(other)) => other.radius,
        _ => HERTZIAN_WALL_RADIUS_FACTOR * r1,
    };
    (modulus, pair_radius(r1, r2))
}

impl Yade {
    /// The clamped damped law YADE integrates for `setup` (linear for the rod), with the mass
    /// of the relative motion ([`CodeSetup::pair_mass`]).
    pub fn dashpot_law(&self, setup: &CodeSetup) -> DashpotLaw {
        let mass = setup.pair_mass();
        match setup.scene {
            SceneKind::RodEnd => {
                clamped_linear_law(mass, setup.stiffness, rod_damping_ratio(setup))
            }
            SceneKind::BallPlate | SceneKind::BallBall => {
                let (modulus, radius) = hertz_parameters(setup);
                let stiffness = 4.0 / 3.0 * modulus * radius.sqrt();
                clamped_hertz_law(
                    mass,
                    stiffness,
                    thornton_damping_ratio(hertz_input_or_target(setup)),
                )
            }
        }
    }

    /// The `en` the script gives `Ip2_FrictMat_FrictMat_MindlinPhys` (Thornton's fit inverted
    /// through the clamped law: some sixty integrations of it, the first time for a target).
    pub(crate) fn input_restitution(setup: &CodeSetup) -> f64 {
        hertz_input_or_target(setup)
    }

    /// The values the script template is filled with for `setup` but its `en`
    /// ([`Yade::input_restitution`], which the template takes in every scene and only the ball
    /// scenes use; a batch lists each impact with these, and its `en` for a ball scene), or why
    /// the setup cannot run.
    pub(crate) fn script_values(
        &self,
        setup: &CodeSetup,
    ) -> Result<Vec<(&'static str, String)>, CodeError> {
        refuse_for_clamped_law(self.name(), setup, "ViscElPhys")?;
        let (linear_stiffness, linear_damping) = match setup.scene {
            SceneKind::RodEnd => {
                let law = self.dashpot_law(setup);
                (law.stiffness, law.damping)
            }
            _ => (0.0, 0.0),
        };
        let mut values = body_values(setup);
        values.extend([
            ("linear_stiffness", exact_number(linear_stiffness)),
            ("linear_damping", exact_number(linear_damping)),
        ]);
        Ok(values)
    }
}

impl CodeDriver for Yade {
    fn card(&self) -> Option<&dyn CalibrationCard> {
        Some(&card::YadeCard)
    }

    fn deck(&self) -> Option<&dyn super::deck::DeckReader> {
        Some(&deck::YadeDeck)
    }

    fn name(&self) -> &'static str {
        "yade"
    }

    fn binary(&self) -> &'static str {
        "yade"
    }

    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        let mut values = self.script_values(setup)?;
        values.push(("restitution", exact_number(Self::input_restitution(setup))));
        let text = fill_template(TEMPLATE, &values)
            .map_err(|reason| setup.unsupported(self.name(), reason.to_string()))?;
        let text = oblique::with_tangential_half(self.name(), setup, text)?;
        Ok(script_input(SCRIPT, text))
    }

    fn parse(
        &self,
        _setup: &CodeSetup,
        workdir: &Path,
        log: &str,
    ) -> Result<ParsedRun, ParseError> {
        let text = super::parse::read_output(workdir.join(TRAJECTORY_FILE))?;
        Ok(ParsedRun {
            trajectory: parse_trajectory(&text)?,
            loop_time: reported(log_value(log, "loop_time="), "loop_time")?,
            version: log_value(log, "version=").map(str::to_string).or_else(|| {
                log.lines()
                    .find_map(|l| l.trim().strip_prefix("Welcome to Yade "))
                    .map(|v| v.trim().to_string())
            }),
        })
    }

    fn runs_oblique(&self) -> bool {
        true
    }

    fn batch(&self) -> Option<&dyn BatchRunner> {
        Some(&batch::YADE_BATCH)
    }

    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        self.dashpot_law(setup).into()
    }

    fn step_scheme(&self) -> StepScheme {
        StepScheme::LeapFrog
    }

    fn expected_restitution(&self, setup: &CodeSetup) -> Option<f64> {
        fit_restitution(setup, &self.dashpot_law(setup))
    }
}

/// The script `file` holding `text`, run by YADE's launcher with one thread and no shell
/// (`yade -j1 -n -x FILE`).
pub(crate) fn script_input(file: &str, text: String) -> RenderedInput {
    RenderedInput {
        file_name: file.to_string(),
        text,
        args: ["-j1", "-n", "-x", file].map(String::from).to_vec(),
    }
}

/// Parse the script's `trajectory.csv`: header `iter,time,overlap,approach_velocity,normal_force`.
pub fn parse_trajectory(text: &str) -> Result<CodeTrajectory, ParseError> {
    parse_csv_columns(text, TRAJECTORY_FILE)
}
