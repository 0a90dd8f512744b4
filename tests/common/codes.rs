//! The canonical impacts as DEM-code setups, built by hand from the numbers of the shipped
//! cases (not through the crate's own `setup_for_case`), so that each driver is checked against
//! an independent reading of the scene.

use std::f64::consts::PI;

use millimpact::codes::{CodeSetup, CodeSphere};
use millimpact::model::count::round_count;
use millimpact::model::scene::SceneKind;

/// Ball radius, m.
pub const RADIUS: f64 = 0.02;
/// Steel density, kg/m³.
pub const DENSITY: f64 = 7800.0;
/// Steel Young's modulus, Pa.
pub const YOUNG: f64 = 2.0e11;
/// Steel Poisson's ratio.
pub const POISSON: f64 = 0.3;
/// Impact speed, m/s.
pub const IMPACT_VELOCITY: f64 = 2.0;
/// Rod diameter, m.
pub const ROD_DIAMETER: f64 = 0.03;
/// Whole rod length, m.
pub const ROD_LENGTH: f64 = 0.5;

/// The COR of the paper's η = 0.35: sqrt((1-η)/(1+η)) = 0.693889.
pub fn e_paper() -> f64 {
    (0.65f64 / 1.35).sqrt()
}

/// One of the canonical impacts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Canonical {
    /// Ball on an elastic steel plate.
    BallPlate,
    /// Ball on a rigid plate.
    BallRigidPlate,
    /// Two equal balls.
    BallBall,
    /// Rod end on a rigid plate.
    RodEnd,
}

impl Canonical {
    /// All four.
    pub const ALL: [Canonical; 4] = [
        Canonical::BallPlate,
        Canonical::BallRigidPlate,
        Canonical::BallBall,
        Canonical::RodEnd,
    ];

    /// The scene it belongs to.
    pub fn scene(self) -> SceneKind {
        match self {
            Canonical::BallPlate | Canonical::BallRigidPlate => SceneKind::BallPlate,
            Canonical::BallBall => SceneKind::BallBall,
            Canonical::RodEnd => SceneKind::RodEnd,
        }
    }

    /// The shipped case file's name.
    pub fn name(self) -> &'static str {
        match self {
            Canonical::BallPlate => "ball_plate",
            Canonical::BallRigidPlate => "ball_plate_rigid",
            Canonical::BallBall => "ball_ball",
            Canonical::RodEnd => "rod_end",
        }
    }
}

/// A 40 mm steel ball.
pub fn steel_ball() -> CodeSphere {
    CodeSphere {
        radius: RADIUS,
        density: DENSITY,
        mass: 4.0 / 3.0 * PI * RADIUS.powi(3) * DENSITY,
        youngs_modulus: YOUNG,
        poisson_ratio: Some(POISSON),
    }
}

/// Hertz's elastic contact time `2.86827 (M² / (R* E*² v0))^(1/5)`, s.
pub fn hertz_contact_time(mass: f64, radius: f64, modulus: f64, velocity: f64) -> f64 {
    2.86827 * (mass * mass / (radius * modulus * modulus * velocity)).powf(0.2)
}

/// The elastic contact time of a setup's spring: Hertz's, or `π sqrt(M/k)` for the rod, s.
pub fn elastic_contact_time(s: &CodeSetup) -> f64 {
    match (s.effective_modulus, s.effective_radius) {
        (Some(modulus), Some(radius)) => {
            hertz_contact_time(s.reduced_mass, radius, modulus, s.impact_velocity)
        }
        _ => PI * (s.reduced_mass / s.stiffness).sqrt(),
    }
}

/// The canonical impact `which` at target COR `e`, stepped at the elastic contact time over
/// `per_contact`, and run for `run_length` elastic contact times.
pub fn code_setup(which: Canonical, e: f64, per_contact: f64, run_length: f64) -> CodeSetup {
    let ball = steel_ball();
    let compliance = (1.0 - POISSON * POISSON) / YOUNG;
    let hertz = |modulus: f64, radius: f64| {
        (
            Some(modulus),
            Some(radius),
            4.0 / 3.0 * modulus * radius.sqrt(),
        )
    };
    let (sphere, other, plate, (modulus, radius, stiffness), mass) = match which {
        Canonical::BallPlate => (
            ball,
            None,
            Some((YOUNG, POISSON)),
            hertz(1.0 / (2.0 * compliance), RADIUS),
            ball.mass,
        ),
        Canonical::BallRigidPlate => (ball, None, None, hertz(1.0 / compliance, RADIUS), ball.mass),
        Canonical::BallBall => (
            ball,
            Some(ball),
            None,
            hertz(1.0 / (2.0 * compliance), RADIUS / 2.0),
            ball.mass / 2.0,
        ),
        Canonical::RodEnd => {
            let area = PI * ROD_DIAMETER * ROD_DIAMETER / 4.0;
            let mass = DENSITY * area * ROD_LENGTH;
            let r = ROD_DIAMETER / 2.0;
            let rod = CodeSphere {
                radius: r,
                density: mass / (4.0 / 3.0 * PI * r.powi(3)),
                mass,
                youngs_modulus: YOUNG,
                poisson_ratio: None,
            };
            let k = area * YOUNG / (ROD_LENGTH / 2.0);
            (rod, None, None, (None, None, k), mass)
        }
    };
    let mut setup = CodeSetup {
        case_name: which.name().to_string(),
        scene: which.scene(),
        sphere,
        other_sphere: other,
        plate_material: plate,
        effective_modulus: modulus,
        effective_radius: radius,
        reduced_mass: mass,
        stiffness,
        exponent: if which == Canonical::RodEnd { 1.0 } else { 1.5 },
        impact_velocity: IMPACT_VELOCITY,
        target_restitution: e,
        loss_coefficient: None,
        timestep: 0.0,
        steps: round_count(run_length * per_contact).expect("a step count"),
        clamp_attractive: false,
        conventions: None,
        oblique: None,
    };
    setup.timestep = elastic_contact_time(&setup) / per_contact;
    setup
}

/// `|a - b| / |b|`.
pub fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The driver's own law stepped the way its code steps, at the setup's step and length.
pub fn stepped_law(
    driver: &dyn millimpact::codes::CodeDriver,
    setup: &CodeSetup,
) -> millimpact::model::trajectory::TrajectoryMetrics {
    let t = millimpact::solve::dashpot::step_trajectory(
        &driver.law(setup),
        setup.impact_velocity,
        setup.timestep,
        setup.steps,
        driver.step_scheme(),
    );
    millimpact::model::trajectory::trajectory_metrics(&t).expect("the stepped law ends its contact")
}
