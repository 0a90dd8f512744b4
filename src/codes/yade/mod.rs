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
//! - Stepping: leap-frog; the force of iteration `i` sees the position `x_i` and the half-step
//!   velocity `v_{i-1/2}`; the initial velocity is `v_{-1/2}`.

pub(crate) mod batch;
pub(crate) mod card;
pub mod deck;
pub(crate) mod dump;
pub mod paper;

pub(crate) use paper::YadePaper;

use std::path::Path;

pub use super::damping::{
    clamped_linear_damping_ratio, hertz_input_restitution, thornton_damping_ratio,
};
use super::parse::ParseError;
use super::template::{exact_number, fill_template};
use super::{
    BatchRunner, CalibrationCard, CodeDriver, CodeError, CodeSetup, ParsedRun, RenderedInput,
};
use crate::model::law::{CodeLaw, DashpotLaw};
use crate::model::scene::{SceneKind, pair_radius};
use crate::model::trajectory::CodeTrajectory;
use crate::solve::dashpot::{StepScheme, accurate_metrics};

/// The Python template of one impact.
const TEMPLATE: &str = include_str!("impact.py");

/// The name of the rendered script in the scratch directory.
const SCRIPT: &str = "impact.py";

/// The trajectory file the script writes.
pub(crate) const TRAJECTORY_FILE: &str = "trajectory.csv";

/// Young's modulus given to the wall that stands for a rigid plate, Pa. YADE mixes the wall's
/// material into `E*`; at this value the wall's share of the compliance, about
/// `(1-ν²)E_ball / E_wall ≈ 1e-19` for steel, is below double precision.
pub const RIGID_WALL_MODULUS: f64 = 1e30;

/// The radius `Ig2_Wall_Sphere_ScGeom(hertzian=True)` gives the wall, in sphere radii.
pub(crate) const HERTZIAN_WALL_RADIUS_FACTOR: f64 = 1e8;

/// How far the COR of [`CodeDriver::law`] may lie from the target before
/// [`CodeDriver::expected_restitution`] reports it: Thornton's fit is good to a few 1e-4 for
/// `e ≤ 0.9` and fails towards `e → 1`.
pub(crate) const RESTITUTION_FIT_TOLERANCE: f64 = 1e-3;

/// The YADE driver.
pub struct Yade;

/// `E*` as `Ip2_FrictMat_FrictMat_MindlinPhys` forms it from two materials.
fn mixed_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    e1 * e2 / ((1.0 - nu1 * nu1) * e2 + (1.0 - nu2 * nu2) * e1)
}

/// The second body's material `(E, ν)` in the ball scenes: the other ball, the plate, or the
/// stand-in for a rigid plate.
fn second_material(setup: &CodeSetup) -> (f64, f64) {
    match (setup.scene, setup.other_sphere, setup.plate_material) {
        (SceneKind::BallBall, Some(other), _) => {
            (other.youngs_modulus, other.poisson_ratio.unwrap_or(0.0))
        }
        (_, _, Some(plate)) => plate,
        _ => (RIGID_WALL_MODULUS, 0.0),
    }
}

/// Effective modulus and radius YADE uses for a ball scene.
fn hertz_parameters(setup: &CodeSetup) -> (f64, f64) {
    let s = setup.sphere;
    let (e2, nu2) = second_material(setup);
    let modulus = mixed_modulus(s.youngs_modulus, s.poisson_ratio.unwrap_or(0.0), e2, nu2);
    let r1 = s.radius;
    let r2 = match (setup.scene, setup.other_sphere) {
        (SceneKind::BallBall, Some(other)) => other.radius,
        _ => HERTZIAN_WALL_RADIUS_FACTOR * r1,
    };
    (modulus, pair_radius(r1, r2))
}

/// The mass the dashpot sees: the reduced mass of two balls, the moving body's at a wall.
fn dynamic_mass(setup: &CodeSetup) -> f64 {
    setup.pair_mass()
}

impl Yade {
    fn unsupported(&self, setup: &CodeSetup, reason: impl Into<String>) -> CodeError {
        CodeError::Unsupported {
            code: self.name().into(),
            case: setup.case_name.clone(),
            reason: reason.into(),
        }
    }

    fn check(&self, setup: &CodeSetup) -> Result<(), CodeError> {
        let e = setup.target_restitution;
        if !(e > 0.0 && e <= 1.0) {
            return Err(self.unsupported(setup, format!("restitution {e} outside (0, 1]")));
        }
        if !(setup.timestep > 0.0 && setup.timestep.is_finite()) || setup.steps == 0 {
            return Err(self.unsupported(setup, "time step and step count must be positive"));
        }
        match setup.scene {
            SceneKind::BallBall if setup.other_sphere.is_none() => {
                Err(self.unsupported(setup, "ball_ball needs a second sphere"))
            }
            SceneKind::RodEnd if clamped_linear_damping_ratio(e).is_none() => Err(self
                .unsupported(
                    setup,
                    format!(
                        "ViscElPhys clamps its force, and an underdamped clamped linear dashpot \
                         cannot rebound with e = {e} < exp(-2)"
                    ),
                )),
            _ => Ok(()),
        }
    }
}

impl Yade {
    /// The clamped damped law YADE integrates for `setup` (linear for the rod).
    pub fn dashpot_law(&self, setup: &CodeSetup) -> DashpotLaw {
        let mass = dynamic_mass(setup);
        match setup.scene {
            SceneKind::RodEnd => {
                // Only reachable for a restitution `render` refuses; saturate rather than fail.
                let zeta = clamped_linear_damping_ratio(setup.target_restitution).unwrap_or(1.0);
                DashpotLaw {
                    mass,
                    stiffness: setup.stiffness,
                    exponent: 1.0,
                    damping: 2.0 * zeta * (mass * setup.stiffness).sqrt(),
                    damping_exponent: 0.0,
                    clamp_attractive: true,
                }
            }
            SceneKind::BallPlate | SceneKind::BallBall => {
                let (modulus, radius) = hertz_parameters(setup);
                let stiffness = 4.0 / 3.0 * modulus * radius.sqrt();
                let en = hertz_input_restitution(setup.target_restitution)
                    .unwrap_or(setup.target_restitution);
                let beta = thornton_damping_ratio(en);
                DashpotLaw {
                    mass,
                    stiffness,
                    exponent: 1.5,
                    // β_n times the critical damping of the tangent stiffness 1.5 k y^0.5.
                    damping: 2.0 * beta * (1.5 * mass * stiffness).sqrt(),
                    damping_exponent: 0.25,
                    clamp_attractive: true,
                }
            }
        }
    }

    /// The `en` the script gives `Ip2_FrictMat_FrictMat_MindlinPhys` (Thornton's fit inverted
    /// through the clamped law: some sixty integrations of it, the first time for a target).
    pub(crate) fn input_restitution(setup: &CodeSetup) -> f64 {
        hertz_input_restitution(setup.target_restitution).unwrap_or(setup.target_restitution)
    }

    /// The values the script template is filled with for `setup` but its `en`
    /// ([`Yade::input_restitution`], which the template takes in every scene and only the ball
    /// scenes use; a batch lists each impact with these, and its `en` for a ball scene), or why
    /// the setup cannot run.
    pub(crate) fn script_values(
        &self,
        setup: &CodeSetup,
    ) -> Result<Vec<(&'static str, String)>, CodeError> {
        self.check(setup)?;
        let s = setup.sphere;
        let (v1, v2) = setup.centre_of_mass_velocities();
        let (wall_young, wall_poisson) = match setup.scene {
            SceneKind::BallBall => (0.0, 0.0),
            _ => second_material(setup),
        };
        let other = setup
            .other_sphere
            .filter(|_| setup.scene == SceneKind::BallBall);
        let (linear_stiffness, linear_damping) = match setup.scene {
            SceneKind::RodEnd => {
                let law = self.dashpot_law(setup);
                (law.stiffness, law.damping)
            }
            _ => (0.0, 0.0),
        };
        let num = exact_number;
        Ok(vec![
            ("scene", setup.scene.name().to_string()),
            ("timestep", num(setup.timestep)),
            ("steps", setup.steps.to_string()),
            ("radius", num(s.radius)),
            ("mass", num(s.mass)),
            ("density", num(s.density)),
            ("young", num(s.youngs_modulus)),
            ("poisson", num(s.poisson_ratio.unwrap_or(0.0))),
            ("velocity", num(v1)),
            ("other_radius", num(other.map_or(0.0, |o| o.radius))),
            ("other_mass", num(other.map_or(0.0, |o| o.mass))),
            ("other_density", num(other.map_or(0.0, |o| o.density))),
            ("other_young", num(other.map_or(0.0, |o| o.youngs_modulus))),
            (
                "other_poisson",
                num(other.and_then(|o| o.poisson_ratio).unwrap_or(0.0)),
            ),
            ("other_velocity", num(v2)),
            ("wall_young", num(wall_young)),
            ("wall_poisson", num(wall_poisson)),
            ("linear_stiffness", num(linear_stiffness)),
            ("linear_damping", num(linear_damping)),
        ])
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
            .map_err(|reason| self.unsupported(setup, reason.to_string()))?;
        Ok(RenderedInput {
            file_name: SCRIPT.to_string(),
            text,
            args: ["-j1", "-n", "-x", SCRIPT].map(String::from).to_vec(),
        })
    }

    fn parse(
        &self,
        _setup: &CodeSetup,
        workdir: &Path,
        log: &str,
    ) -> Result<ParsedRun, ParseError> {
        let path = workdir.join(TRAJECTORY_FILE);
        let text =
            std::fs::read_to_string(&path).map_err(|source| ParseError::Read { path, source })?;
        Ok(ParsedRun {
            trajectory: parse_trajectory(&text)?,
            loop_time: log_value(log, "loop_time=")
                .map(|v| {
                    v.parse::<f64>().map_err(|_| ParseError::BadValue {
                        field: "loop_time",
                        value: v.to_string(),
                    })
                })
                .transpose()?,
            version: log_value(log, "version=").map(str::to_string).or_else(|| {
                log.lines()
                    .find_map(|l| l.trim().strip_prefix("Welcome to Yade "))
                    .map(|v| v.trim().to_string())
            }),
        })
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
        if setup.scene == SceneKind::RodEnd {
            // The damping is solved for the clamped law: it realises the target.
            return None;
        }
        let law = self.dashpot_law(setup);
        let cor = accurate_metrics(&law, setup.impact_velocity, 1e-10)
            .ok()?
            .cor;
        ((cor - setup.target_restitution).abs() > RESTITUTION_FIT_TOLERANCE).then_some(cor)
    }
}

/// The value after `key` on the script's `MILLIMPACT` lines, up to the next blank.
pub(super) fn log_value<'a>(log: &'a str, key: &str) -> Option<&'a str> {
    log.lines()
        .filter_map(|l| l.trim().strip_prefix("MILLIMPACT "))
        .flat_map(|rest| rest.split_whitespace())
        .find_map(|field| field.strip_prefix(key))
}

/// Parse the script's `trajectory.csv`: header `iter,time,overlap,approach_velocity,normal_force`.
pub fn parse_trajectory(text: &str) -> Result<CodeTrajectory, ParseError> {
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header = lines.next().ok_or_else(|| ParseError::Empty {
        file: TRAJECTORY_FILE.to_string(),
    })?;
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |name: &'static str| {
        columns
            .iter()
            .position(|c| *c == name)
            .ok_or_else(|| ParseError::MissingColumn {
                file: TRAJECTORY_FILE.to_string(),
                column: name,
                header: header.to_string(),
            })
    };
    let (it, iy, iv, iff) = (
        find("time")?,
        find("overlap")?,
        find("approach_velocity")?,
        find("normal_force")?,
    );
    let mut t = CodeTrajectory::default();
    for (row, line) in lines.enumerate() {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != columns.len() {
            return Err(ParseError::Row {
                file: TRAJECTORY_FILE.to_string(),
                line: row + 2,
                reason: format!("{} fields, header has {}", fields.len(), columns.len()),
            });
        }
        let value = |i: usize| {
            fields[i].parse::<f64>().map_err(|e| ParseError::Row {
                file: TRAJECTORY_FILE.to_string(),
                line: row + 2,
                reason: format!("`{}`: {e}", fields[i]),
            })
        };
        t.time.push(value(it)?);
        t.overlap.push(value(iy)?);
        t.approach_velocity.push(value(iv)?);
        t.normal_force.push(value(iff)?);
    }
    Ok(t)
}
