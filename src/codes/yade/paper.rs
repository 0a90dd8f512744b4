//! The driver of the paper's law in YADE (`yade-paper`): the Debian build of YADE 2023.02a, with
//! `F = C yⁿ (1 + η sign ẏ)` added by a `PyRunner` between `ForceResetter` and
//! `NewtonIntegrator` (the script `paper.py` beside `impact.py`).
//!
//! YADE's laws are compiled C++ and its Debian build ships no headers, so the law runs as a
//! Python call per step: a validation build, not a production one (its cost:
//! `reference/yade-paper/CONVENTIONS.md` §4). The script has no collider and no
//! `InteractionLoop`, so YADE's own laws never see the bodies; the hook reads each body's
//! position `x_i` and half-step velocity `v_{i−½}` (what a compiled law sees), forms the overlap
//! and its rate, adds the force with `O.forces.addF`, and YADE's leap-frog kicks and drifts with
//! it.
//!
//! - Ball scenes: `C = (4/3) E* sqrt(R*)` as the case forms it ([`CodeSetup::stiffness`]): the
//!   plate is the plane `z = 0` with its own `E`, `ν` mixed into `E*`, and a rigid plate
//!   leaves the ball's own `E/(1−ν²)` exactly (the hook's plane needs no stand-in modulus, where
//!   the stock driver's wall needs `E = 1e30`). Rod end: `C = kn` of the case, `n = 1`.
//! - η is the setup's `loss_coefficient`, exactly; the branch is chosen as LIGGGHTS `model
//!   paper` chooses it, the sign of the approach rate resolved to one step
//!   (`crate::solve::dashpot::paper_force_in_step`, the same operations in the same order), so
//!   a contact at rest carries its elastic force. The force never attracts: `--clamp` is
//!   refused.
//! - The bodies touch at `t = 0` (the hook's force at zero overlap is zero, so no start gap is
//!   needed); the rows are the stock driver's (`x_i`, `v_{i−½}`, the force of iteration `i`).
//!
//! Batches put every impact of one time step into one scene (no collider: the impacts never
//! meet), one hook for all, so each impact does its single run's arithmetic to the last bit.

use std::path::Path;

use super::Yade;
use super::batch::{PREAMBLE, launch};
use crate::codes::batch::{marked_trajectory_file, parse_marked_batch};
use crate::codes::batch_fns::{BatchFns, check_batch_size};
use crate::codes::paper_law::paper_law_methods;
use crate::codes::script_values::{body_values, python_dict, without};
use crate::codes::template::exact_number;
use crate::codes::{
    BatchError, CalibrationCard, CodeDriver, CodeError, CodeSetup, ParseError, ParsedRun,
    RenderedInput,
};
use crate::codes::{paper_loss_coefficient, refuse_for_paper_law};
use crate::model::law::{CodeLaw, PaperLaw};
use crate::model::scene::SceneKind;
use crate::solve::dashpot::{CodeFrame, FrameBody};

/// The script after its list of impacts: the hook, the bodies and the loop over groups.
const SCRIPT: &str = include_str!("paper.py");

/// The name of the rendered script in the scratch directory.
const SCRIPT_FILE: &str = "paper.py";

/// The trajectory file of a single run.
const TRAJECTORY_FILE: &str = super::TRAJECTORY_FILE;

/// Most impacts in one batch (the script's size).
const MAX_BATCH: usize = 256;

/// Impacts whose steps cost what one start of YADE does: a batch's start (importing the
/// library) takes about 0.7 s of CPU, an impact at 1,000 steps per contact 23–49 ms of hook and
/// stepping (the loop times of the stored runs in `reference/yade-paper/`).
const IMPACTS_PER_START: usize = 20;

/// Why `--clamp` is refused for this build.
const CLAMP_REFUSAL: &str = "the paper's force C y^n (1 - eta) never attracts, so there is \
                             nothing to clamp";

/// The start of a run of the script in YADE's coordinates, mirrored (every coordinate negated,
/// which is exact; `crate::solve::dashpot::step_in_leap_frog_frame`): sphere 1 at `−r1` below
/// the plane `z = 0`, or at the origin with sphere 2 at `r1 + r2` along x, approaching with the
/// centre-of-mass velocities; the masses as the script sets them.
pub fn code_frame(setup: &CodeSetup) -> CodeFrame {
    let (v1, v2) = setup.centre_of_mass_velocities();
    let r1 = setup.sphere.radius;
    match setup.other_sphere {
        Some(other) if setup.scene == SceneKind::BallBall => {
            let reach = r1 + other.radius;
            CodeFrame {
                reach,
                upper: FrameBody {
                    height: -0.0,
                    velocity: -v1,
                    mass: setup.sphere.mass,
                },
                lower: Some(FrameBody {
                    height: -reach,
                    velocity: -v2,
                    mass: other.mass,
                }),
            }
        }
        _ => CodeFrame {
            reach: r1,
            upper: FrameBody {
                height: r1,
                velocity: -v1,
                mass: setup.sphere.mass,
            },
            lower: None,
        },
    }
}

/// YADE with the paper's law added by a Python hook.
pub struct YadePaper;

impl YadePaper {
    /// What the hook cannot run, said before YADE starts: what every build of the paper's law
    /// refuses ([`refuse_for_paper_law`]).
    fn validate(&self, setup: &CodeSetup) -> Result<(), CodeError> {
        refuse_for_paper_law(self.name(), setup, CLAMP_REFUSAL)
    }

    /// The paper's law the hook evaluates for `setup`: the case's `C`, `n`, reduced mass and η.
    pub fn paper_law(setup: &CodeSetup) -> PaperLaw {
        PaperLaw {
            mass: setup.reduced_mass,
            stiffness: setup.stiffness,
            exponent: setup.exponent,
            loss_coefficient: paper_loss_coefficient(setup),
        }
    }

    /// One impact's values as a Python dict literal (every number exact), or why it cannot run.
    fn impact_literal(&self, setup: &CodeSetup) -> Result<String, CodeError> {
        self.validate(setup)?;
        let law = Self::paper_law(setup);
        // The hook forms the law from C, n, η and the pair's mass, and the plate is its plane.
        let mut values = without(
            body_values(setup),
            &[
                "other_density",
                "other_young",
                "other_poisson",
                "wall_young",
                "wall_poisson",
            ],
        );
        values.extend([
            ("stiffness", exact_number(law.stiffness)),
            ("exponent", exact_number(law.exponent)),
            ("loss_coefficient", exact_number(law.loss_coefficient)),
            ("pair_mass", exact_number(law.mass)),
        ]);
        Ok(python_dict(&values))
    }

    /// The script that runs `setups`, writing impact `i`'s rows to `files[i]`: consecutive
    /// impacts of one time step share a scene.
    fn script(&self, setups: &[CodeSetup], files: &[String]) -> Result<String, CodeError> {
        let mut impacts = String::new();
        for s in setups {
            impacts += &format!("    {},\n", self.impact_literal(s)?);
        }
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for (i, s) in setups.iter().enumerate() {
            match groups.last_mut() {
                Some(g) if setups[g[0]].timestep.to_bits() == s.timestep.to_bits() => g.push(i),
                _ => groups.push(vec![i]),
            }
        }
        let python_list = |items: Vec<String>| format!("[{}]", items.join(", "));
        let group_list = python_list(
            groups
                .iter()
                .map(|g| python_list(g.iter().map(usize::to_string).collect()))
                .collect(),
        );
        let file_list = python_list(
            groups
                .iter()
                .map(|g| python_list(g.iter().map(|&i| format!("\"{}\"", files[i])).collect()))
                .collect(),
        );
        Ok(format!(
            "# millimpact: {} impact(s) in YADE under the paper's law (src/codes/yade/paper.rs).\n\
             {PREAMBLE}\n# Each impact's bodies and law (C in N/m^n, the pair's mass in kg).\n\
             IMPACTS = [\n{impacts}]\nGROUPS = {group_list}\nFILES = {file_list}\n{SCRIPT}",
            setups.len(),
        ))
    }
}

impl CodeDriver for YadePaper {
    fn name(&self) -> &'static str {
        "yade-paper"
    }

    fn binary(&self) -> &'static str {
        "yade"
    }

    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        let text = self.script(std::slice::from_ref(setup), &[TRAJECTORY_FILE.to_string()])?;
        Ok(super::script_input(SCRIPT_FILE, text))
    }

    fn parse(&self, setup: &CodeSetup, workdir: &Path, log: &str) -> Result<ParsedRun, ParseError> {
        Yade.parse(setup, workdir, log)
    }

    /// The paper's law with the case's own `C`, `n`, mass and the setup's η: the hook is given
    /// them as exact numbers, so the model difference is zero.
    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        CodeLaw::Paper(Self::paper_law(setup))
    }

    fn step_scheme(&self) -> crate::solve::dashpot::StepScheme {
        crate::solve::dashpot::StepScheme::LeapFrog
    }

    fn frame(&self, setup: &CodeSetup) -> Option<CodeFrame> {
        Some(code_frame(setup))
    }

    paper_law_methods!(CLAMP_REFUSAL, PAPER_BATCH, YadePaperCard);

    /// The paper's law, as liggghts-paper integrates it (drawn as one in the figures).
    fn shares_law_with(&self) -> Option<crate::codes::CodeName> {
        Some(crate::codes::CodeName::LiggghtsPaper)
    }
}

/// The paper build's batches: every impact of one time step in one scene, one hook for all.
static PAPER_BATCH: BatchFns = BatchFns::new(MAX_BATCH, render_batch, parse_marked_batch)
    .costing(IMPACTS_PER_START)
    .launched_by(launch);

/// The script running `setups`, each writing its own trajectory file, as a batch of YADE's is
/// run.
fn render_batch(setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
    check_batch_size(setups, MAX_BATCH, "the batch script's size")?;
    let files: Vec<String> = (0..setups.len()).map(marked_trajectory_file).collect();
    let text = YadePaper.script(setups, &files)?;
    Ok(super::script_input(super::batch::BATCH_SCRIPT, text))
}

/// The paper build's card: the impact's law as the hook is given it, and the engines.
struct YadePaperCard;

impl CalibrationCard for YadePaperCard {
    fn setting_keys(&self, _scene: SceneKind) -> &'static [&'static str] {
        &["{\"scene\": ", "PyRunner(", "NewtonIntegrator("]
    }

    fn traps(&self, setup: &CodeSetup) -> Vec<String> {
        let mut t = vec![
            "the hook is a PyRunner(iterPeriod=1) between ForceResetter and NewtonIntegrator: placed after the integrator, its force is reset by the next step's ForceResetter before any kick".into(),
            "YADE's own contact must be off for the pair (no collider, or masks that keep the pair apart): else its law adds its force to the hook's".into(),
            "numerical damping: NewtonIntegrator(damping=0.2) is the default; set damping=0".into(),
            "loss coefficient is η itself, not a COR: e = sqrt((1 − η)/(1 + η)), 0 <= η < 1".into(),
            "sign(ẏ) from the half-step velocity needs the one-step band 2η C yⁿ Δt / M: a plain sign alternates the force of a contact at rest between C yⁿ (1 ± η)".into(),
        ];
        if setup.scene == SceneKind::BallPlate {
            t.push("plate: the plane's own E and ν are mixed into E*; a rigid plate leaves E/(1 − ν²) of the ball".into());
        }
        if setup.scene == SceneKind::RodEnd {
            t.push("rod: n = 1 with the rod's kn as C".into());
        }
        t.push(
            "cost: a Python call per step, tens of µs: a validation build, not a production one"
                .into(),
        );
        t
    }
}
