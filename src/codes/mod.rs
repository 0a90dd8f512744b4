//! Drivers for the reference DEM codes: render an input deck for one impact, run the installed
//! code in a scratch directory under a time limit, and parse its trajectory.
//!
//! Every driver implements [`CodeDriver`]; [`run_code`] does the part they share (scratch
//! directory, time limit, log capture, error reporting), and [`trajectory_metrics`] turns any
//! code's trajectory into the same figures the solver reports.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::case::Case;
use crate::exact;
use crate::law::DashpotLaw;
use crate::scene::{Ball, Plate, Scene, SceneKind};
use crate::solve::SolveError;
use crate::solve::dashpot::{StepScheme, accurate_metrics};

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
}

impl CodeSetup {
    /// Velocities `(v1, v2)` along the line of centres, m/s, of the two bodies in the
    /// centre-of-mass frame (body 1 moves towards body 2 with positive speed). For a plate the
    /// second body is at rest and `v1 = impact_velocity`.
    pub fn centre_of_mass_velocities(&self) -> (f64, f64) {
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
    pub fn pair_radius(&self) -> f64 {
        let r1 = self.sphere.radius;
        match self.other_sphere {
            Some(o) => r1 * o.radius / (r1 + o.radius),
            None => r1,
        }
    }

    /// The mass of the relative motion, kg: the sphere's own at a wall (the wall does not
    /// move), `m1 m2 / (m1 + m2)` between two spheres, from the given masses.
    pub fn pair_mass(&self) -> f64 {
        let m1 = self.sphere.mass;
        match self.other_sphere {
            Some(o) => m1 * o.mass / (m1 + o.mass),
            None => m1,
        }
    }

    /// Simulated duration, s.
    pub fn duration(&self) -> f64 {
        self.timestep * self.steps as f64
    }
}

/// A trajectory read back from a code: one row per written step.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CodeTrajectory {
    /// Time, s.
    pub time: Vec<f64>,
    /// Overlap (approach of the centres), m, positive in contact.
    pub overlap: Vec<f64>,
    /// Relative normal velocity, m/s, positive while approaching.
    pub approach_velocity: Vec<f64>,
    /// Normal contact force, N, positive when repulsive (empty if the code does not write it).
    pub normal_force: Vec<f64>,
}

/// What a driver's parser returns.
#[derive(Clone, Debug, PartialEq)]
pub struct ParsedRun {
    /// The trajectory.
    pub trajectory: CodeTrajectory,
    /// The code's own loop time, s, where it reports one.
    pub loop_time: Option<f64>,
    /// The code's version as it prints it.
    pub version: Option<String>,
}

/// A rendered input: the file to write and the arguments that run it.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderedInput {
    /// File name inside the scratch directory.
    pub file_name: String,
    /// The whole input text.
    pub text: String,
    /// Command-line arguments, the input file name among them.
    pub args: Vec<String>,
}

/// A fault of an external code. Each variant names the code and, where there is one, where
/// its log was kept.
#[derive(Debug, Error)]
pub enum CodeError {
    /// The binary is not on PATH.
    #[error(
        "{code}: binary `{binary}` not found on PATH (install it with scripts/install-dem-codes.sh)"
    )]
    MissingBinary {
        /// Code name.
        code: String,
        /// Binary name.
        binary: String,
    },
    /// The code exited with a failure status.
    #[error("{code}: exited with {status}; log kept in {}", log.display())]
    Crashed {
        /// Code name.
        code: String,
        /// Exit status as text.
        status: String,
        /// The kept log file.
        log: PathBuf,
    },
    /// The code ran past its time limit and was killed.
    #[error("{code}: killed after the time limit of {seconds} s; log kept in {}", log.display())]
    TimedOut {
        /// Code name.
        code: String,
        /// The limit, s.
        seconds: f64,
        /// The kept log file.
        log: PathBuf,
    },
    /// The code's output could not be read.
    #[error("{code}: unparsable output: {reason}; log kept in {}", log.display())]
    Unparsable {
        /// Code name.
        code: String,
        /// What was wrong.
        reason: String,
        /// The kept log file.
        log: PathBuf,
    },
    /// The case cannot be set up in this code.
    #[error("{code}: cannot set up {case}: {reason}")]
    Unsupported {
        /// Code name.
        code: String,
        /// Case name.
        case: String,
        /// Why.
        reason: String,
    },
    /// Scratch-directory or process I/O failed.
    #[error("{code}: {context}: {source}")]
    Io {
        /// Code name.
        code: String,
        /// What was being done.
        context: String,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// One external DEM code.
pub trait CodeDriver: Send + Sync {
    /// Short name: `liggghts`, `yade` or `lammps`.
    fn name(&self) -> &'static str;
    /// The executable looked up on PATH.
    fn binary(&self) -> &'static str;
    /// Render the input deck for `setup` (from the template in `scripts/`).
    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError>;
    /// Parse the run's files in `workdir` and its combined stdout/stderr `log`.
    fn parse(&self, setup: &CodeSetup, workdir: &Path, log: &str) -> Result<ParsedRun, String>;
    /// The contact law this code really integrates for `setup`, as measured on the installed
    /// version (effective radius and modulus, damping formula, clamp).
    fn law(&self, setup: &CodeSetup) -> DashpotLaw;
    /// How the code advances a step (what velocity its damping sees).
    fn step_scheme(&self) -> StepScheme {
        StepScheme::VelocityVerlet
    }
    /// The COR the code realises when it cannot realise the target exactly (a clamp, a
    /// missing factor); `None` when it realises the target. By default: the COR of the
    /// code's own law when that law is clamped at the setup's request, since a clamp cuts
    /// the attractive tail the target's damping was computed with.
    fn expected_restitution(&self, setup: &CodeSetup) -> Option<f64> {
        let law = self.law(setup);
        if !(setup.clamp_attractive && law.clamp_attractive) {
            return None;
        }
        accurate_metrics(&law, setup.impact_velocity, 1e-12)
            .ok()
            .map(|m| m.cor)
    }
}

/// A finished run of an external code.
#[derive(Clone, Debug)]
pub struct CodeRun {
    /// Code name.
    pub code: String,
    /// Version string as the code printed it.
    pub code_version: String,
    /// The exact input it ran.
    pub input: String,
    /// The trajectory.
    pub trajectory: CodeTrajectory,
    /// Process wall time, s.
    pub wall_time: f64,
    /// The code's own loop time, s, where reported.
    pub loop_time: Option<f64>,
    /// The combined stdout and stderr.
    pub log: String,
}

/// Time limit and scratch location for [`run_code`].
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Kill the code after this long.
    pub timeout: Duration,
    /// Parent directory for scratch directories (the system temp dir by default).
    pub scratch_parent: Option<PathBuf>,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            timeout: Duration::from_secs(120),
            scratch_parent: None,
        }
    }
}

/// Whether `binary` is an executable on PATH.
pub fn find_on_path(binary: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(binary))
        .find(|candidate| candidate.is_file())
}

/// Render, run and parse one impact in `driver`'s code.
///
/// The scratch directory is removed after a good run and kept, with its `log.txt`, after any
/// failure, so that the error can point at it.
pub fn run_code(
    driver: &dyn CodeDriver,
    setup: &CodeSetup,
    options: &RunOptions,
) -> Result<CodeRun, CodeError> {
    let code = driver.name().to_string();
    let io_error = |context: &str| {
        let code = code.clone();
        let context = context.to_string();
        move |source| CodeError::Io {
            code,
            context,
            source,
        }
    };
    let binary = find_on_path(driver.binary()).ok_or_else(|| CodeError::MissingBinary {
        code: code.clone(),
        binary: driver.binary().to_string(),
    })?;
    let input = driver.render(setup)?;
    let parent = options
        .scratch_parent
        .clone()
        .unwrap_or_else(std::env::temp_dir);
    std::fs::create_dir_all(&parent).map_err(io_error("creating the scratch parent"))?;
    let scratch = tempfile::Builder::new()
        .prefix(&format!("millimpact-{}-{}-", code, setup.case_name))
        .tempdir_in(&parent)
        .map_err(io_error("creating a scratch directory"))?;
    let workdir = scratch.path().to_path_buf();
    std::fs::write(workdir.join(&input.file_name), &input.text)
        .map_err(io_error("writing the input"))?;
    let log_path = workdir.join("log.txt");
    let log_file = std::fs::File::create(&log_path).map_err(io_error("creating the log"))?;
    let log_err = log_file
        .try_clone()
        .map_err(io_error("duplicating the log handle"))?;

    let started = Instant::now();
    let mut child = Command::new(&binary)
        .args(&input.args)
        .current_dir(&workdir)
        .stdin(Stdio::null())
        .stdout(Stdio::from(log_file))
        .stderr(Stdio::from(log_err))
        .spawn()
        .map_err(io_error("starting the code"))?;
    let status = wait_timeout::ChildExt::wait_timeout(&mut child, options.timeout)
        .map_err(io_error("waiting for the code"))?;
    let wall_time = started.elapsed().as_secs_f64();
    let keep = |scratch: tempfile::TempDir| scratch.keep().join("log.txt");
    let status = match status {
        Some(status) => status,
        None => {
            let _ = child.kill();
            let _ = child.wait();
            return Err(CodeError::TimedOut {
                code,
                seconds: options.timeout.as_secs_f64(),
                log: keep(scratch),
            });
        }
    };
    let mut log = String::new();
    std::fs::File::open(&log_path)
        .and_then(|mut f| f.read_to_string(&mut log))
        .map_err(io_error("reading the log"))?;
    if !status.success() {
        return Err(CodeError::Crashed {
            code,
            status: status.to_string(),
            log: keep(scratch),
        });
    }
    let parsed = match driver.parse(setup, &workdir, &log) {
        Ok(parsed) => parsed,
        Err(reason) => {
            return Err(CodeError::Unparsable {
                code,
                reason,
                log: keep(scratch),
            });
        }
    };
    if let Err(reason) = check_trajectory(&parsed.trajectory) {
        return Err(CodeError::Unparsable {
            code,
            reason,
            log: keep(scratch),
        });
    }
    Ok(CodeRun {
        code,
        code_version: parsed.version.unwrap_or_else(|| "unknown".to_string()),
        input: input.text,
        trajectory: parsed.trajectory,
        wall_time,
        loop_time: parsed.loop_time,
        log,
    })
}

fn check_trajectory(t: &CodeTrajectory) -> Result<(), String> {
    let n = t.time.len();
    if n < 3 {
        return Err(format!("trajectory has {n} rows, at least 3 needed"));
    }
    if t.overlap.len() != n || t.approach_velocity.len() != n {
        return Err("trajectory columns differ in length".to_string());
    }
    let all = t.time.iter().chain(&t.overlap).chain(&t.approach_velocity);
    if all.clone().any(|x| !x.is_finite()) {
        return Err("trajectory holds a non-finite value".to_string());
    }
    Ok(())
}

/// Read a trajectory written as whitespace-separated columns `time overlap approach_velocity
/// normal_force`, one row per line; blank lines and `#` comments are skipped. `file` names the
/// file in error messages.
pub fn parse_columns(text: &str, file: &str) -> Result<CodeTrajectory, String> {
    let mut out = CodeTrajectory::default();
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let values: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|e| format!("{file} line {}: {e}: {line:?}", number + 1))?;
        let [t, overlap, approach, force] = values[..] else {
            return Err(format!(
                "{file} line {}: expected 4 columns, found {}",
                number + 1,
                values.len()
            ));
        };
        out.time.push(t);
        out.overlap.push(overlap);
        out.approach_velocity.push(approach);
        out.normal_force.push(force);
    }
    Ok(out)
}

/// Replace every `{{key}}` in `template` by its value; an unreplaced placeholder is an error.
pub fn fill_template(template: &str, values: &[(&str, String)]) -> Result<String, String> {
    let mut text = template.to_string();
    for (key, value) in values {
        text = text.replace(&format!("{{{{{key}}}}}"), value);
    }
    match text.find("{{") {
        Some(at) => {
            let rest: String = text[at..].chars().take(40).collect();
            Err(format!("template placeholder left unfilled: {rest}"))
        }
        None => Ok(text),
    }
}

/// Format a float so that a code reads it back exactly (shortest round-trip form).
pub fn exact_number(x: f64) -> String {
    format!("{x:e}")
}

/// Impact figures read from a trajectory, the way they are read from a DEM code's output.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrajectoryMetrics {
    /// Coefficient of restitution: approach speed after contact over approach speed before.
    pub cor: f64,
    /// Largest overlap, m.
    pub peak_deformation: f64,
    /// Largest normal force, N (NaN if the trajectory has no force column).
    pub peak_force: f64,
    /// Contact duration, s, from the zero crossings of the overlap (linearly interpolated).
    pub contact_time: f64,
}

/// Read COR, peak overlap, peak force and contact time from a trajectory.
///
/// The speed before contact is the first row's, the speed after is the first row past the
/// contact (overlap ≤ 0 after having been positive), or the last row's if the contact has not
/// ended, in which case the error says so.
pub fn trajectory_metrics(t: &CodeTrajectory) -> Result<TrajectoryMetrics, String> {
    check_trajectory(t)?;
    let first_in = t
        .overlap
        .iter()
        .position(|&d| d > 0.0)
        .ok_or("the bodies never touched")?;
    let last_in = t.overlap[first_in..]
        .iter()
        .position(|&d| d <= 0.0)
        .map(|k| first_in + k)
        .ok_or("the contact had not ended when the run stopped")?;
    let crossing = |i: usize| -> f64 {
        // Overlap changes sign between rows i-1 and i.
        if i == 0 {
            return t.time[0];
        }
        let (d0, d1) = (t.overlap[i - 1], t.overlap[i]);
        let (t0, t1) = (t.time[i - 1], t.time[i]);
        if d1 == d0 {
            t1
        } else {
            t0 + (t1 - t0) * d0 / (d0 - d1)
        }
    };
    let start = crossing(first_in);
    let end = crossing(last_in);
    let v_in = t.approach_velocity[0];
    let v_out = -t.approach_velocity[last_in];
    let peak_deformation = t.overlap.iter().cloned().fold(f64::MIN, f64::max);
    let peak_force = if t.normal_force.is_empty() {
        f64::NAN
    } else {
        t.normal_force.iter().cloned().fold(f64::MIN, f64::max)
    };
    Ok(TrajectoryMetrics {
        cor: v_out / v_in,
        peak_deformation,
        peak_force,
        contact_time: end - start,
    })
}

/// Default number of steps per estimated contact time for a code's time step.
pub const DEFAULT_STEPS_PER_CONTACT: u32 = 1000;

/// The elastic contact time of the case's spring, s: Hertz's `2 J(1.5) δ_max / v0` for the
/// balls, `π sqrt(M/k)` for the rod. It sets the codes' time step.
pub fn elastic_contact_time(case: &Case) -> f64 {
    match (
        case.scene.effective_modulus(),
        case.scene.effective_radius(),
    ) {
        (Some(e), Some(r)) => {
            exact::hertz_elastic(case.scene.reduced_mass(), e, r, case.impact_velocity).contact_time
        }
        _ => {
            std::f64::consts::PI * (case.scene.reduced_mass() / case.scene.hertz_stiffness()).sqrt()
        }
    }
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
/// length left at zero: [`prepare`] sets it from the code's own law.
pub fn setup_for_case(case: &Case, timestep: f64) -> CodeSetup {
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
        timestep,
        steps: 0,
        clamp_attractive: false,
    }
}

/// The setup of `case` for `driver`, its time step either given or the elastic contact time
/// over `steps_per_contact`, and its run length the contact time of the code's own law (at
/// zero step error) plus 5 % and three steps: enough to end the contact, no more.
pub fn prepare(
    driver: &dyn CodeDriver,
    case: &Case,
    steps_per_contact: Option<u32>,
    timestep: Option<f64>,
    clamp_attractive: bool,
) -> Result<CodeSetup, SolveError> {
    let dt = timestep.unwrap_or_else(|| {
        elastic_contact_time(case) / steps_per_contact.unwrap_or(DEFAULT_STEPS_PER_CONTACT) as f64
    });
    let mut setup = setup_for_case(case, dt);
    setup.clamp_attractive = clamp_attractive;
    let law = driver.law(&setup);
    let contact = accurate_metrics(&law, setup.impact_velocity, 1e-12)?.contact_time;
    setup.steps = (1.05 * contact / dt).ceil() as u64 + 3;
    Ok(setup)
}

pub mod lammps;
pub mod liggghts;
pub mod yade;

/// Every driver, in report order.
pub fn all_drivers() -> Vec<Box<dyn CodeDriver>> {
    vec![
        Box::new(liggghts::Liggghts),
        Box::new(yade::Yade),
        Box::new(lammps::Lammps),
    ]
}

/// The driver named `name`, if there is one.
pub fn driver(name: &str) -> Option<Box<dyn CodeDriver>> {
    all_drivers().into_iter().find(|d| d.name() == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fill_template_replaces_and_refuses_leftovers() {
        let filled = fill_template("a {{x}} b {{y}}", &[("x", "1".into()), ("y", "2".into())]);
        assert_eq!(filled.unwrap(), "a 1 b 2");
        let err = fill_template("a {{x}} b {{z}}", &[("x", "1".into())]).unwrap_err();
        assert!(err.contains("{{z}}"), "{err}");
    }

    #[test]
    fn parse_columns_reads_rows_and_names_bad_lines() {
        let t = parse_columns("# t d v f\n0 0 2 0\n\n1e-7 2e-7 1.9 5\n", "traj").unwrap();
        assert_eq!(t.time, vec![0.0, 1e-7]);
        assert_eq!(t.normal_force, vec![0.0, 5.0]);
        let err = parse_columns("0 0 2\n", "traj").unwrap_err();
        assert!(
            err.contains("traj line 1") && err.contains("4 columns"),
            "{err}"
        );
        assert!(parse_columns("0 0 x 1\n", "traj").is_err());
    }

    #[test]
    fn trajectory_metrics_interpolates_the_zero_crossings() {
        // Overlap rises from -1 to 3 and falls to -1: zero crossings at t = 0.25 and t = 3.75.
        let t = CodeTrajectory {
            time: vec![0.0, 1.0, 2.0, 3.0, 4.0],
            overlap: vec![-1.0, 3.0, 4.0, 3.0, -1.0],
            approach_velocity: vec![2.0, 1.0, 0.0, -1.0, -1.5],
            normal_force: vec![0.0, 10.0, 20.0, 10.0, 0.0],
        };
        let m = trajectory_metrics(&t).unwrap();
        assert_eq!(m.contact_time, 3.5);
        assert_eq!(m.cor, 0.75);
        assert_eq!(m.peak_deformation, 4.0);
        assert_eq!(m.peak_force, 20.0);
    }

    #[test]
    fn trajectory_metrics_refuses_an_unfinished_contact() {
        let t = CodeTrajectory {
            time: vec![0.0, 1.0, 2.0],
            overlap: vec![0.0, 1.0, 2.0],
            approach_velocity: vec![1.0, 1.0, 1.0],
            normal_force: vec![],
        };
        let err = trajectory_metrics(&t).unwrap_err();
        assert!(err.contains("had not ended"), "{err}");
    }
}
