//! Drivers for the reference DEM codes: render an input deck for one impact, run the installed
//! code in a scratch directory under a time limit, and parse its trajectory.
//!
//! Every driver implements [`CodeDriver`] and is listed once in the registry below; the
//! registry owns the codes' names (the command line derives its choices from it).
//! [`runner::run_code`] does the part the drivers share (scratch directory, time limit, log
//! capture, error reporting), and [`crate::model::trajectory::trajectory_metrics`] turns any
//! code's trajectory into the same figures the solver reports.

pub mod batch;
pub(crate) mod batch_fns;
pub(crate) mod conventions;
pub mod damping;
pub mod deck;
pub(crate) mod paper_law;
pub(crate) mod parse;
pub(crate) mod probe;
pub mod runner;
pub mod script;
pub(crate) mod script_values;
pub(crate) mod setup;
pub mod template;

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::model::law::{CodeLaw, DashpotLaw};
use crate::model::scene::SceneKind;
use crate::model::trajectory::CodeTrajectory;
use crate::solve::dashpot::{CodeFrame, CodeStepping, StepScheme, own_law_metrics};
pub(crate) use batch::BatchError;
pub use conventions::{Conventions, DampingVelocity, TsujiFit, WallModulus};
pub use parse::{ParseError, TangentialRun};
pub use probe::{Hypothesis, Measured, ProbeError, ProbeItem, ProbeReport};
pub use runner::{CodeError, CodeRun, LocateError, RunOptions, run_code};
pub(crate) use setup::setup_for_case;
pub use setup::{
    CodeOblique, CodeSetup, CodeSphere, SetupError, elastic_contact_time, prepare, prepare_with,
};

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

/// How to start a build's executable: the program and the environment it needs.
#[derive(Clone, Debug, PartialEq)]
pub struct Executable {
    /// The program file.
    pub program: PathBuf,
    /// Variables set for it (a library path, a thread count).
    pub env: Vec<(&'static str, OsString)>,
}

impl Executable {
    /// A program that needs nothing set.
    pub fn plain(program: PathBuf) -> Self {
        Executable {
            program,
            env: Vec::new(),
        }
    }

    /// The program linked to Open MPI and started alone (the Debian builds of LIGGGHTS and
    /// LAMMPS), told not to spawn Open MPI's support daemon (`orted`): a program that never
    /// spawns others has no use for it, and starting it costs each process about 0.15 s and,
    /// on a loaded machine, now and then fails the start (`Unable to start a daemon on the
    /// local node`). The variable changes nothing the code computes; a build without Open MPI
    /// ignores it.
    pub(crate) fn open_mpi_alone(mut self) -> Self {
        self.env.push((
            "OMPI_MCA_ess_singleton_isolated",
            std::ffi::OsString::from("1"),
        ));
        self
    }

    /// A command that starts it.
    pub fn command(&self) -> Command {
        let mut command = Command::new(&self.program);
        command.envs(self.env.iter().map(|(k, v)| (k, v)));
        command
    }
}

/// One external DEM code, as one build of it (a code with two builds has two entries). It
/// speaks only of what every code has; what a code can do beyond one run is a capability it
/// offers ([`CodeDriver::batch`], [`CodeDriver::prober`], [`CodeDriver::card`],
/// [`CodeDriver::deck`]).
pub trait CodeDriver: Send + Sync {
    /// Short name, as on the command line and in `reference/<name>/`.
    fn name(&self) -> &'static str;
    /// The executable's file name (looked up on PATH by the default [`CodeDriver::locate`]).
    fn binary(&self) -> &'static str;
    /// Find the build's executable: by default the file in `MILLIMPACT_<NAME>_BINARY` if set
    /// (a user's own build), else [`CodeDriver::binary`] on PATH.
    fn locate(&self) -> Result<Executable, LocateError> {
        runner::locate_override_or_path(self.name(), self.binary())
    }
    /// Render the input deck for `setup` (from the template in the code's folder).
    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError>;
    /// Parse the run's files in `workdir` and its combined stdout/stderr `log`.
    fn parse(&self, setup: &CodeSetup, workdir: &Path, log: &str) -> Result<ParsedRun, ParseError>;
    /// The contact law this code really integrates for `setup`, as measured on the installed
    /// version (effective radius and modulus, damping formula, clamp).
    fn law(&self, setup: &CodeSetup) -> CodeLaw;
    /// Rows a complete trajectory of `setup` has (by default the initial state and one per
    /// step): fewer is a truncated run, refused rather than read.
    fn trajectory_rows(&self, setup: &CodeSetup) -> u64 {
        setup.steps + 1
    }
    /// The gap between the surfaces at `t = 0`, m, that the code's run of `setup` starts from
    /// (a code that counts touching as contact starts a hair before touch). The code's own law
    /// is stepped from the same start: stepped from touch instead, a run whose last contact
    /// step grazes the end of contact differs from it by up to 2.6e-8 in COR (LIGGGHTS at
    /// η = 0.63 and 200 steps per contact), not by the 1e-13 of rounding.
    fn start_gap(&self, setup: &CodeSetup) -> f64 {
        let _ = setup;
        0.0
    }
    /// How the code advances a step (what velocity its damping sees).
    fn step_scheme(&self) -> StepScheme {
        StepScheme::VelocityVerlet
    }
    /// Where a run of `setup` starts in the code's own coordinates, for a code whose
    /// rounding of the bodies' positions is worth repeating ([`CodeFrame`]); by default none:
    /// its law is stepped from touch in the coordinates of the relative motion.
    fn frame(&self, setup: &CodeSetup) -> Option<CodeFrame> {
        let _ = setup;
        None
    }
    /// How the code steps its law for `setup`: its scheme and its frame.
    fn stepping(&self, setup: &CodeSetup) -> CodeStepping {
        CodeStepping {
            scheme: self.step_scheme(),
            frame: self.frame(setup),
        }
    }
    /// Whether the code is given the paper's η itself (its law is the paper's) rather than a
    /// COR: its setups then carry η ([`CodeSetup::loss_coefficient`]).
    fn takes_loss_coefficient(&self) -> bool {
        false
    }
    /// Why the code cannot cut off attractive force at a user's request (`--clamp`), where it
    /// cannot; `None` where it can (or always does).
    fn clamp_refusal(&self) -> Option<&'static str> {
        None
    }
    /// Whether the build renders an oblique or spinning ball-on-plate impact
    /// ([`CodeSetup::oblique`]): the ball's motion along the plane, the friction, the
    /// tangential law, and after the run one line [`deck::TANGENTIAL_LINE`]` VT OMEGA` in its
    /// output. A build that does not is refused such a setup before it starts.
    fn runs_oblique(&self) -> bool {
        false
    }
    /// Many independent impacts in one process, where the code can.
    fn batch(&self) -> Option<&dyn BatchRunner> {
        None
    }
    /// The build's conventions measured by a probe, where they vary between builds.
    fn prober(&self) -> Option<&dyn Prober> {
        None
    }
    /// What a user who sets the code up by hand types, and the traps to avoid.
    fn card(&self) -> Option<&dyn CalibrationCard> {
        None
    }
    /// A reader of this code's users' own decks (`millimpact deck`).
    fn deck(&self) -> Option<&dyn deck::DeckReader> {
        None
    }
    /// Where the decks this build's reader reads run when they select the paper's law, for a
    /// build that lacks the law (a stock build: its paper build has it); `None` where this
    /// build runs such a deck itself, or reads no decks.
    fn paper_build(&self) -> Option<PaperBuild> {
        None
    }
    /// The build that runs the paper's law beside this build's damped Hertz in a mill
    /// (`millimpact mill`: a drum deck run under both laws); `None` for a build that runs no
    /// mill.
    fn mill_paper_build(&self) -> Option<CodeName> {
        None
    }
    /// The code whose contact law this one integrates too (drawn as one in the figures).
    fn shares_law_with(&self) -> Option<CodeName> {
        None
    }
    /// The COR the code realises when it cannot realise the target exactly (a clamp, a
    /// missing factor); `None` when it realises the target. By default: the COR of the
    /// code's own law when that law is clamped at the setup's request, since a clamp cuts
    /// the attractive tail the target's damping was computed with.
    fn expected_restitution(&self, setup: &CodeSetup) -> Option<f64> {
        let law = self.law(setup);
        if !(setup.clamp_attractive && law.clamp_attractive()) {
            return None;
        }
        own_law_metrics(&law, setup.impact_velocity, 1e-12)
            .ok()
            .map(|m| m.cor)
    }
    /// The conventions a live run of this build is set up with: its located executable's
    /// probe (once per process). `Ok(None)` for a code with no probe, when the executable is
    /// not found, or when it fails the probe's basic deck: no run of it can succeed then, and
    /// the run reports why with its own log. `Err` when the build runs but its probe is
    /// inconclusive.
    fn measured_conventions(&self) -> Result<Option<Conventions>, ProbeError> {
        let Some(prober) = self.prober() else {
            return Ok(None);
        };
        let Ok(executable) = self.locate() else {
            return Ok(None);
        };
        match prober.probe(&executable) {
            Err(_) => Ok(None),
            Ok(report) if !report.ran() => Ok(None),
            Ok(report) => report.conventions().map(Some),
        }
    }
}

/// A stock build's paper build as a user's deck meets it ([`CodeDriver::paper_build`]): the
/// build of the same code that has the paper's law, and what the stock build says when asked
/// to run a deck that selects the law itself (it would stop on the unknown style).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PaperBuild {
    /// The build with the paper's law.
    pub code: CodeName,
    /// What the refusal calls the deck's selection, before the model as the deck writes it
    /// (`normal model `, or nothing).
    pub selection: &'static str,
    /// Why the stock build cannot run such a deck.
    pub lacks: &'static str,
    /// What to run instead.
    pub instead: &'static str,
}

impl PaperBuild {
    /// Why `stock` refuses a deck that selects the paper's law with `model`.
    pub fn refusal(&self, stock: CodeName, model: &str) -> String {
        format!(
            "{}`{model}` with --code {stock}: {}",
            self.selection, self.lacks
        )
    }
}

/// A code's capability to run many independent impacts in one process (start-up paid once).
pub trait BatchRunner: Send + Sync {
    /// Most impacts one batch input may hold.
    fn max_batch(&self) -> usize;
    /// Render one input that runs the independent impacts of `setups` (one time step), or
    /// say why they cannot run together.
    fn render_batch(&self, setups: &[CodeSetup]) -> Result<RenderedInput, BatchError>;
    /// Parse a batch's runs in `workdir`, one result per setup, in order.
    fn parse_batch(
        &self,
        setups: &[CodeSetup],
        workdir: &Path,
        log: &str,
    ) -> Vec<Result<ParsedRun, ParseError>>;
    /// How many impacts' steps cost what one start of the code's process does (measured): a
    /// sweep runs fewer batches than it has workers rather than start a process for fewer
    /// (see `balanced_sizes` in the sweep). By default 1: a start as cheap as an impact.
    fn impacts_per_start(&self) -> usize {
        1
    }
    /// The program that runs a rendered batch `input`, given the build's located
    /// `executable`, and its arguments: by default the executable itself with the input's.
    fn launch(&self, executable: Executable, input: &RenderedInput) -> Launch {
        Launch {
            executable,
            args: input.args.clone(),
        }
    }
}

/// What a batch is started with: a program, its environment and its arguments.
#[derive(Clone, Debug, PartialEq)]
pub struct Launch {
    /// The program and the variables set for it.
    pub executable: Executable,
    /// Its arguments, the input file's name among them.
    pub args: Vec<String>,
}

/// A code's capability to measure, by short runs, the conventions its build follows.
pub trait Prober: Send + Sync {
    /// Probe the build at `executable`: what it does, measured, item by item (a probe kept
    /// from an earlier run of this very build is read instead of run again).
    fn probe(&self, executable: &Executable) -> Result<ProbeReport, ProbeError>;
    /// Probe the build at `executable` now, whatever is kept, and keep the new report.
    fn probe_afresh(&self, executable: &Executable) -> Result<ProbeReport, ProbeError>;
    /// The conventions `setup` is planned with in this build (its own, else the build's
    /// fallback).
    fn planned_conventions(&self, setup: &CodeSetup) -> Conventions;
}

/// A code's calibration card: the lines of its rendered input a user types by hand, and the
/// traps those lines avoid.
pub trait CalibrationCard: Send + Sync {
    /// Markers of the lines of a rendered input that set the contact law and the bodies'
    /// materials for `scene`.
    fn setting_keys(&self, scene: SceneKind) -> &'static [&'static str];
    /// The traps a card for `setup` avoids (`reference/<code>/CONVENTIONS.md`).
    fn traps(&self, setup: &CodeSetup) -> Vec<String>;
    /// The law a user gets who takes the code's COR setting at its word (gives e itself
    /// where the code wants another number), with its label; `None` where e is what the
    /// code takes.
    fn law_at_its_word(&self, setup: &CodeSetup) -> Option<(&'static str, DashpotLaw)> {
        let _ = setup;
        None
    }
    /// The input setting that clamps the attractive tail, where the code has one (off by
    /// default).
    fn clamp_setting(&self) -> Option<&'static str> {
        None
    }
}

/// The η a build with the paper's law is given for `setup`: the case's own, carried by the
/// setup; for a setup made without it (a bare [`setup_for_case`] of an older record), the η of
/// its target COR, `(1 − e²)/(1 + e²)`, which may differ from the case's in the last bit.
pub(crate) fn paper_loss_coefficient(setup: &CodeSetup) -> f64 {
    setup
        .loss_coefficient
        .unwrap_or_else(|| crate::model::exact::loss_coefficient(setup.target_restitution))
}

/// What every build with the paper's law refuses before it runs, in this order: η outside
/// `[0, 1)`, a clamp (`clamp_refusal` says why the build has none), no positive time step or no
/// steps, and a ball pair without its second ball.
pub(crate) fn refuse_for_paper_law(
    code: &str,
    setup: &CodeSetup,
    clamp_refusal: &str,
) -> Result<(), CodeError> {
    let refuse = |reason: String| Err(setup.unsupported(code, reason));
    let eta = paper_loss_coefficient(setup);
    if !(0.0..1.0).contains(&eta) {
        return refuse(format!(
            "the paper's law requires 0 <= eta < 1, got {eta} (eta >= 1 never separates the \
             bodies, eta < 0 creates energy)"
        ));
    }
    if setup.clamp_attractive {
        return refuse(clamp_refusal.to_string());
    }
    setup.refuse_unrunnable(code)
}

pub mod kratos;
pub mod lammps;
pub mod liggghts;
pub mod yade;

/// The registry of codes: one line per code folder, `folder { Variant => Driver }`. It declares
/// the [`CodeName`] variant and its dispatch, so that a new code is its driver folder, its `mod`
/// line above (declared outside the macro so that rustfmt follows it) and one line here.
macro_rules! code_registry {
    ($($module:ident { $($variant:ident => $driver:ident),+ $(,)? }),+ $(,)?) => {

        /// A DEM code the harness drives.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum CodeName {
            $($(
                #[doc = concat!("`", stringify!($driver), "`, in `codes/", stringify!($module), "/`")]
                $variant,
            )+)+
        }

        impl CodeName {
            /// Every code, in report order.
            pub const ALL: &'static [CodeName] = &[$($(CodeName::$variant),+),+];

            /// The code's driver.
            pub fn driver(self) -> &'static dyn CodeDriver {
                match self {
                    $($(CodeName::$variant => &$module::$driver,)+)+
                }
            }
        }
    };
}

code_registry! {
    liggghts { Liggghts => Liggghts, LiggghtsPaper => LiggghtsPaper },
    yade { Yade => Yade, YadePaper => YadePaper },
    lammps { Lammps => Lammps, Lammps2025 => Lammps2025, LammpsPaper => LammpsPaper },
    kratos { Kratos => Kratos, KratosPaper => KratosPaper },
}

impl CodeName {
    /// The names of the builds that run an oblique impact ([`CodeDriver::runs_oblique`]).
    pub fn oblique_builds() -> Vec<&'static str> {
        CodeName::ALL
            .iter()
            .filter(|c| c.driver().runs_oblique())
            .map(|c| c.name())
            .collect()
    }

    /// The name on the command line, in reports and in `reference/<name>/`.
    pub fn name(self) -> &'static str {
        self.driver().name()
    }

    /// The code called `name`, if there is one.
    pub(crate) fn from_name(name: &str) -> Option<CodeName> {
        CodeName::ALL.iter().copied().find(|c| c.name() == name)
    }

    /// Every code's name, in report order.
    pub fn names() -> Vec<&'static str> {
        CodeName::ALL.iter().map(|c| c.name()).collect()
    }
}

crate::solve::method::by_name!(CodeName, "code");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_lists_every_code_once_by_its_own_name() {
        assert_eq!(
            CodeName::names(),
            [
                "liggghts",
                "liggghts-paper",
                "yade",
                "yade-paper",
                "lammps",
                "lammps-2025",
                "lammps-paper",
                "kratos",
                "kratos-paper"
            ]
        );
        for &code in CodeName::ALL {
            assert_eq!(CodeName::from_name(code.name()), Some(code));
            let json = serde_json::to_string(&code).unwrap();
            assert_eq!(serde_json::from_str::<CodeName>(&json).unwrap(), code);
        }
        assert!(serde_json::from_str::<CodeName>("\"chrono\"").is_err());
    }
}
