//! The Kratos Multiphysics DEM driver (PyPI `KratosMultiphysics` and `KratosDEMApplication`
//! 10.4.4, `.codes/kratos/bin/python impact.py`).
//!
//! The scene is built by the Python template `scripts/kratos/impact.py`: a `DEMAnalysisStage`
//! whose model is made in the script (no mdpa or materials file), one sphere moving along an
//! axis towards a second sphere or a wall of two `RigidFace3D3N` triangles, no gravity, no
//! friction and no rotation (but in an oblique impact, below), no global damping, no output
//! files, and the script's own step loop of exactly `setup.steps` steps. It writes one row per
//! step, aligned as YADE's rows.
//!
//! What the installed version really integrates, as measured (see
//! `reference/kratos/CONVENTIONS.md` for the runs and numbers):
//!
//! - Ball scenes: `DEM_D_Hertz_viscous_Coulomb`: `F = k y^1.5 + 2 γ sqrt(1.5 M k) y^0.25 ẏ`,
//!   `k = (4/3) E* sqrt(R*)`, `E*` mixed from both materials (the wall's own `E`, `ν` at a
//!   wall), `R* = R` at a wall, the total normal force clamped at zero. `γ` comes from
//!   `COEFFICIENT_OF_RESTITUTION` through Thornton's fit, with Kratos' cut-offs
//!   ([`hertz_damping_gamma`]): the law YADE builds from its `en`, so the driver gives the same
//!   compensated `en` ([`hertz_input_restitution`](super::damping::hertz_input_restitution)).
//!   `M` is the reduced mass of two balls, the ball's own at a wall; Kratos forms each mass
//!   from density and radius ([`particle_mass`]).
//! - Rod end: `DEM_D_Linear_Custom_Constants` with `K_NORMAL` in the contact's sub-properties
//!   and `DAMPING_GAMMA` set directly: `F = k y + 2 γ sqrt(M k) ẏ`, clamped at zero, `γ` the
//!   damping ratio at which the clamped dashpot realises the target.
//! - Stepping: the default `Symplectic_Euler` scheme is leap-frog (the force of step `n` sees
//!   `x_n` and the velocity `v_{n-1/2}`); `Forward_Euler` gains energy and is not used.
//!
//! - Oblique and spinning impacts at a plate (the script's part from `oblique.py`, rendered
//!   only for them): rotation on, μ as the contact's `STATIC_FRICTION` = `DYNAMIC_FRICTION`,
//!   the ball's `VELOCITY_X` and `ANGULAR_VELOCITY_Y` (the wall's normal is +z, so `ω_y` has
//!   millimpact's sign). The tangential law is the Hertz law's own and fixed: Mindlin's spring
//!   `8 G* sqrt(R* δ)` stepped by increments (the old force scaled by `sqrt(δ/δ_old)` while
//!   unloading), a dashpot `2 γ sqrt(M* k_t)` at the normal `γ`, and spring plus dashpot
//!   bounded by μ times the whole clamped normal force. Spring and dashpot act only while the
//!   contact sticks, so a case's Mindlin law is run where the contact slides throughout and
//!   refused elsewhere, and a linear or proportional spring is refused. The moment arm at a
//!   wall is `R − δ`, so the spin changes by the force-weighted `(R − δ)/R` of a rigid
//!   sphere's change: 2.1e-3 short in the held-out gross-sliding case, 8e-4 in the spin case.
//!
//! Settings without which the answer silently changes, each set by the template and checked by
//! the tests: the integration scheme in the particles' properties (and the properties proxies)
//! before any particle is created (else a segfault, exit 139), `NeighbourSearchFrequency` 1
//! (the default 50 finds the wall contact late), one OpenMP thread ([`Kratos::locate`]), the
//! state paired with the force it produced in each row.

pub(crate) mod batch;
pub(crate) mod card;
pub(crate) mod deck;
mod files;
mod materials;
mod mdpa;
pub mod paper;
mod project;

pub(crate) use paper::KratosPaper;
// The deck reader mixes its materials as the driver does.
pub(crate) use super::setup::mixed_modulus;

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use super::damping::{
    clamped_hertz_law, clamped_linear_law, fit_restitution, hertz_input_or_target,
    refuse_for_clamped_law, rod_damping_ratio, thornton_damping_ratio,
};
use super::deck::TANGENTIAL_LINE;
use super::parse::{ParseError, log_value, parse_csv_columns};
use super::runner::{self, CodesDir};
use super::script_values::{body_values, reported};
use super::setup::CodeOblique;
use super::template::{exact_number, fill_template};
use super::{
    CalibrationCard, CodeDriver, CodeError, CodeSetup, Executable, LocateError, ParsedRun,
    RenderedInput,
};
use crate::model::law::{CodeLaw, DashpotLaw};
use crate::model::scene::{SceneKind, pair_radius};
use crate::model::tangential::{PlaneMotion, SLIP_FACTOR, TangentialSpring};
use crate::model::trajectory::CodeTrajectory;
use crate::solve::dashpot::StepScheme;

/// The Python template of one impact.
const TEMPLATE: &str = include_str!("impact.py");

/// The Python every Kratos script shares (imports, the stage's settings, materials and
/// relations, the wall, the step loop, the rows), written into each rendered script in place of
/// its template's `{{common}}` line, so that the script runs on its own in its scratch folder.
const COMMON: &str = include_str!("common.py");

/// `template` with the shared Python ([`COMMON`]) in place of its `{{common}}` line.
fn with_common(template: &str) -> String {
    template.replacen("{{common}}", COMMON.trim_end(), 1)
}

/// The Python an oblique or spinning impact adds to [`TEMPLATE`], in place of its
/// [`OBLIQUE_LINE`]: the stage with rotation on, μ in the contact's properties, the ball's
/// motion along the wall and its spin, and the line [`TANGENTIAL_LINE`] after the steps.
const OBLIQUE: &str = include_str!("oblique.py");

/// The line of [`TEMPLATE`] that [`OBLIQUE`] replaces; a normal impact drops it whole, so its
/// script is the one rendered before oblique impacts existed, byte for byte.
const OBLIQUE_LINE: &str = "{{oblique}}\n";

/// The name of the rendered script in the scratch directory.
pub(crate) const SCRIPT: &str = "impact.py";

/// The trajectory file the script writes.
pub(crate) const TRAJECTORY_FILE: &str = super::parse::CSV_TRAJECTORY_FILE;

/// The files a run leaves in its scratch directory (besides the harness's `log.txt`): the
/// script and its trajectory; Kratos writes nothing else when its output options are off.
pub const RUN_FILES: [&str; 2] = [SCRIPT, TRAJECTORY_FILE];

/// The script `file` holding `text`, run by the python [`Kratos::locate`] finds.
fn script_input(file: &str, text: String) -> RenderedInput {
    RenderedInput {
        file_name: file.to_string(),
        text,
        args: vec![file.to_string()],
    }
}

/// Parse the script's `trajectory.csv` (header `iter,time,overlap,approach_velocity,normal_force`).
pub(crate) fn parse_trajectory(text: &str) -> Result<CodeTrajectory, ParseError> {
    parse_csv_columns(text, TRAJECTORY_FILE)
}

/// The python of the installed Kratos, under the codes' folder (`find_codes_dir`).
pub const PYTHON: &str = "kratos/bin/python";

/// The translational integration scheme: symplectic Euler, Kratos' leap-frog. `Forward_Euler`
/// (the scheme of Kratos' own restitution test) gains energy: an elastic impact rebounds at
/// 1.0056 with 1000 steps per contact.
pub const SCHEME: &str = "Symplectic_Euler";

/// Young's modulus of the wall that stands for a rigid plate, Pa: Kratos mixes the wall's `E`
/// and `ν` into `E*`; at this value the wall's share of the compliance is below double
/// precision.
pub const RIGID_WALL_MODULUS: f64 = super::setup::RIGID_WALL_MODULUS;

/// Above this restitution Kratos' `GammaForHertzThornton` gives no damping at all.
pub(crate) const UNDAMPED_ABOVE: f64 = 0.999;

/// Below this restitution Kratos' `GammaForHertzThornton` uses this value instead.
pub(crate) const LOWEST_RESTITUTION: f64 = 0.001;

/// The Kratos DEM driver.
pub struct Kratos;

/// The damping ratio `γ` Kratos 10.4.4 derives from `COEFFICIENT_OF_RESTITUTION` for
/// `DEM_D_Hertz_viscous_Coulomb` (`GammaForHertzThornton`): Thornton's fit, zero above
/// `UNDAMPED_ABOVE`, and the fit at `LOWEST_RESTITUTION` below that.
pub fn hertz_damping_gamma(restitution: f64) -> f64 {
    if restitution > UNDAMPED_ABOVE {
        return 0.0;
    }
    thornton_damping_ratio(restitution.max(LOWEST_RESTITUTION))
}

/// `coeff_of_rest_diff` of Kratos 10.4.4's `sphere_strategy.py`: the COR of a clamped linear
/// dashpot of damping ratio `gamma` (the force vanishing ends the contact), less `target`, in
/// its three branches (under-damped below `1/sqrt(2)`, the atan's other branch up to 1, and
/// over-damped), each as Kratos writes it.
// Kratos compares `gamma == 1.0` exactly and returns its rounded constant there.
#[allow(clippy::float_cmp)]
fn linear_restitution_difference(gamma: f64, target: f64) -> f64 {
    use std::f64::consts::PI;
    let e = if gamma <= 1.0 / 2f64.sqrt() {
        let s = (1.0 - gamma * gamma).sqrt();
        (-gamma / s * (PI - (2.0 * gamma * s / (-2.0 * gamma * gamma + 1.0)).atan())).exp()
    } else if gamma < 1.0 {
        let s = (1.0 - gamma * gamma).sqrt();
        (-gamma / s * (2.0 * gamma * s / (2.0 * gamma * gamma - 1.0)).atan()).exp()
    } else if gamma == 1.0 {
        0.135335283
    } else {
        let x = gamma / (gamma * gamma - 1.0).sqrt();
        (-x * ((x + 1.0) / (x - 1.0)).ln()).exp()
    };
    e - target
}

/// The damping ratio `γ` Kratos 10.4.4 derives from `COEFFICIENT_OF_RESTITUTION` for its linear
/// laws (`DEM_D_Linear_viscous_Coulomb`, `DEM_D_Linear_Custom_Constants`: `RootByBisection`):
/// the clamped linear dashpot's closed form solved by bisection on [0, 16] until the bracket is
/// narrower than 1e-4, so `γ` is off by up to 5e-5 and the law's COR misses the entered one by
/// up to a few 1e-5; zero above `UNDAMPED_ABOVE`, the bisection at `LOWEST_RESTITUTION`
/// below it. The same operations in the same order: the bits Kratos logs.
// Kratos' exact comparisons: the bisection's `== 0` exit.
#[allow(clippy::float_cmp)]
pub fn linear_damping_gamma(restitution: f64) -> f64 {
    let target = restitution.max(LOWEST_RESTITUTION);
    if restitution > UNDAMPED_ABOVE {
        return 0.0;
    }
    let (mut a, mut b) = (0.0, 16.0);
    let mut gamma = 0.5 * (a + b);
    let mut k = 0;
    while b - a > 1e-4 && k <= 300 {
        let trial = linear_restitution_difference(gamma, target);
        if linear_restitution_difference(a, target) * trial < 0.0 {
            b = gamma;
        } else if trial == 0.0 {
            return gamma;
        } else {
            a = gamma;
        }
        gamma = 0.5 * (a + b);
        k += 1;
    }
    gamma
}

/// The Kratos python in the codes' folder `codes`, or why there is none: the path looked at,
/// how the folder was chosen, how to install it there, and how to point at another; or, for
/// an environment made on another machine, the Python it links to that is not here.
pub fn python_in(codes: &CodesDir) -> Result<PathBuf, LocateError> {
    let path = codes.path.join(PYTHON);
    let variable = runner::binary_override_variable("kratos");
    if path.is_file() {
        Ok(path)
    } else if let Some(target) = runner::dangling_link(&path) {
        Err(LocateError::MovedEnvironment {
            link: path,
            target,
            variable,
        })
    } else {
        Err(LocateError::NotInstalled {
            expected: PYTHON,
            folder: codes.path.clone(),
            origin: codes.origin,
            variable,
        })
    }
}

/// The python that runs `driver`'s scripts (a build of Kratos): the one in its
/// `MILLIMPACT_<NAME>_BINARY` if set, else the venv's under the codes' folder ([`python_in`]);
/// with one OpenMP thread.
fn locate_python(driver: &dyn CodeDriver) -> Result<Executable, LocateError> {
    let found = runner::locate_override_or_installed(driver, |codes, _| {
        python_in(codes).map(Executable::plain)
    })?;
    Ok(Executable {
        program: found.program,
        env: vec![("OMP_NUM_THREADS", OsString::from("1"))],
    })
}

/// Refuses a run whose script reports other than `asked` steps.
fn check_steps(log: &str, asked: u64) -> Result<(), ParseError> {
    match reported::<u64>(log_value(log, "iterations="), "iterations")? {
        Some(ran) if ran != asked => Err(ParseError::StepCount { ran, asked }),
        _ => Ok(()),
    }
}

/// A sphere's mass as Kratos forms it from density and radius, kg (it may differ from the
/// case's `4/3 π R³ ρ` in the last bit).
pub fn particle_mass(radius: f64, density: f64) -> f64 {
    density * (4.0 / 3.0 * std::f64::consts::PI * radius * radius * radius)
}

/// The mass the dashpot sees, from Kratos' own particle masses.
fn dynamic_mass(setup: &CodeSetup) -> f64 {
    let m1 = particle_mass(setup.sphere.radius, setup.sphere.density);
    match (setup.scene, setup.other_sphere) {
        (SceneKind::BallBall, Some(o)) => {
            let m2 = particle_mass(o.radius, o.density);
            1.0 / (1.0 / m1 + 1.0 / m2)
        }
        _ => m1,
    }
}

/// The Hertz stiffness `(4/3) E* sqrt(R*)` of a ball scene as Kratos' Hertz law forms it: `E*`
/// mixed from both materials ([`CodeSetup::mixed_modulus`]), `R*` the pair's, the ball's own at the flat
/// wall.
fn hertz_stiffness(setup: &CodeSetup) -> f64 {
    let s = setup.sphere;
    let modulus = setup.mixed_modulus();
    let radius = match (setup.scene, setup.other_sphere) {
        (SceneKind::BallBall, Some(o)) => pair_radius(s.radius, o.radius),
        // RigidFace3D3N is flat: the sphere's own radius.
        _ => s.radius,
    };
    4.0 / 3.0 * modulus * radius.sqrt()
}

impl Kratos {
    /// The clamped damped law Kratos integrates for `setup` (linear for the rod).
    pub fn dashpot_law(&self, setup: &CodeSetup) -> DashpotLaw {
        let mass = dynamic_mass(setup);
        match setup.scene {
            SceneKind::RodEnd => {
                clamped_linear_law(mass, setup.stiffness, rod_damping_ratio(setup))
            }
            SceneKind::BallPlate | SceneKind::BallBall => clamped_hertz_law(
                mass,
                hertz_stiffness(setup),
                hertz_damping_gamma(hertz_input_or_target(setup)),
            ),
        }
    }

    /// The values the script template is filled with for `setup` (a batch lists each impact
    /// with the same ones), or why the setup cannot run.
    pub(crate) fn script_values(
        &self,
        setup: &CodeSetup,
    ) -> Result<Vec<(&'static str, String)>, CodeError> {
        refuse_for_clamped_law(self.name(), setup, "DEM_D_Linear_Custom_Constants")?;
        let (restitution, linear_stiffness, damping_gamma) = match setup.scene {
            // The linear law's γ is set directly: Kratos' own bisection from a restitution
            // solves the same clamped closed form, but stops at 1e-4 in γ.
            SceneKind::RodEnd => (1.0, setup.stiffness, rod_damping_ratio(setup)),
            // A negative γ leaves the one Kratos derives from the restitution.
            _ => (hertz_input_or_target(setup), 0.0, -1.0),
        };
        let mut values = body_values(setup);
        values.extend([
            ("restitution", exact_number(restitution)),
            ("linear_stiffness", exact_number(linear_stiffness)),
            ("damping_gamma", exact_number(damping_gamma)),
            ("scheme", SCHEME.to_string()),
        ]);
        Ok(values)
    }
}

/// The slip of an oblique ball-on-plate start, m/s: the ball's surface at the contact, which
/// moves at `v_t − R ω`.
fn plate_slip(setup: &CodeSetup, ball: PlaneMotion) -> f64 {
    ball.tangential_velocity - setup.sphere.radius * ball.angular_velocity
}

/// Why `DEM_D_Hertz_viscous_Coulomb` cannot run the case's tangential law for `setup`, if it
/// cannot. Its tangential half is fixed: Mindlin's stiffness `k_t = 8 G* sqrt(R* δ)`, but its
/// force grows by increments `k_t Δs` while loading (the case's Mindlin spring is `k_t ξ` of
/// the whole elongation, stepped as LIGGGHTS' `tangential history`) and is scaled by
/// `sqrt(δ/δ_old)` while unloading; a dashpot `2 γ sqrt(M* k_t)` at the normal law's damping
/// ratio `γ`; and spring plus dashpot bounded by μ times the whole normal force, clamped at
/// zero, as the case's law bounds it. The spring and the dashpot act only while the contact
/// sticks: a contact that slides throughout (the rigid-body condition
/// `|s0| ≥ (7/2) μ (1+e) v_n`, at the case's COR) has Kratos' force at the bound, μ F_n, at
/// every step whatever its spring and dashpot, so a Mindlin case is run there and refused
/// elsewhere; a linear or proportional spring is not Kratos' and is refused.
fn tangential_law_refusal(setup: &CodeSetup, oblique: &CodeOblique) -> Option<String> {
    let offered = "DEM_D_Hertz_viscous_Coulomb's tangential spring is Mindlin's \
                   k_t = 8 G* sqrt(R* δ) (spring = \"mindlin\"), stepped by increments, with a \
                   dashpot at the normal damping ratio";
    match oblique.law.spring {
        TangentialSpring::Mindlin => {}
        TangentialSpring::Linear { stiffness } => {
            return Some(format!(
                "tangential spring \"linear\" (k_t = {stiffness} N/m): {offered}"
            ));
        }
        TangentialSpring::Proportional { ratio } => {
            return Some(format!(
                "tangential spring \"proportional\" (stiffness_ratio = {ratio}): {offered}"
            ));
        }
    }
    let slip = plate_slip(setup, oblique.ball).abs();
    let bound = SLIP_FACTOR
        * oblique.friction_coefficient
        * (1.0 + setup.target_restitution)
        * setup.impact_velocity;
    (slip < bound).then(|| {
        let gamma = hertz_damping_gamma(hertz_input_or_target(setup));
        format!(
            "the Mindlin spring in a contact that sticks (slip {slip} m/s below \
             (7/2) μ (1+e) v_n = {bound} m/s): {offered} (γ = {gamma} here), both of which act \
             while the contact sticks, so Kratos runs the Mindlin law only in gross sliding"
        )
    })
}

/// A script's values: each placeholder's name and its text.
type ScriptValues = Vec<(&'static str, String)>;

/// The Python an oblique `setup` adds to the script and the values it is filled with, or why
/// Kratos cannot run it; nothing for a normal impact.
fn oblique_section(
    code: &str,
    setup: &CodeSetup,
) -> Result<(&'static str, ScriptValues), CodeError> {
    let Some(oblique) = setup.oblique else {
        return Ok(("", Vec::new()));
    };
    if setup.scene != SceneKind::BallPlate || oblique.partner.is_some() {
        return Err(setup.unsupported(
            code,
            format!(
                "an oblique impact in scene \"{}\": the Kratos driver renders one at a plate only",
                setup.scene.name()
            ),
        ));
    }
    if let Some(reason) = tangential_law_refusal(setup, &oblique) {
        return Err(setup.unsupported(code, reason));
    }
    // The ball meets the wall 2 R inside its nearest edge (the script's L = 4 R): a run that
    // carries it a radius along the wall would bring the edge near the contact.
    let travel = oblique.ball.tangential_velocity.abs() * setup.timestep * (setup.steps as f64);
    if travel >= setup.sphere.radius {
        return Err(setup.unsupported(
            code,
            format!(
                "tangential_velocity = {} m/s carries the ball {travel} m along the wall in the \
                 run, more than its radius {} m: the Kratos wall is 2 R wide of the contact",
                oblique.ball.tangential_velocity, setup.sphere.radius
            ),
        ));
    }
    Ok((
        OBLIQUE,
        vec![
            (
                "tangential_velocity",
                exact_number(oblique.ball.tangential_velocity),
            ),
            (
                "angular_velocity",
                exact_number(oblique.ball.angular_velocity),
            ),
            ("friction", exact_number(oblique.friction_coefficient)),
            ("tangential_line", TANGENTIAL_LINE.to_string()),
        ],
    ))
}

impl CodeDriver for Kratos {
    fn card(&self) -> Option<&dyn CalibrationCard> {
        Some(&card::KratosCard)
    }

    fn deck(&self) -> Option<&dyn super::deck::DeckReader> {
        Some(&deck::KratosDeck)
    }

    fn name(&self) -> &'static str {
        "kratos"
    }

    fn binary(&self) -> &'static str {
        "python"
    }

    /// The venv's python under the codes' folder (or the python in `MILLIMPACT_KRATOS_BINARY`),
    /// with `OMP_NUM_THREADS=1`: Kratos' default of two OpenMP threads makes a one-sphere
    /// run's loop five to ten times slower.
    fn locate(&self) -> Result<Executable, LocateError> {
        locate_python(self)
    }

    fn runs_oblique(&self) -> bool {
        true
    }

    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        let mut values = self.script_values(setup)?;
        let (section, oblique_values) = oblique_section(self.name(), setup)?;
        values.extend(oblique_values);
        let template = with_common(TEMPLATE).replacen(OBLIQUE_LINE, section, 1);
        let text = fill_template(&template, &values)
            .map_err(|reason| setup.unsupported(self.name(), reason.to_string()))?;
        Ok(script_input(SCRIPT, text))
    }

    fn parse(&self, setup: &CodeSetup, workdir: &Path, log: &str) -> Result<ParsedRun, ParseError> {
        let text = super::parse::read_output(workdir.join(TRAJECTORY_FILE))?;
        check_steps(log, setup.steps)?;
        Ok(ParsedRun {
            trajectory: parse_trajectory(&text)?,
            loop_time: reported(log_value(log, "loop_time="), "loop_time")?,
            version: log_value(log, "version=").map(str::to_string),
        })
    }

    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        self.dashpot_law(setup).into()
    }

    fn step_scheme(&self) -> StepScheme {
        StepScheme::LeapFrog
    }

    fn batch(&self) -> Option<&dyn super::BatchRunner> {
        Some(&batch::KRATOS_BATCH)
    }

    fn expected_restitution(&self, setup: &CodeSetup) -> Option<f64> {
        fit_restitution(setup, &self.dashpot_law(setup))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::CodeSphere;
    use crate::codes::damping::hertz_input_restitution;

    /// The recorded run in `tests/data/kratos`: a steel ball on a steel plate, target 0.6944,
    /// 40 steps per elastic contact time, 50 steps.
    const SAMPLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/kratos");
    const LOG: &str = include_str!("../../../tests/data/kratos/log.txt");

    /// Each template takes the shared Python once, whole, and the shared Python has no
    /// placeholder a script's values could fill.
    #[test]
    fn every_script_carries_the_shared_python_once() {
        assert!(!COMMON.contains("{{"));
        for template in [TEMPLATE, deck::TEMPLATE, batch::SCRIPT] {
            assert_eq!(template.matches("{{common}}").count(), 1);
            let whole = with_common(template);
            assert_eq!(whole.matches(COMMON.trim_end()).count(), 1);
            assert!(!whole.contains("{{common}}"));
        }
    }

    fn sample_setup() -> CodeSetup {
        let ball = CodeSphere {
            radius: 0.02,
            density: 7800.0,
            mass: 4.0 / 3.0 * std::f64::consts::PI * 0.02f64.powi(3) * 7800.0,
            youngs_modulus: 2e11,
            poisson_ratio: Some(0.3),
        };
        CodeSetup {
            case_name: "sample".into(),
            scene: SceneKind::BallPlate,
            sphere: ball,
            other_sphere: None,
            plate_material: Some((2e11, 0.3)),
            effective_modulus: None,
            effective_radius: None,
            reduced_mass: ball.mass,
            stiffness: 0.0,
            exponent: 1.5,
            impact_velocity: 2.0,
            target_restitution: 0.6944,
            loss_coefficient: None,
            timestep: 3.059_664_992_222_593_2e-6,
            steps: 50,
            clamp_attractive: false,
            conventions: None,
            oblique: None,
        }
    }

    // The sample's rows are written with %r: t = 0 and v = v0 exactly.
    #[allow(clippy::float_cmp)]
    #[test]
    fn parses_the_recorded_run() {
        let parsed = Kratos
            .parse(&sample_setup(), Path::new(SAMPLE), LOG)
            .unwrap();
        assert_eq!(parsed.version.as_deref(), Some("10.4.4"));
        assert!(parsed.loop_time.is_some_and(|t| t > 0.0 && t < 1.0));
        let t = &parsed.trajectory;
        assert_eq!(t.time.len(), 51);
        assert_eq!((t.time[0], t.approach_velocity[0]), (0.0, 2.0));
        // One ulp of gap at t = 0, no force.
        assert!(t.overlap[0] <= 0.0 && t.overlap[0] > -1e-17);
        assert_eq!(t.normal_force[0], 0.0);
        // Contact from the first step on, and out of contact at the end.
        assert!(t.overlap[1] > 0.0 && t.normal_force[1] > 0.0);
        assert!(*t.overlap.last().unwrap() < 0.0);
        assert_eq!(*t.normal_force.last().unwrap(), 0.0);
    }

    #[test]
    fn a_run_of_another_length_is_refused() {
        let mut s = sample_setup();
        s.steps = 49;
        match Kratos.parse(&s, Path::new(SAMPLE), LOG) {
            Err(ParseError::StepCount { ran: 50, asked: 49 }) => {}
            other => panic!("{other:?}"),
        }
        let bad = LOG.replace("iterations=50", "iterations=fifty");
        assert!(matches!(
            Kratos.parse(&sample_setup(), Path::new(SAMPLE), &bad),
            Err(ParseError::BadValue {
                field: "iterations",
                ..
            })
        ));
        let bad = LOG.replace("loop_time=", "loop_time=x");
        assert!(matches!(
            Kratos.parse(&sample_setup(), Path::new(SAMPLE), &bad),
            Err(ParseError::BadValue {
                field: "loop_time",
                ..
            })
        ));
    }

    #[test]
    fn a_run_without_its_trajectory_is_refused() {
        let empty = tempfile::tempdir().unwrap();
        let err = Kratos
            .parse(&sample_setup(), empty.path(), LOG)
            .unwrap_err();
        assert!(matches!(err, ParseError::Read { .. }), "{err}");
        assert!(err.to_string().contains(TRAJECTORY_FILE), "{err}");
        std::fs::write(empty.path().join(TRAJECTORY_FILE), "").unwrap();
        assert!(matches!(
            Kratos.parse(&sample_setup(), empty.path(), LOG),
            Err(ParseError::Empty { .. })
        ));
    }

    #[test]
    fn a_missing_install_says_where_it_looked_and_how_to_install() {
        let empty = tempfile::tempdir().unwrap();
        let codes = CodesDir {
            path: empty.path().to_path_buf(),
            origin: runner::CodesDirOrigin::Variable,
        };
        let err = python_in(&codes).unwrap_err().to_string();
        assert!(err.contains(&empty.path().join(PYTHON).display().to_string()));
        assert!(err.contains("named by MILLIMPACT_CODES_DIR"), "{err}");
        assert!(err.contains("scripts/install-dem-codes.sh"), "{err}");
        std::fs::create_dir_all(empty.path().join("kratos/bin")).unwrap();
        // A venv made on another machine: its python links to a Python that is not here.
        let elsewhere = empty.path().join("gone/bin/python3");
        std::os::unix::fs::symlink(&elsewhere, empty.path().join(PYTHON)).unwrap();
        let err = python_in(&codes).unwrap_err().to_string();
        assert!(
            err.starts_with(&format!(
                "{} links to {}, which is not on this machine",
                empty.path().join(PYTHON).display(),
                elsewhere.display()
            )),
            "{err}"
        );
        assert!(err.contains("bash scripts/install-dem-codes.sh"), "{err}");
        std::fs::remove_file(empty.path().join(PYTHON)).unwrap();
        std::fs::write(empty.path().join(PYTHON), "").unwrap();
        assert_eq!(python_in(&codes).unwrap(), empty.path().join(PYTHON));
    }

    // Kratos' cut-offs are exact comparisons in its source.
    #[allow(clippy::float_cmp)]
    #[test]
    fn kratos_gamma_cut_offs() {
        assert_eq!(hertz_damping_gamma(1.0), 0.0);
        assert_eq!(hertz_damping_gamma(0.9995), 0.0);
        assert_eq!(hertz_damping_gamma(0.999), thornton_damping_ratio(0.999));
        assert_eq!(hertz_damping_gamma(0.0), thornton_damping_ratio(0.001));
        // What 10.4.4 logged as DAMPING_GAMMA for COEFFICIENT_OF_RESTITUTION = the sample's en.
        let logged: f64 = log_value(LOG, "damping_gamma=").unwrap().parse().unwrap();
        let en = hertz_input_restitution(0.6944).unwrap();
        assert_eq!(hertz_damping_gamma(en), logged);
        // And the masses it formed from density and radius.
        let mass: f64 = LOG
            .lines()
            .find_map(|l| l.strip_prefix("MILLIMPACT particle id=1 mass="))
            .and_then(|rest| rest.split_whitespace().next())
            .unwrap()
            .parse()
            .unwrap();
        assert_eq!(mass, particle_mass(0.02, 7800.0));
    }
}
