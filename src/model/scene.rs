//! Geometry and materials of the three canonical impacts, reduced to `M`, `C` and `n`.

use serde::{Deserialize, Serialize};

use crate::model::figures::Elastic;

/// Which impact a case describes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SceneKind {
    /// A ball on a massive plate (Hertz, n = 1.5).
    BallPlate,
    /// Two balls, head on (Hertz, n = 1.5).
    BallBall,
    /// A rod's end on a massive rigid plate (linear, n = 1).
    RodEnd,
}

impl SceneKind {
    /// The elastic force model of this impact.
    pub(crate) fn spring(self) -> SpringModel {
        match self {
            SceneKind::RodEnd => SpringModel::Linear,
            SceneKind::BallPlate | SceneKind::BallBall => SpringModel::Hertz,
        }
    }

    /// The name used in case files and reports.
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::BallPlate => "ball_plate",
            SceneKind::BallBall => "ball_ball",
            SceneKind::RodEnd => "rod_end",
        }
    }
}

/// The elastic force model of a contact: which power of the overlap the spring follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum SpringModel {
    /// Hertz, `k δ^1.5` (the balls).
    Hertz,
    /// Linear, `k δ` (the rod's end).
    Linear,
}

impl SpringModel {
    /// The exponent `n` of the elastic force.
    pub(crate) fn exponent(self) -> f64 {
        match self {
            SpringModel::Hertz => 1.5,
            SpringModel::Linear => 1.0,
        }
    }
}

/// The mass of the relative motion of two bodies, kg: `m1 m2 / (m1 + m2)` (the one home of
/// this formula; a massive body is `f64::INFINITY` and gives `m1`).
pub fn reduced_mass(m1: f64, m2: f64) -> f64 {
    if m2.is_infinite() {
        m1
    } else {
        m1 * m2 / (m1 + m2)
    }
}

/// The contact radius of two spheres, m: `R1 R2 / (R1 + R2)` (a flat wall is
/// `f64::INFINITY` and gives `R1`).
pub fn pair_radius(r1: f64, r2: f64) -> f64 {
    if r2.is_infinite() {
        r1
    } else {
        r1 * r2 / (r1 + r2)
    }
}

/// How the ball stiffness `C` is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StiffnessConvention {
    /// Hertz: `C = (4/3) E* sqrt(R*)`.
    #[default]
    Hertz,
    /// The paper's printed `C = a E sqrt(R) / (1 - ν²)` with the first ball's E, ν and R, and
    /// `a = 2/3` on a plate, `a = 1/3` for two balls.
    Paper,
}

/// An isotropic elastic material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio, dimensionless, in (-1, 0.5).
    pub poisson_ratio: f64,
}

impl Material {
    /// The compliance `(1 - ν²) / E`, 1/Pa, that enters `1/E*`.
    pub(crate) fn compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus
    }
}

/// A solid sphere.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ball {
    /// Radius, m.
    pub radius: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Material.
    pub material: Material,
}

impl Ball {
    /// Mass, kg.
    pub(crate) fn mass(&self) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3) * self.density
    }
}

/// The plate under a ball: rigid, or elastic with its own material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Plate {
    /// Does not deform: contributes nothing to `1/E*`.
    Rigid,
    /// Deforms elastically.
    Elastic(Material),
}

/// A cylindrical rod striking a rigid plate with its flat end.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rod {
    /// Diameter `D`, m.
    pub diameter: f64,
    /// Whole length `2H`, m.
    pub length: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
}

impl Rod {
    /// Cross-section area `π D²/4`, m².
    pub(crate) fn area(&self) -> f64 {
        std::f64::consts::PI * self.diameter * self.diameter / 4.0
    }
    /// Mass, kg.
    pub(crate) fn mass(&self) -> f64 {
        self.area() * self.length * self.density
    }
    /// Stiffness `π D² E / (4H)`, N/m: only the lower half (length H) compresses.
    pub(crate) fn stiffness(&self) -> f64 {
        self.area() * self.youngs_modulus / (self.length / 2.0)
    }
}

/// One physical situation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Scene {
    /// A ball on a massive plate.
    BallPlate {
        /// The ball.
        ball: Ball,
        /// The plate.
        plate: Plate,
    },
    /// Two balls head on.
    BallBall {
        /// The first ball.
        ball: Ball,
        /// The second ball.
        other: Ball,
    },
    /// A rod's end on a rigid plate.
    RodEnd {
        /// The rod.
        rod: Rod,
    },
}

impl Scene {
    /// Which impact this is.
    pub(crate) fn kind(&self) -> SceneKind {
        match self {
            Scene::BallPlate { .. } => SceneKind::BallPlate,
            Scene::BallBall { .. } => SceneKind::BallBall,
            Scene::RodEnd { .. } => SceneKind::RodEnd,
        }
    }

    /// The elastic force model.
    pub(crate) fn spring(&self) -> SpringModel {
        self.kind().spring()
    }

    /// Exponent `n` of the elastic force.
    pub(crate) fn exponent(&self) -> f64 {
        self.spring().exponent()
    }

    /// Reduced mass `M`, kg (the plate is massive).
    pub fn reduced_mass(&self) -> f64 {
        match self {
            Scene::BallPlate { ball, .. } => ball.mass(),
            Scene::BallBall { ball, other } => reduced_mass(ball.mass(), other.mass()),
            Scene::RodEnd { rod } => rod.mass(),
        }
    }

    /// Effective modulus `E*`, Pa, of the ball scenes: `1/E* = Σ (1-ν²)/E`.
    pub fn effective_modulus(&self) -> Option<f64> {
        match self {
            Scene::BallPlate { ball, plate } => {
                let plate_compliance = match plate {
                    Plate::Rigid => 0.0,
                    Plate::Elastic(m) => m.compliance(),
                };
                Some(1.0 / (ball.material.compliance() + plate_compliance))
            }
            Scene::BallBall { ball, other } => {
                Some(1.0 / (ball.material.compliance() + other.material.compliance()))
            }
            Scene::RodEnd { .. } => None,
        }
    }

    /// Effective radius `R*`, m, of the ball scenes.
    pub fn effective_radius(&self) -> Option<f64> {
        match self {
            Scene::BallPlate { ball, .. } => Some(ball.radius),
            Scene::BallBall { ball, other } => Some(pair_radius(ball.radius, other.radius)),
            Scene::RodEnd { .. } => None,
        }
    }

    /// Contact stiffness `C`, N/m^n, by the chosen convention (the rod ignores it).
    pub(crate) fn stiffness(&self, convention: StiffnessConvention) -> f64 {
        match (self, convention) {
            (Scene::RodEnd { rod }, _) => rod.stiffness(),
            (_, StiffnessConvention::Hertz) => self.hertz_stiffness(),
            (Scene::BallPlate { ball, .. }, StiffnessConvention::Paper) => {
                paper_ball_stiffness(2.0 / 3.0, ball)
            }
            (Scene::BallBall { ball, .. }, StiffnessConvention::Paper) => {
                paper_ball_stiffness(1.0 / 3.0, ball)
            }
        }
    }

    /// Hertz stiffness `(4/3) E* sqrt(R*)`, N/m^1.5 (the rod's linear stiffness for rod_end).
    pub(crate) fn hertz_stiffness(&self) -> f64 {
        match (self.effective_modulus(), self.effective_radius()) {
            (Some(e), Some(r)) => 4.0 / 3.0 * e * r.sqrt(),
            _ => match self {
                Scene::RodEnd { rod } => rod.stiffness(),
                _ => unreachable!("ball scenes have E* and R*"),
            },
        }
    }
}

impl Scene {
    /// The elastic contact of the scene's own spring at approach speed `impact_velocity`
    /// (m/s): Hertz's for the balls, the linear spring's for the rod. It is the yardstick of
    /// the codes' time steps and of the "vs elastic" comparison.
    pub fn elastic_contact(&self, impact_velocity: f64) -> Elastic {
        let mass = self.reduced_mass();
        match (self.effective_modulus(), self.effective_radius()) {
            (Some(modulus), Some(radius)) => {
                crate::model::exact::hertz_elastic(mass, modulus, radius, impact_velocity)
            }
            _ => {
                let omega_inverse = (mass / self.hertz_stiffness()).sqrt();
                Elastic {
                    peak_deformation: impact_velocity * omega_inverse,
                    contact_time: std::f64::consts::PI * omega_inverse,
                    ..Elastic::default()
                }
            }
        }
    }
}

fn paper_ball_stiffness(a: f64, ball: &Ball) -> f64 {
    let m = ball.material;
    a * m.youngs_modulus * ball.radius.sqrt() / (1.0 - m.poisson_ratio * m.poisson_ratio)
}
