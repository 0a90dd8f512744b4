//! Command-line definitions (clap only; the work is done in [`crate::app`]).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use crate::report::Format;
use crate::solve::Method;

/// millimpact: checks the contact law of grinding bodies against exact closed forms and
/// against LIGGGHTS, YADE and LAMMPS.
#[derive(Debug, Parser)]
#[command(name = "millimpact", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// One impact of a case by one method, against the closed forms.
    Run(RunArgs),
    /// One impact per loss coefficient over a range (the paper's Figure 3), CSV on stdout.
    Sweep(SweepArgs),
    /// Every case in cases/ by every method against the closed forms, and the stored DEM-code
    /// references; exit 1 if anything disagrees beyond its stated tolerance.
    Verify(VerifyArgs),
    /// Run one case in a DEM code (LIGGGHTS, YADE or LAMMPS) on the equivalent setup.
    Reference(ReferenceArgs),
    /// Each case by each source (paper law, DEM codes, their own laws, elastic Hertz), side by
    /// side, with the differences attributed to model and integration.
    Compare(CompareArgs),
    /// Error against cost for each method and DEM code: the work–precision picture.
    Precision(PrecisionArgs),
    /// A built-in grid of stiff and extreme cases by every method.
    Stability(StabilityArgs),
}

/// Integration settings shared by the commands that integrate.
#[derive(Debug, Args, Clone)]
pub struct IntegrationArgs {
    /// Integration method.
    #[arg(long, value_enum, default_value = "rk4-event")]
    pub method: Method,
    /// Fixed-step methods: steps per undamped oscillation period.
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u32).range(4..))]
    pub steps_per_period: u32,
    /// Fixed-step methods: the step in seconds instead (checked against the stability limit).
    #[arg(long)]
    pub timestep: Option<f64>,
    /// Adaptive method: relative tolerance.
    #[arg(long, default_value_t = 1e-12)]
    pub rtol: f64,
    /// Bilateral contact: undamped periods to follow.
    #[arg(long, default_value_t = 3.0)]
    pub periods: f64,
}

/// `millimpact run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The case file (TOML).
    pub case: PathBuf,
    /// Integration settings.
    #[command(flatten)]
    pub integration: IntegrationArgs,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: Format,
    /// Write the trajectory (t, y, ẏ, forces, energy) to this CSV file.
    #[arg(long)]
    pub trajectory: Option<PathBuf>,
}

/// `millimpact sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// The case file (TOML); its own η or restitution is replaced by each swept value.
    pub case: PathBuf,
    /// Range of η as START:STOP:STEP, STOP included, all in [0, 1).
    #[arg(long)]
    pub loss_coefficient: String,
    /// Also draw COR against η, with the closed form, to this SVG file.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Integration settings.
    #[command(flatten)]
    pub integration: IntegrationArgs,
}

/// `millimpact verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// Folder of case files.
    #[arg(long, default_value = "cases")]
    pub cases: PathBuf,
    /// Folder of stored DEM-code references.
    #[arg(long, default_value = "reference")]
    pub reference: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: Format,
}

/// The DEM codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum CodeName {
    /// LIGGGHTS-PUBLIC.
    Liggghts,
    /// YADE.
    Yade,
    /// LAMMPS (GRANULAR package).
    Lammps,
}

impl CodeName {
    /// The driver name.
    pub fn name(self) -> &'static str {
        match self {
            CodeName::Liggghts => "liggghts",
            CodeName::Yade => "yade",
            CodeName::Lammps => "lammps",
        }
    }
}

/// `millimpact reference`.
#[derive(Debug, Args)]
pub struct ReferenceArgs {
    /// Which code.
    #[arg(long, value_enum)]
    pub code: CodeName,
    /// The case file (TOML).
    pub case: PathBuf,
    /// Steps per (estimated) contact time.
    #[arg(long, conflicts_with = "timestep")]
    pub steps_per_contact: Option<u32>,
    /// The code's time step in seconds instead.
    #[arg(long)]
    pub timestep: Option<f64>,
    /// Replace the case's η (to store references at several η).
    #[arg(long)]
    pub loss_coefficient: Option<f64>,
    /// Kill the code after this many seconds.
    #[arg(long, default_value_t = 300.0)]
    pub timeout: f64,
    /// Let the code cut off attractive contact force (LIGGGHTS limitForce on, LAMMPS
    /// limit_damping; YADE always does): the COR then rises above the target, to the clamped
    /// law's, which is reported as the expected COR.
    #[arg(long)]
    pub clamp: bool,
    /// Output format (table or json).
    #[arg(long, value_enum, default_value = "table")]
    pub format: Format,
    /// Store the result, with provenance, in `reference/<code>/<case>.json`.
    #[arg(long)]
    pub save: bool,
    /// Folder of stored references.
    #[arg(long, default_value = "reference")]
    pub reference: PathBuf,
}

/// `millimpact compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// Case files (default: the canonical ones in cases/).
    pub cases: Vec<PathBuf>,
    /// Run the codes now instead of reading reference/.
    #[arg(long)]
    pub live: bool,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: Format,
    /// Folder of stored references.
    #[arg(long, default_value = "reference")]
    pub reference: PathBuf,
    /// Kill a code after this many seconds (with --live).
    #[arg(long, default_value_t = 300.0)]
    pub timeout: f64,
}

/// `millimpact precision`.
#[derive(Debug, Args)]
pub struct PrecisionArgs {
    /// The case file (TOML).
    pub case: PathBuf,
    /// Methods to sweep (default: rk4, rk4-event, dopri5, verlet).
    #[arg(long, value_enum, num_args = 1.., value_delimiter = ',')]
    pub methods: Vec<Method>,
    /// DEM codes to sweep over their time step (default: none).
    #[arg(long, value_enum, num_args = 1.., value_delimiter = ',')]
    pub codes: Vec<CodeName>,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: Format,
    /// Write the work–precision diagram here (SVG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Timed repetitions per point (the median is reported).
    #[arg(long, default_value_t = 7)]
    pub repeats: u32,
}

/// `millimpact stability`.
#[derive(Debug, Args)]
pub struct StabilityArgs {
    /// Output format (table or json).
    #[arg(long, value_enum, default_value = "table")]
    pub format: Format,
}
