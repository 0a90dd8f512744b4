//! The paper's law in Kratos DEM (`kratos-paper`): the installed Kratos 10.4.4 with the force
//! `F = C yⁿ (1 + η sign ẏ)` applied through Kratos' own hook, not a compiled law.
//!
//! Kratos' contact laws are compiled C++ and the wheel carries no headers, but
//! `SphericParticle::ComputeAdditionalForces` adds each node's `EXTERNAL_APPLIED_FORCE` to the
//! forces it integrates. The script (`paper.py`, sharing `common.py` with the stock scripts)
//! sets that force before every `SolveSolutionStep` from the position and velocity the step
//! starts from, with the rule of `crate::solve::dashpot::paper_force_in_step` (the sign of
//! ẏ resolved within one step's band, so a contact at rest carries its elastic force; never
//! attractive). No stock law acts: there are no wall conditions (the plate is the plane z = 0
//! of the hook) and the two balls meet under a linear law of zero stiffness and damping; each
//! run checks this (a node's `TOTAL_FORCES` is the applied force, plus the weight under
//! gravity, to the rounding of Kratos' sum, else the run is refused,
//! [`ParseError::ForeignForce`]). A validation build: one Python call per step.
//!
//! - Ball scenes: `C = (4/3) E* sqrt(R*)`, `E*` mixed from the ball's and the plate's (or the
//!   other ball's) `E`, `ν` as Kratos' Hertz law mixes them, a rigid plate as the stock driver
//!   makes its wall ([`super::RIGID_WALL_MODULUS`], ν = 0); `R* = R` at the plane.
//! - `rod_end`: `n = 1` with the case's `kn`.
//! - η is the setup's loss coefficient itself; `M` the ball's mass over the plane, the reduced
//!   mass of two balls, from the masses Kratos forms ([`super::particle_mass`]).
//!
//! Kratos steps by symplectic Euler: the force of step `n` sees `(x_n, v_n)`, then
//! `v_{n+1} = v_n + Δt F/m`, `x_{n+1} = x_n + Δt v_{n+1}`; the harness steps the law the same
//! way ([`StepScheme::LeapFrog`]), from the same start (touching, exactly zero overlap).

use std::path::Path;

use super::{dynamic_mass, hertz_stiffness};
use crate::codes::batch::{BatchError, parse_marked_batch};
use crate::codes::batch_fns::{BatchFns, check_batch_size};
use crate::codes::paper_law::paper_law_methods;
use crate::codes::parse::{ParseError, log_value};
use crate::codes::script_values::{body_values, python_dict, reported, without};
use crate::codes::template::exact_number;
use crate::codes::{
    CalibrationCard, CodeDriver, CodeError, CodeSetup, Executable, LocateError, ParsedRun,
    RenderedInput,
};
use crate::codes::{paper_loss_coefficient, refuse_for_paper_law};
use crate::model::law::{CodeLaw, PaperLaw};
use crate::model::scene::SceneKind;
use crate::solve::dashpot::StepScheme;

/// The part of the script after its list of impacts.
const SCRIPT: &str = include_str!("paper.py");

/// The name of the rendered script in the scratch directory.
const SCRIPT_FILE: &str = "paper.py";

/// Most impacts in one script.
const MAX_BATCH: usize = 256;

/// Impacts whose steps cost what one start of Kratos does: importing Kratos and initialising
/// the stage take about 0.3 s of CPU, an impact at 200 steps per contact about 4.5 ms of its
/// batch, the hook's Python included (measured: a sweep of 20 η on ball_plate at 200 steps per
/// contact took 0.38 s of CPU with `--batch 20`, 5.9 s with `--batch 1`).
const IMPACTS_PER_START: usize = 60;

/// Why `--clamp` is refused for this build.
const CLAMP_REFUSAL: &str = "the paper's law applied through EXTERNAL_APPLIED_FORCE is C y^n \
                             (1 - eta) at least while in contact: it never attracts, so there \
                             is nothing to clamp";

/// Kratos with the paper's law through `EXTERNAL_APPLIED_FORCE`.
pub struct KratosPaper;

impl KratosPaper {
    /// What the build refuses before it runs: what every build of the paper's law refuses
    /// ([`refuse_for_paper_law`]).
    fn validate(&self, setup: &CodeSetup) -> Result<(), CodeError> {
        refuse_for_paper_law(self.name(), setup, CLAMP_REFUSAL)
    }

    /// The paper's law the hook applies for `setup`: `C` as the module says, Kratos' masses,
    /// the setup's η.
    fn paper_law(&self, setup: &CodeSetup) -> PaperLaw {
        let stiffness = match setup.scene {
            SceneKind::RodEnd => setup.stiffness,
            SceneKind::BallPlate | SceneKind::BallBall => hertz_stiffness(setup),
        };
        PaperLaw {
            mass: dynamic_mass(setup),
            stiffness,
            exponent: setup.exponent,
            loss_coefficient: paper_loss_coefficient(setup),
        }
    }

    /// The values of one impact in the script's list, or why the setup cannot run.
    fn script_values(&self, setup: &CodeSetup) -> Result<Vec<(&'static str, String)>, CodeError> {
        self.validate(setup)?;
        let law = self.paper_law(setup);
        // Kratos forms the masses from the densities, and the hook is the plate.
        let mut values = without(
            body_values(setup),
            &["mass", "other_mass", "wall_young", "wall_poisson"],
        );
        values.extend([
            ("stiffness", exact_number(law.stiffness)),
            ("exponent", exact_number(law.exponent)),
            ("loss_coefficient", exact_number(law.loss_coefficient)),
            ("scheme", super::SCHEME.to_string()),
        ]);
        Ok(values)
    }
}

/// The script running `setups` side by side in one stage under `gravity` (m/s², downwards
/// along z; the driver's runs have none), or why they cannot run together.
pub fn render_script(setups: &[CodeSetup], gravity: f64) -> Result<RenderedInput, BatchError> {
    check_batch_size(setups, MAX_BATCH, "the script's size")?;
    let first = &setups[0];
    let mut impacts = String::new();
    for s in setups {
        if s.timestep.to_bits() != first.timestep.to_bits() {
            return Err(BatchError::Differ { what: "time step" });
        }
        impacts += &format!("    {},\n", python_dict(&KratosPaper.script_values(s)?));
    }
    // Far enough apart that no two impacts' bodies ever come within each other's search.
    let reach = setups
        .iter()
        .map(|s| {
            4.0 * s
                .sphere
                .radius
                .max(s.other_sphere.map_or(0.0, |o| o.radius))
        })
        .fold(0.0f64, f64::max);
    let text = format!(
        "# millimpact: {} impacts under the paper's law in Kratos DEM (src/codes/kratos/paper.rs).\n\
         # Each impact's values.\nIMPACTS = [\n{impacts}]\nSPACING = {}\nGRAVITY = {}\n{}",
        setups.len(),
        exact_number(reach),
        exact_number(gravity),
        super::with_common(SCRIPT),
    );
    Ok(super::script_input(SCRIPT_FILE, text))
}

/// Each impact's run from a script's `log` and files in `workdir`: refused as a whole when the
/// script ran another number of steps than the longest setup's, or when a stock law added a
/// force of its own.
fn parse_runs(
    setups: &[CodeSetup],
    workdir: &Path,
    log: &str,
) -> Vec<Result<ParsedRun, ParseError>> {
    // ParseError is not Clone (it may hold an io::Error): each impact gets its own.
    let refusals: Vec<ParseError> = setups
        .iter()
        .filter_map(|_| check_log(setups, log).err())
        .collect();
    if !refusals.is_empty() {
        return refusals.into_iter().map(Err).collect();
    }
    parse_marked_batch(setups, workdir, log)
}

/// The script's own account of the run: its step count and the largest difference between a
/// node's total force and the force applied to it.
fn check_log(setups: &[CodeSetup], log: &str) -> Result<(), ParseError> {
    super::check_steps(log, setups.iter().map(|s| s.steps).max().unwrap_or(0))?;
    match reported::<f64>(log_value(log, "force_mismatch="), "force_mismatch")? {
        Some(mismatch) if mismatch != 0.0 => Err(ParseError::ForeignForce { mismatch }),
        _ => Ok(()),
    }
}

impl CodeDriver for KratosPaper {
    fn name(&self) -> &'static str {
        "kratos-paper"
    }

    fn binary(&self) -> &'static str {
        "python"
    }

    /// `MILLIMPACT_KRATOS_PAPER_BINARY` if set (a python that imports Kratos), else the Kratos
    /// venv's python under the codes' folder; one OpenMP thread, as the stock driver's.
    fn locate(&self) -> Result<Executable, LocateError> {
        super::locate_python(self)
    }

    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        render_script(std::slice::from_ref(setup), 0.0).map_err(|e| match e {
            BatchError::Impact(e) => e,
            other => setup.unsupported(self.name(), other.to_string()),
        })
    }

    fn parse(&self, setup: &CodeSetup, workdir: &Path, log: &str) -> Result<ParsedRun, ParseError> {
        parse_runs(std::slice::from_ref(setup), workdir, log)
            .pop()
            .unwrap_or_else(|| {
                Err(ParseError::Empty {
                    file: crate::codes::batch::marked_trajectory_file(0),
                })
            })
    }

    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        CodeLaw::Paper(self.paper_law(setup))
    }

    fn step_scheme(&self) -> StepScheme {
        StepScheme::LeapFrog
    }

    paper_law_methods!(CLAMP_REFUSAL, PAPER_BATCH, KratosPaperCard);

    /// The law liggghts-paper integrates, stepped through the same positions (symplectic
    /// Euler and velocity Verlet see the same state): drawn as one in the figures.
    fn shares_law_with(&self) -> Option<crate::codes::CodeName> {
        Some(crate::codes::CodeName::LiggghtsPaper)
    }
}

/// Many impacts side by side in one stage: any scenes, one time step.
static PAPER_BATCH: BatchFns =
    BatchFns::new(MAX_BATCH, |setups| render_script(setups, 0.0), parse_runs)
        .costing(IMPACTS_PER_START);

/// The card: the impact's values and the line that hands Kratos the force.
struct KratosPaperCard;

impl CalibrationCard for KratosPaperCard {
    fn setting_keys(&self, _scene: SceneKind) -> &'static [&'static str] {
        // The impact's line of the list, and the line that hands Kratos the force.
        &["{\"scene\": ", "EXTERNAL_APPLIED_FORCE, applied"]
    }

    fn traps(&self, setup: &CodeSetup) -> Vec<String> {
        let mut t = vec![
            "η is the loss coefficient itself, not a COR: e = sqrt((1 − η)/(1 + η)), 0 <= η < 1".into(),
            "set EXTERNAL_APPLIED_FORCE after InitializeSolutionStep and before SolveSolutionStep, from the position and velocity the step starts from (symplectic Euler: the force of step n sees x_n, v_n)".into(),
            "no stock law may act on the pair: no wall conditions where the hook is the wall, and a ball pair's law of zero stiffness (DEM_D_Linear_Custom_Constants, K_NORMAL = 0) or out of search".into(),
            "at rest: the sign of ẏ within the band 2η C yⁿ Δt / M is ẏ / band, else a resting contact's force flips branch every step".into(),
        ];
        if setup.scene == SceneKind::BallPlate {
            t.push("the plate's E and ν are mixed into E* as Kratos' Hertz law mixes them (a rigid plate: E = 1e30, ν = 0)".into());
        }
        t
    }
}
