//! The tangential half of an impact: what an oblique or spinning case adds to a normal one, the
//! tangential law, and the closed forms that hold exactly.
//!
//! Sign convention (the book's "The tangential half" states it with a figure in words): `t` is
//! the tangential axis along the contact plane, `v_t` the ball's centre velocity along it. The
//! spin `ω` is about the axis in the contact plane normal to `t`, positive in the sense in which
//! the ball rolls towards `+t` on the body below it: the ball's surface at the contact point then
//! moves at `v_t − R ω`, and a ball rolling without slip has `v_t = R ω`. The slip of the
//! contact is that surface velocity less the other body's (zero for a plate). For two balls
//! both spins are components of the same axial vector, so the other ball's surface at the
//! contact moves at `v_t2 + R2 ω2`.

use serde::{Deserialize, Serialize};

use crate::model::scene::{Ball, Plate, Scene};

/// What the other ball does along the contact plane in a ball–ball case.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OtherBallMotion {
    /// It neither moves along the plane nor spins.
    #[default]
    AtRest,
    /// The point mirror of the ball through the contact point: centre at `−tangential_velocity`
    /// and the same spin vector (so the slip of the contact doubles for equal balls).
    Opposed,
    /// The mirror image of the ball in the contact plane: centre at `+tangential_velocity` and
    /// the opposite spin vector, so that for equal balls both surfaces move together at the
    /// contact and nothing slips (Chung & Ooi's test 7: two spheres spinning in opposite
    /// senses).
    Mirrored,
}

/// The tangential spring of the law.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "spring")]
pub enum TangentialSpring {
    /// Mindlin's no-slip stiffness `k_t = 8 G* sqrt(R* δ)`, N/m, as LIGGGHTS' `model hertz` and
    /// the paper's `model paper` hand it to `tangential history`.
    Mindlin,
    /// A constant `k_t`, N/m.
    Linear {
        /// `k_t`, N/m.
        stiffness: f64,
    },
    /// `k_t = ratio × C δ^(n−1)`: the normal spring's secant stiffness times a ratio, as LAMMPS'
    /// classic `gran/hertz/history` scales both springs by `sqrt(R* δ)` (its `Kt NULL` is
    /// `2 Kn / 7`).
    Proportional {
        /// `k_t` over the normal secant stiffness, dimensionless (the case's
        /// `stiffness_ratio`).
        #[serde(rename = "stiffness_ratio")]
        ratio: f64,
    },
}

/// The tangential law: a history spring bounded by Coulomb, with an optional dashpot.
///
/// Stepped as LIGGGHTS' `tangential history` steps it: the spring's elongation `ξ` grows with
/// the slip, the spring force is `−k_t ξ`; where `k_t |ξ|` exceeds `μ |F_n|` (the whole normal
/// force of the law) the force is `μ |F_n|` against `ξ` and `ξ` is cut back to the bound, and
/// the dashpot acts only while the spring is inside the bound.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TangentialLaw {
    /// The spring.
    #[serde(flatten)]
    pub spring: TangentialSpring,
    /// Damping ratio `ζ`, dimensionless, of the dashpot `γ_t = 2 ζ sqrt(k_t M*)` (`M*` the
    /// reduced mass); 0 for none, and a case gives more only with the linear spring. With a
    /// dashpot the Coulomb bound applies to spring and dashpot together (LAMMPS' rule).
    pub damping_ratio: f64,
}

impl Default for TangentialLaw {
    /// What the paper's builds run: `tangential history` with the Mindlin spring and no
    /// tangential damping (`model paper` sets `gammat = 0`).
    fn default() -> Self {
        TangentialLaw {
            spring: TangentialSpring::Mindlin,
            damping_ratio: 0.0,
        }
    }
}

/// The tangential part of an oblique or spinning case.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Oblique {
    /// The ball's centre velocity along the contact plane at first contact, m/s.
    pub tangential_velocity: f64,
    /// The ball's spin at first contact, rad/s (sign: see the module).
    pub angular_velocity: f64,
    /// Coulomb's friction coefficient μ, dimensionless, ≥ 0.
    pub friction_coefficient: f64,
    /// Ball–ball: what the other ball does.
    pub other_ball: OtherBallMotion,
    /// The tangential law.
    pub law: TangentialLaw,
}

/// Shear modulus `E / (2 (1 + ν))`, Pa.
fn shear_modulus(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    youngs_modulus / (2.0 * (1.0 + poisson_ratio))
}

/// Mindlin's `(2 − ν)/G` of one body, 1/Pa.
pub(crate) fn mindlin_compliance(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    (2.0 - poisson_ratio) / shear_modulus(youngs_modulus, poisson_ratio)
}

/// Effective shear modulus `G*`, Pa: `1/G* = Σ (2 − ν)/G` over the bodies (a rigid plate adds
/// nothing); `None` for the rod.
pub fn effective_shear_modulus(scene: &Scene) -> Option<f64> {
    let ball = |b: &Ball| mindlin_compliance(b.material.youngs_modulus, b.material.poisson_ratio);
    match scene {
        Scene::BallPlate { ball: b, plate } => {
            let plate = match plate {
                Plate::Rigid => 0.0,
                Plate::Elastic(m) => mindlin_compliance(m.youngs_modulus, m.poisson_ratio),
            };
            Some(1.0 / (ball(b) + plate))
        }
        Scene::BallBall { ball: b, other } => Some(1.0 / (ball(b) + ball(other))),
        Scene::RodEnd { .. } => None,
    }
}

/// A body's motion along the contact plane: centre velocity (m/s) and spin (rad/s).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlaneMotion {
    /// Centre velocity along `t`, m/s.
    pub tangential_velocity: f64,
    /// Spin, rad/s.
    pub angular_velocity: f64,
}

/// The moving bodies of a ball scene as the tangential motion sees them: mass (kg), radius (m)
/// and the motion at first contact. The moment of inertia is a solid sphere's `2/5 m R²`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentialBodies {
    /// The ball: mass, radius, motion.
    pub ball: (f64, f64, PlaneMotion),
    /// The other ball (ball–ball), else `None` (a plate, which does not move).
    pub other: Option<(f64, f64, PlaneMotion)>,
}

impl TangentialBodies {
    /// The bodies of `scene` (a ball scene) with `oblique`'s motion.
    pub fn of(scene: &Scene, oblique: &Oblique) -> Option<TangentialBodies> {
        let motion = PlaneMotion {
            tangential_velocity: oblique.tangential_velocity,
            angular_velocity: oblique.angular_velocity,
        };
        match scene {
            Scene::BallPlate { ball, .. } => Some(TangentialBodies {
                ball: (ball.mass(), ball.radius, motion),
                other: None,
            }),
            Scene::BallBall { ball, other } => {
                let other_motion = match oblique.other_ball {
                    OtherBallMotion::AtRest => PlaneMotion {
                        tangential_velocity: 0.0,
                        angular_velocity: 0.0,
                    },
                    OtherBallMotion::Opposed => PlaneMotion {
                        tangential_velocity: -oblique.tangential_velocity,
                        angular_velocity: oblique.angular_velocity,
                    },
                    OtherBallMotion::Mirrored => PlaneMotion {
                        tangential_velocity: oblique.tangential_velocity,
                        angular_velocity: -oblique.angular_velocity,
                    },
                };
                Some(TangentialBodies {
                    ball: (ball.mass(), ball.radius, motion),
                    other: Some((other.mass(), other.radius, other_motion)),
                })
            }
            Scene::RodEnd { .. } => None,
        }
    }

    /// The slip of the contact, m/s: the ball's surface velocity at the contact point less the
    /// other body's.
    pub fn slip(&self) -> f64 {
        let (_, r, m) = self.ball;
        let own = m.tangential_velocity - r * m.angular_velocity;
        match self.other {
            None => own,
            Some((_, r2, m2)) => own - (m2.tangential_velocity + r2 * m2.angular_velocity),
        }
    }

    /// The motions after a tangential impulse `impulse` (N·s, along `t`, on the ball; the other
    /// ball takes its opposite): `Δv = J/m`, `Δω = −R J / I` for the ball, `Δv = −J/m`,
    /// `Δω = −R J / I` for the other (both torques are `R J` about the same axis).
    pub fn after(&self, impulse: f64) -> (PlaneMotion, Option<PlaneMotion>) {
        let moved = |(m, r, motion): (f64, f64, PlaneMotion), j: f64| PlaneMotion {
            tangential_velocity: motion.tangential_velocity + j / m,
            angular_velocity: motion.angular_velocity - r * impulse / inertia(m, r),
        };
        (
            moved(self.ball, impulse),
            self.other.map(|o| moved(o, -impulse)),
        )
    }

    /// Kinetic energy of the tangential motion (translation along `t` and spin), J.
    pub fn energy(ball: (f64, f64, PlaneMotion), other: Option<(f64, f64, PlaneMotion)>) -> f64 {
        let one = |(m, r, p): (f64, f64, PlaneMotion)| {
            0.5 * m * p.tangential_velocity.powi(2)
                + 0.5 * inertia(m, r) * p.angular_velocity.powi(2)
        };
        one(ball) + other.map_or(0.0, one)
    }
}

/// Moment of inertia of a solid sphere, `2/5 m R²`, kg·m².
pub fn inertia(mass: f64, radius: f64) -> f64 {
    0.4 * mass * radius * radius
}

/// The slip's response to a tangential force on a pair of solid spheres (or one on a plate):
/// `d(slip)/dt = (7/2) F_t / M*`; this is the 7/2.
pub const SLIP_FACTOR: f64 = 3.5;

/// Which closed form a tangential result is compared with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClosedFormKind {
    /// Coulomb sliding throughout the contact.
    GrossSliding,
    /// An undamped proportional spring of ratio 2/7 that never reaches the Coulomb bound: the
    /// slip turns round exactly.
    StickReversal,
}

impl ClosedFormKind {
    /// Its name in words.
    pub fn describe(self) -> &'static str {
        match self {
            ClosedFormKind::GrossSliding => "Coulomb sliding throughout",
            ClosedFormKind::StickReversal => "stick reversal (2/7 spring, no slip)",
        }
    }
}

/// The tangential closed form of an impact: the tangential impulse on the ball, N·s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentialClosedForm {
    /// Which one.
    pub kind: ClosedFormKind,
    /// The tangential impulse on the ball, N·s.
    pub impulse: f64,
}

/// Coulomb sliding throughout: the tangential impulse on the ball is `−sign(s0) μ (1+e) M* v_n`
/// (the whole normal impulse times μ, against the slip), N·s. The rigid-body condition for it,
/// `|s0| ≥ (7/2) μ (1+e) v_n`, holds for any normal law whose force never attracts; a history
/// spring adds its own (see [`gross_sliding_holds`]).
pub fn gross_sliding_impulse(
    reduced_mass: f64,
    normal_velocity: f64,
    restitution: f64,
    friction: f64,
    slip: f64,
) -> f64 {
    -slip.signum() * friction * (1.0 + restitution) * reduced_mass * normal_velocity
}

/// The rigid-body stick limit (no tangential compliance, μ large enough): the slip is brought
/// to zero and stays there, so the impulse on the ball is `−s0 M* / (7/2)`, N·s; for a ball on a
/// plate `v_t' = (5 v_t + 2 R ω)/7 = R ω'`. It needs `|s0| ≤ (7/2) μ (1+e) v_n`.
pub fn rigid_stick_impulse(reduced_mass: f64, slip: f64) -> f64 {
    -slip * reduced_mass / SLIP_FACTOR
}

/// Whether the law slides throughout the contact of the paper's law at loss coefficient `eta`,
/// exponent 1.5 (Hertz) and the case's COR `e`: the rigid-body condition
/// `|s0| ≥ (7/2) μ (1+e) v_n`, and for the history spring that its force reaches the bound at
/// first contact and grows at least as fast as the bound while loading. For the Mindlin spring
/// the second part is exactly `|s0| ≥ μ (1+η) C v_n / (8 G* sqrt(R*))` (both forces grow as
/// δ^1.5 at first contact and their rates differ linearly in the approach rate, so the ends of
/// the loading decide). For the proportional spring it is `|s0| ≥ μ (1+η) v_n / ratio`, and
/// the linear spring (whose force starts as δ against the bound's δ^1.5) always reaches the
/// bound first but is not checked along the loading: `None`, no closed form claimed.
#[allow(clippy::too_many_arguments)]
pub fn gross_sliding_holds(
    law: &TangentialLaw,
    friction: f64,
    slip: f64,
    normal_velocity: f64,
    restitution: f64,
    eta: f64,
    hertz_stiffness: f64,
    shear_modulus: f64,
    radius: f64,
    exponent: f64,
) -> Option<bool> {
    let s = slip.abs();
    let rigid = s >= SLIP_FACTOR * friction * (1.0 + restitution) * normal_velocity;
    // The ball scenes' exponent is exactly 1.5 (`SpringModel::exponent`).
    #[allow(clippy::float_cmp)]
    let hertz = exponent == 1.5;
    let spring = match law.spring {
        TangentialSpring::Mindlin if hertz => {
            s * 8.0 * shear_modulus * radius.sqrt()
                >= friction * (1.0 + eta) * hertz_stiffness * normal_velocity
        }
        TangentialSpring::Proportional { ratio } => {
            s * ratio >= friction * (1.0 + eta) * normal_velocity
        }
        _ => return None,
    };
    Some(rigid && spring)
}

/// Whether the stick-reversal closed form holds: the proportional spring at ratio 2/7 (to
/// 1e-12), no damping, an elastic normal law (η = 0) and a slip inside the bound
/// (`|s0| ≤ (7/2) μ v_n`). Then `ξ = (s0/v_n) δ` solves the tangential motion (both springs
/// share the frequency `sqrt(C δ^(n−1)/M*)` at every δ) and the slip leaves as `−s0`: the
/// impulse on the ball is `−2 s0 M* / (7/2)`; for a ball on a plate without spin
/// `v_t' = 3 v_t / 7` and `R ω' = 10 v_t / 7`.
pub fn stick_reversal_holds(
    law: &TangentialLaw,
    eta: f64,
    friction: f64,
    slip: f64,
    v_n: f64,
) -> bool {
    matches!(law.spring, TangentialSpring::Proportional { ratio } if (ratio - 2.0 / 7.0).abs() <= 1e-12)
        && law.damping_ratio == 0.0
        && eta == 0.0
        && slip.abs() <= SLIP_FACTOR * friction * v_n
}

/// Thornton's normalised angle of a slip `slip` (m/s) at normal incidence speed `v_n` (m/s),
/// friction μ and COR `e`: `ψ = 2 slip / (μ (1+e) v_n)`, the contact point's tangent of the
/// angle over its gross-sliding scale. Incident: `ψ = 2 tanθ/(μ(1+e))` with `tanθ = s0/v_n`;
/// in gross sliding `ψ' = ψ − 7`. `None` at μ = 0.
pub fn normalised_angle(slip: f64, v_n: f64, friction: f64, restitution: f64) -> Option<f64> {
    (friction > 0.0).then(|| 2.0 * slip / (friction * (1.0 + restitution) * v_n))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stick-reversal numbers of the literature follow from the impulse: `v_t' = 3 v_t/7`,
    /// `R ω' = 10 v_t/7` for a ball on a plate without initial spin.
    #[test]
    fn stick_reversal_gives_three_sevenths() {
        let (m, r, v) = (2.0, 0.1, 1.3);
        let bodies = TangentialBodies {
            ball: (
                m,
                r,
                PlaneMotion {
                    tangential_velocity: v,
                    angular_velocity: 0.0,
                },
            ),
            other: None,
        };
        let (after, _) = bodies.after(-2.0 * v * m / SLIP_FACTOR);
        assert!((after.tangential_velocity - 3.0 * v / 7.0).abs() < 1e-14);
        assert!((r * after.angular_velocity - 10.0 * v / 7.0).abs() < 1e-14);
        // The slip reversed.
        let out = after.tangential_velocity - r * after.angular_velocity;
        assert!((out + v).abs() < 1e-14);
    }

    /// Rolling without slip carries no slip, and the rigid stick limit ends rolling.
    #[test]
    fn rigid_stick_ends_in_rolling() {
        let (m, r) = (0.3, 0.02);
        let bodies = TangentialBodies {
            ball: (
                m,
                r,
                PlaneMotion {
                    tangential_velocity: 1.0,
                    angular_velocity: -20.0,
                },
            ),
            other: None,
        };
        let (after, _) = bodies.after(rigid_stick_impulse(m, bodies.slip()));
        assert!((after.tangential_velocity - r * after.angular_velocity).abs() < 1e-14);
        assert!((after.tangential_velocity - (5.0 * 1.0 + 2.0 * r * -20.0) / 7.0).abs() < 1e-14);
    }

    /// The mirrored other ball's surface moves with the ball's at the contact: two equal balls
    /// spinning in opposite senses do not slip, whatever their speed along the plane.
    #[test]
    fn a_mirrored_ball_does_not_slip() {
        use crate::model::scene::{Ball, Material};
        let ball = Ball {
            radius: 0.1,
            density: 2700.0,
            material: Material {
                youngs_modulus: 7e10,
                poisson_ratio: 0.33,
            },
        };
        let scene = Scene::BallBall { ball, other: ball };
        let oblique = Oblique {
            tangential_velocity: 0.3,
            angular_velocity: 7.0,
            friction_coefficient: 0.4,
            other_ball: OtherBallMotion::Mirrored,
            law: TangentialLaw::default(),
        };
        let bodies = TangentialBodies::of(&scene, &oblique).unwrap();
        assert!(bodies.slip().abs() < 1e-15, "{}", bodies.slip());
        let opposed = Oblique {
            other_ball: OtherBallMotion::Opposed,
            ..oblique
        };
        let doubled = TangentialBodies::of(&scene, &opposed).unwrap().slip();
        assert!(
            (doubled - 2.0 * (0.3 - 0.1 * 7.0)).abs() < 1e-15,
            "{doubled}"
        );
    }

    /// For two equal balls the slip responds to the impulse on the first with 7/2 over M*.
    #[test]
    fn two_balls_share_the_slip_factor() {
        let p = |v, w| PlaneMotion {
            tangential_velocity: v,
            angular_velocity: w,
        };
        let bodies = TangentialBodies {
            ball: (1.0, 0.1, p(1.0, 3.0)),
            other: Some((3.0, 0.2, p(-0.5, 1.0))),
        };
        let reduced = 1.0 * 3.0 / 4.0;
        let j = 0.01;
        let (a, b) = bodies.after(j);
        let moved = TangentialBodies {
            ball: (1.0, 0.1, a),
            other: Some((3.0, 0.2, b.unwrap())),
        };
        let ratio = (moved.slip() - bodies.slip()) / (j / reduced);
        assert!((ratio - SLIP_FACTOR).abs() < 1e-12, "{ratio}");
    }
}
