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

use std::f64::consts::PI;
use std::path::Path;

use super::parse::ParseError;
use super::template::{exact_number, fill_template};
use super::{CodeDriver, CodeError, CodeSetup, ParsedRun, RenderedInput};
use crate::model::law::DashpotLaw;
use crate::model::scene::{SceneKind, pair_radius};
use crate::model::trajectory::CodeTrajectory;
use crate::solve::dashpot::{StepScheme, accurate_metrics};

/// The Python template of one impact.
const TEMPLATE: &str = include_str!("../../scripts/yade/impact.py");

/// The name of the rendered script in the scratch directory.
const SCRIPT: &str = "impact.py";

/// The trajectory file the script writes.
pub const TRAJECTORY_FILE: &str = "trajectory.csv";

/// Young's modulus given to the wall that stands for a rigid plate, Pa. YADE mixes the wall's
/// material into `E*`; at this value the wall's share of the compliance, about
/// `(1-ν²)E_ball / E_wall ≈ 1e-19` for steel, is below double precision.
pub const RIGID_WALL_MODULUS: f64 = 1e30;

/// The radius `Ig2_Wall_Sphere_ScGeom(hertzian=True)` gives the wall, in sphere radii.
pub const HERTZIAN_WALL_RADIUS_FACTOR: f64 = 1e8;

/// How far the COR of [`CodeDriver::law`] may lie from the target before
/// [`CodeDriver::expected_restitution`] reports it: Thornton's fit is good to a few 1e-4 for
/// `e ≤ 0.9` and fails towards `e → 1`.
pub const RESTITUTION_FIT_TOLERANCE: f64 = 1e-3;

/// The YADE driver.
pub struct Yade;

/// The damping ratio `β_n` YADE 2023.02a derives from a restitution coefficient `e` for the
/// Hertz–Mindlin law: Thornton, Cummins & Cleary, Powder Technol. 233 (2013) 30–46, Eq. (B6)
/// `β = sqrt(1 / (1 - (1+e)² exp(α)) - 1)` with the polynomial fit (B7)
/// `α = Σ h_i e^i` of their Table 2. `e = 1` gives exactly zero.
// `e = 1` is compared exactly: it is the one input YADE special-cases (the fit does not vanish).
#[allow(clippy::float_cmp)]
pub fn thornton_damping_ratio(restitution: f64) -> f64 {
    const H: [f64; 10] = [
        -6.918798, -16.41105, 146.8049, -796.4559, 2928.711, -7206.864, 11494.29, -11342.18,
        6276.757, -1489.915,
    ];
    if restitution == 1.0 {
        return 0.0;
    }
    let e = restitution;
    let alpha = H.iter().rev().fold(0.0, |acc, h| e * (h + acc));
    (1.0 / (1.0 - (1.0 + e).powi(2) * alpha.exp()) - 1.0).sqrt()
}

/// The Hertz–Mindlin law YADE builds from `en`, reduced to its dimensionless COR: clamped
/// damped Hertz with `c = 2 β_n(en) sqrt(1.5 M k)`. The COR depends on `en` alone.
fn hertz_mindlin_cor(en: f64) -> f64 {
    let beta = thornton_damping_ratio(en);
    let unit = DashpotLaw {
        mass: 1.0,
        stiffness: 1.0,
        exponent: 1.5,
        damping: 2.0 * beta * 1.5f64.sqrt(),
        damping_exponent: 0.25,
        clamp_attractive: true,
    };
    accurate_metrics(&unit, 1.0, 1e-13).map_or(f64::NAN, |m| m.cor)
}

/// The `en` to give `Ip2_FrictMat_FrictMat_MindlinPhys` so that the law YADE builds from it
/// realises the restitution `target`: Thornton's fit alone misses by up to 3.3e-4 for
/// `e <= 0.9` and by 1.1e-2 at 0.99, so the driver inverts the fit through the clamped law
/// (bisection; the realised COR rises monotonically with `en`). The fit does not reach zero
/// damping as `en → 1` (β_n² tends to 2.06e-5, not 0; only `en = 1` itself gives 0), so
/// restitutions between about 0.979 and 1 cannot be realised: `None` for them, and for any
/// other target no `en` in (0, 1] reaches.
// A target of exactly 1 is passed through exactly, as YADE's own `en = 1` special case.
#[allow(clippy::float_cmp)]
pub fn hertz_input_restitution(target: f64) -> Option<f64> {
    // Each inversion integrates the law some sixty times, and a run asks for it several times
    // (sizing, input, law, expected COR): remembered by target, a pure function's results.
    type Memo = std::sync::Mutex<std::collections::HashMap<u64, Option<f64>>>;
    static MEMO: std::sync::OnceLock<Memo> = std::sync::OnceLock::new();
    let memo = MEMO.get_or_init(Default::default);
    if let Some(&known) = memo.lock().ok().and_then(|m| m.get(&target.to_bits()).copied()).as_ref() {
        return known;
    }
    let found = invert_hertz_fit(target);
    if let Ok(mut m) = memo.lock() {
        if m.len() >= 100_000 {
            m.clear();
        }
        m.insert(target.to_bits(), found);
    }
    found
}

fn invert_hertz_fit(target: f64) -> Option<f64> {
    if !(target > 0.0 && target <= 1.0) {
        return None;
    }
    if target >= 1.0 {
        return Some(1.0);
    }
    let (mut lo, mut hi) = (1e-6, 1.0 - 1e-12);
    if hertz_mindlin_cor(lo) > target || hertz_mindlin_cor(hi) < target {
        return None;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if hertz_mindlin_cor(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The damping ratio `ζ = c / (2 sqrt(M k))` at which a linear spring–dashpot whose force is
/// clamped at zero (it never attracts) rebounds with restitution `e`, or `None` below the
/// smallest COR an underdamped clamped dashpot reaches (`e^-2`).
///
/// The force `k y + c ẏ` of the damped oscillation from `y = 0`, `ẏ = v0` first vanishes at
/// `ω t* = π - 2 atan(x)`, `x = ζ / sqrt(1 - ζ²)`, where the speed is `v0 exp(-β t*)`; the body
/// then leaves at that speed, so `-ln e = x (π - 2 atan x)`, which rises monotonically from 0
/// to 2 as `x` goes from 0 to infinity.
pub fn clamped_linear_damping_ratio(restitution: f64) -> Option<f64> {
    if !(restitution > 0.0 && restitution <= 1.0) {
        return None;
    }
    let target = -restitution.ln();
    let g = |x: f64| x * (PI - 2.0 * x.atan());
    if target >= 2.0 {
        return None;
    }
    if target == 0.0 {
        return Some(0.0);
    }
    let mut hi = 1.0;
    while g(hi) < target {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let x = 0.5 * (lo + hi);
    Some(x / (1.0 + x * x).sqrt())
}

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

impl CodeDriver for Yade {
    fn name(&self) -> &'static str {
        "yade"
    }

    fn binary(&self) -> &'static str {
        "yade"
    }

    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
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
                let law = self.law(setup);
                (law.stiffness, law.damping)
            }
            _ => (0.0, 0.0),
        };
        let num = exact_number;
        let values = [
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
            (
                "restitution",
                num(hertz_input_restitution(setup.target_restitution)
                    .unwrap_or(setup.target_restitution)),
            ),
            ("linear_stiffness", num(linear_stiffness)),
            ("linear_damping", num(linear_damping)),
        ];
        let text =
            fill_template(TEMPLATE, &values)
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

    fn render_batch(&self, setups: &[CodeSetup]) -> Result<RenderedInput, String> {
        super::yade_batch::render_batch(setups)
    }

    fn max_batch(&self) -> usize {
        super::yade_batch::MAX_BATCH
    }

    fn parse_batch(
        &self,
        setups: &[CodeSetup],
        workdir: &Path,
        log: &str,
    ) -> Vec<Result<ParsedRun, ParseError>> {
        super::yade_batch::parse_batch(setups, workdir, log)
    }

    fn law(&self, setup: &CodeSetup) -> DashpotLaw {
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

    fn step_scheme(&self) -> StepScheme {
        StepScheme::LeapFrog
    }

    fn expected_restitution(&self, setup: &CodeSetup) -> Option<f64> {
        if setup.scene == SceneKind::RodEnd {
            // The damping is solved for the clamped law: it realises the target.
            return None;
        }
        let law = self.law(setup);
        let cor = accurate_metrics(&law, setup.impact_velocity, 1e-10)
            .ok()?
            .cor;
        ((cor - setup.target_restitution).abs() > RESTITUTION_FIT_TOLERANCE).then_some(cor)
    }
}

/// The value after `key` on the script's `MILLIMPACT` lines, up to the next blank.
fn log_value<'a>(log: &'a str, key: &str) -> Option<&'a str> {
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
            fields[i]
                .parse::<f64>()
                .map_err(|e| ParseError::Row {
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
