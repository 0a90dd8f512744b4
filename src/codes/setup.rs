//! The equivalent setup of a case in a DEM code (physics.md §5): the bodies, their materials,
//! the partner of the impact, the time step and the run length.

use serde::{Deserialize, Serialize};

use super::CodeDriver;
use thiserror::Error;

use super::conventions::Conventions;
use crate::model::case::Case;
use crate::model::count::ceil_count;
use crate::model::scene::{Ball, Plate, Scene, SceneKind, SpringModel, pair_radius, reduced_mass};
use crate::model::tangential::{PlaneMotion, TangentialBodies, TangentialLaw};
use crate::solve::SolveError;
use crate::solve::dashpot::own_law_metrics;

/// Young's modulus, Pa, given to the wall that stands for a rigid plate in a code whose walls
/// always mix their material into `E*`: at 1e30 the wall's `(1-ν²)/E` (1e-30) is below the
/// rounding of a steel ball's compliance (4.55e-12 × 1.1e-16 = 5e-28), so the code's `E*` is
/// the ball's `E/(1-ν²)` to the last bit.
pub(crate) const RIGID_WALL_MODULUS: f64 = 1e30;
/// Poisson's ratio given to that wall (irrelevant at [`RIGID_WALL_MODULUS`]).
pub(crate) const RIGID_WALL_POISSON: f64 = 0.0;

/// `E*` of two materials as YADE's `Ip2_FrictMat_FrictMat_MindlinPhys` and Kratos'
/// `DEM_D_Hertz_viscous_Coulomb` (and `DEM_D_Linear_viscous_Coulomb`) form it, with their
/// operations: `E1 E2 / ((1−ν1²) E2 + (1−ν2²) E1)`.
pub(crate) fn mixed_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    e1 * e2 / ((1.0 - nu1 * nu1) * e2 + (1.0 - nu2 * nu2) * e1)
}

/// One sphere in a DEM code (a ball, or the sphere that stands for the rod).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CodeSphere {
    /// Radius, m.
    pub radius: f64,
    /// Density, kg/m³ (for the rod's sphere, chosen so that its mass is the rod's).
    pub density: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio; `None` for the rod (its linear model has none).
    pub poisson_ratio: Option<f64>,
}

/// Everything a DEM code needs for one normal impact, in SI units.
///
/// At `t = 0` the bodies touch (zero overlap) and approach at `impact_velocity`. Gravity,
/// friction and rotation are off. For `ball_ball` the driver chooses the frame (for instance
/// the centre-of-mass frame); only the relative normal motion is compared.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CodeSetup {
    /// Case name (the case file's stem).
    pub case_name: String,
    /// Which impact.
    pub scene: SceneKind,
    /// The moving sphere.
    pub sphere: CodeSphere,
    /// The second sphere for `ball_ball`; `None` when the other body is a plate.
    pub other_sphere: Option<CodeSphere>,
    /// The plate's material `(E, ν)` for `ball_plate`; `None` for a rigid plate (and rod_end).
    pub plate_material: Option<(f64, f64)>,
    /// Effective modulus `E*`, Pa (ball scenes).
    pub effective_modulus: Option<f64>,
    /// Effective radius `R*`, m (ball scenes).
    pub effective_radius: Option<f64>,
    /// Reduced mass `M`, kg.
    pub reduced_mass: f64,
    /// Spring constant: Hertz `k = (4/3) E* sqrt(R*)`, N/m^1.5, or linear `k`, N/m (rod_end).
    pub stiffness: f64,
    /// Exponent of the spring: 1.5 (Hertz) or 1 (linear).
    pub exponent: f64,
    /// Normal approach speed at contact, m/s (relative speed for ball_ball).
    pub impact_velocity: f64,
    /// The coefficient of restitution the code's damping is asked to realise.
    pub target_restitution: f64,
    /// The paper's loss coefficient η itself, for a code whose law is the paper's (it is given
    /// η, not a COR: [`CodeDriver::takes_loss_coefficient`]); `None` in the setups of the
    /// other codes, which take `target_restitution`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loss_coefficient: Option<f64>,
    /// Time step, s.
    pub timestep: f64,
    /// Number of steps to run: enough to end the contact, no more.
    pub steps: u64,
    /// Ask the code to cut the contact force off at zero instead of letting the dashpot
    /// attract (LIGGGHTS `limitForce on`, LAMMPS `limit_damping`; YADE's laws always do). The
    /// code then realises the clamped law's COR, not the target: its
    /// [`CodeDriver::expected_restitution`].
    #[serde(default)]
    pub clamp_attractive: bool,
    /// The conventions of the build that runs it, as its probe measured them (LAMMPS builds);
    /// `None` for the other codes and in records made before the probe, whose driver then
    /// plans with the conventions its build was measured to have.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conventions: Option<Conventions>,
    /// The tangential half of an oblique or spinning impact; `None` for a normal one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub oblique: Option<CodeOblique>,
}

/// The tangential half of an oblique or spinning impact as a DEM code is given it: each
/// ball's motion along the contact plane at first contact (sign convention of
/// [`crate::model::tangential`]; at a plate the plane's axis is the code's x and the spin the
/// ball's ω_y), Coulomb's μ and the tangential law.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CodeOblique {
    /// The ball's centre velocity along the plane (m/s) and spin (rad/s).
    pub ball: PlaneMotion,
    /// The other ball's, for two balls; `None` at a plate.
    pub partner: Option<PlaneMotion>,
    /// Coulomb's friction coefficient μ.
    pub friction_coefficient: f64,
    /// The tangential law the case names.
    pub law: TangentialLaw,
}

impl CodeSetup {
    /// Velocities `(v1, v2)` along the line of centres, m/s, of the two bodies in the
    /// centre-of-mass frame (body 1 moves towards body 2 with positive speed). For a plate the
    /// second body is at rest and `v1 = impact_velocity`.
    pub(crate) fn centre_of_mass_velocities(&self) -> (f64, f64) {
        match self.other_sphere {
            Some(other) => {
                let total = self.sphere.mass + other.mass;
                (
                    self.impact_velocity * other.mass / total,
                    -self.impact_velocity * self.sphere.mass / total,
                )
            }
            None => (self.impact_velocity, 0.0),
        }
    }

    /// The contact radius of the pair, m: the sphere's own at a flat wall (the wall's radius
    /// is infinite), `R1 R2 / (R1 + R2)` between two spheres.
    pub(crate) fn pair_radius(&self) -> f64 {
        pair_radius(
            self.sphere.radius,
            self.other_sphere.map_or(f64::INFINITY, |o| o.radius),
        )
    }

    /// The mass of the relative motion, kg: the sphere's own at a wall (the wall does not
    /// move), `m1 m2 / (m1 + m2)` between two spheres, from the given masses.
    pub fn pair_mass(&self) -> f64 {
        reduced_mass(
            self.sphere.mass,
            self.other_sphere.map_or(f64::INFINITY, |o| o.mass),
        )
    }

    /// The spring model the code must use.
    pub(crate) fn spring(&self) -> SpringModel {
        self.scene.spring()
    }

    /// Simulated duration, s.
    pub fn duration(&self) -> f64 {
        self.timestep * self.steps as f64
    }

    /// The second body's material `(E, ν)` in a ball scene: the other ball's (ν 0 where it has
    /// none), else the plate's, else the rigid plate's stand-in ([`RIGID_WALL_MODULUS`], ν 0).
    pub(crate) fn second_material(&self) -> (f64, f64) {
        match (self.scene, self.other_sphere, self.plate_material) {
            (SceneKind::BallBall, Some(other), _) => {
                (other.youngs_modulus, other.poisson_ratio.unwrap_or(0.0))
            }
            (_, _, Some(plate)) => plate,
            _ => (RIGID_WALL_MODULUS, RIGID_WALL_POISSON),
        }
    }

    /// The second body's material `(E, ν)` in a ball scene as a code with a material per body
    /// gives it: the other ball's (`None` where it has no ν), the plate's or the rigid plate's
    /// stand-in ([`RIGID_WALL_MODULUS`], ν 0); `None` for the rod.
    pub(crate) fn partner_material(&self) -> Option<(f64, f64)> {
        match self.scene {
            SceneKind::BallPlate => Some(
                self.plate_material
                    .unwrap_or((RIGID_WALL_MODULUS, RIGID_WALL_POISSON)),
            ),
            SceneKind::BallBall => self
                .other_sphere
                .and_then(|o| o.poisson_ratio.map(|nu| (o.youngs_modulus, nu))),
            SceneKind::RodEnd => None,
        }
    }

    /// `E*` of a ball scene as YADE's and Kratos' Hertz laws mix the sphere's material with
    /// the [`second_material`](CodeSetup::second_material) ([`mixed_modulus`]).
    pub(crate) fn mixed_modulus(&self) -> f64 {
        let s = self.sphere;
        let (e2, nu2) = self.second_material();
        mixed_modulus(s.youngs_modulus, s.poisson_ratio.unwrap_or(0.0), e2, nu2)
    }

    /// Refuses, as a fault of `code`, a setup that has no positive time step or no steps, or
    /// a ball pair without its second ball: what no code can run.
    pub(crate) fn refuse_unrunnable(&self, code: &str) -> Result<(), super::CodeError> {
        if !(self.timestep > 0.0 && self.timestep.is_finite()) || self.steps == 0 {
            return Err(self.unsupported(code, "time step and step count must be positive"));
        }
        if self.scene == SceneKind::BallBall && self.other_sphere.is_none() {
            return Err(self.unsupported(code, "ball_ball needs a second sphere"));
        }
        Ok(())
    }

    /// The start of a run in a code whose deck puts sphere 1 at `height` above the contact
    /// point, moving down, and below it the plane `z = 0` or, for two balls, sphere 2 at
    /// `−r2`, both at the velocities of the centre-of-mass frame ([`CodeFrame`]); `mass` is a
    /// sphere's mass as the code forms it.
    ///
    /// [`CodeFrame`]: crate::solve::dashpot::CodeFrame
    pub(crate) fn frame_below(
        &self,
        height: f64,
        mass: impl Fn(&CodeSphere) -> f64,
    ) -> crate::solve::dashpot::CodeFrame {
        use crate::solve::dashpot::{CodeFrame, FrameBody};
        let (v1, v2) = self.centre_of_mass_velocities();
        let upper = FrameBody {
            height,
            velocity: -v1,
            mass: mass(&self.sphere),
        };
        match self.other_sphere {
            Some(other) if self.scene == SceneKind::BallBall => CodeFrame {
                reach: self.sphere.radius + other.radius,
                upper,
                lower: Some(FrameBody {
                    height: -other.radius,
                    velocity: -v2,
                    mass: mass(&other),
                }),
            },
            _ => CodeFrame {
                reach: self.sphere.radius,
                upper,
                lower: None,
            },
        }
    }

    /// Mindlin's effective shear modulus `G*` of a ball scene, Pa: `1/G* = Σ (2 − ν)/G` over
    /// the sphere and its [`partner_material`](CodeSetup::partner_material) (the rigid
    /// plate's stand-in adds nothing a double can hold); `None` for the rod, or a partner
    /// without ν.
    pub(crate) fn effective_shear_modulus(&self) -> Option<f64> {
        use crate::model::tangential::mindlin_compliance;
        let (e2, nu2) = self.partner_material()?;
        let own = mindlin_compliance(self.sphere.youngs_modulus, self.sphere.poisson_ratio?);
        Some(1.0 / (own + mindlin_compliance(e2, nu2)))
    }

    /// `code`'s refusal of this setup, for `reason`.
    pub(crate) fn unsupported(&self, code: &str, reason: impl Into<String>) -> super::CodeError {
        super::CodeError::Unsupported {
            code: code.into(),
            case: self.case_name.clone(),
            reason: reason.into(),
        }
    }
}

/// Default number of steps per estimated contact time for a code's time step.
pub(crate) const DEFAULT_STEPS_PER_CONTACT: u32 = 1000;

/// The elastic contact time of the case's spring, s: Hertz's `2 J(1.5) δ_max / v0` for the
/// balls, `π sqrt(M/k)` for the rod. It sets the codes' time step.
pub fn elastic_contact_time(case: &Case) -> f64 {
    case.scene
        .elastic_contact(case.impact_velocity)
        .contact_time
}

fn code_sphere(ball: &Ball) -> CodeSphere {
    CodeSphere {
        radius: ball.radius,
        density: ball.density,
        mass: ball.mass(),
        youngs_modulus: ball.material.youngs_modulus,
        poisson_ratio: Some(ball.material.poisson_ratio),
    }
}

/// The equivalent setup of `case` (physics.md §5) at time step `timestep` (s), with the run
/// length left at zero: [`prepare`] sets it from the code's own law, and keeps the case's η
/// only for a code that takes it.
pub(crate) fn setup_for_case(case: &Case, timestep: f64) -> CodeSetup {
    let scene = &case.scene;
    let (sphere, other_sphere, plate_material) = match scene {
        Scene::BallPlate { ball, plate } => (
            code_sphere(ball),
            None,
            match plate {
                Plate::Rigid => None,
                Plate::Elastic(m) => Some((m.youngs_modulus, m.poisson_ratio)),
            },
        ),
        Scene::BallBall { ball, other } => (code_sphere(ball), Some(code_sphere(other)), None),
        Scene::RodEnd { rod } => {
            // A sphere of the rod's mass, as wide as the rod.
            let radius = rod.diameter / 2.0;
            let volume = 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
            (
                CodeSphere {
                    radius,
                    density: rod.mass() / volume,
                    mass: rod.mass(),
                    youngs_modulus: rod.youngs_modulus,
                    poisson_ratio: None,
                },
                None,
                None,
            )
        }
    };
    CodeSetup {
        case_name: case.name.clone(),
        scene: scene.kind(),
        sphere,
        other_sphere,
        plate_material,
        effective_modulus: scene.effective_modulus(),
        effective_radius: scene.effective_radius(),
        reduced_mass: scene.reduced_mass(),
        stiffness: scene.hertz_stiffness(),
        exponent: scene.exponent(),
        impact_velocity: case.impact_velocity,
        target_restitution: case.restitution(),
        loss_coefficient: Some(case.loss_coefficient),
        timestep,
        steps: 0,
        clamp_attractive: false,
        conventions: None,
        oblique: case.oblique.as_ref().and_then(|oblique| {
            let bodies = TangentialBodies::of(scene, oblique)?;
            Some(CodeOblique {
                ball: bodies.ball.2,
                partner: bodies.other.map(|(_, _, motion)| motion),
                friction_coefficient: oblique.friction_coefficient,
                law: oblique.law,
            })
        }),
    }
}

/// Why a code's run could not be set up.
#[derive(Debug, Error)]
pub enum SetupError {
    /// The build's conventions could not be measured.
    #[error("{code}")]
    Probe {
        /// The code's name.
        code: &'static str,
        /// Why.
        source: super::ProbeError,
    },
    /// The code's own law could not be integrated to size the run.
    #[error(transparent)]
    OwnLaw(#[from] SolveError),
}

/// The setup of `case` for `driver`, its time step either given or the elastic contact time
/// over `steps_per_contact`, and its run length the contact time of the code's own law (at
/// zero step error) plus 5 % and three steps: enough to end the contact, no more. A build with
/// a probe is probed first (once per process) and the setup carries what it measured.
pub fn prepare(
    driver: &dyn CodeDriver,
    case: &Case,
    steps_per_contact: Option<u32>,
    timestep: Option<f64>,
    clamp_attractive: bool,
) -> Result<CodeSetup, SetupError> {
    let conventions = driver
        .measured_conventions()
        .map_err(|source| SetupError::Probe {
            code: driver.name(),
            source,
        })?;
    Ok(prepare_with(
        driver,
        case,
        steps_per_contact,
        timestep,
        clamp_attractive,
        conventions,
    )?)
}

/// [`prepare`] with the build's conventions given (a stored record's), without a probe.
pub fn prepare_with(
    driver: &dyn CodeDriver,
    case: &Case,
    steps_per_contact: Option<u32>,
    timestep: Option<f64>,
    clamp_attractive: bool,
    conventions: Option<Conventions>,
) -> Result<CodeSetup, SolveError> {
    let dt = timestep.unwrap_or_else(|| {
        elastic_contact_time(case) / steps_per_contact.unwrap_or(DEFAULT_STEPS_PER_CONTACT) as f64
    });
    let mut setup = setup_for_case(case, dt);
    setup.clamp_attractive = clamp_attractive;
    setup.conventions = conventions;
    if !driver.takes_loss_coefficient() {
        setup.loss_coefficient = None;
    }
    let law = driver.law(&setup);
    let contact = own_law_metrics(&law, setup.impact_velocity, 1e-12)?.contact_time;
    // A step so small that the count passes u64 saturates: the run then meets its time limit.
    setup.steps = ceil_count(1.05 * contact / dt).map_or(u64::MAX, |n| n.saturating_add(3));
    Ok(setup)
}

/// The setup of the shipped case `cases/<scene>.toml` at loss coefficient `eta` for `code`, at
/// 200 steps per contact and with no probe: what the drivers' unit tests render.
#[cfg(test)]
pub(crate) fn shipped_setup(code: super::CodeName, scene: &str, eta: f64) -> CodeSetup {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cases")
        .join(format!("{scene}.toml"));
    let case = Case::load(&path).unwrap().with_loss_coefficient(eta);
    prepare_with(code.driver(), &case, Some(200), None, false, None).unwrap()
}

/// The setups of `cases/<scene>.toml` for `code` at three loss coefficients across the range
/// ([`shipped_setup`]): a batch's worth.
#[cfg(test)]
pub(crate) fn shipped_setups(code: super::CodeName, scene: &str) -> Vec<CodeSetup> {
    [0.0, 0.35, 0.9]
        .map(|eta| shipped_setup(code, scene, eta))
        .to_vec()
}
