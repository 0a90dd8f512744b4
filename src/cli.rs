//! The command line: its definitions (clap, here alone), and [`parse`], which reads it or
//! reports a usage error in one line. The choices of `--method`, `--code`
//! and `--format` come from the registries that own them; values are checked by typed parsers
//! here, so that a bad value is refused before any work, in one line.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand};

use millimpact::codes::CodeName;
use millimpact::output::Format;
use millimpact::solve::Method;

/// Parse the command line; a usage error is reported on one line (exit 2), like every other
/// bad input, while help and version print as clap lays them out.
pub(crate) fn parse() -> Result<Cli, ExitCode> {
    use clap::error::ErrorKind;
    match Cli::try_parse() {
        Ok(cli) => Ok(cli),
        Err(error) => match error.kind() {
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => error.exit(),
            _ => {
                let text = error.render().to_string();
                let line: Vec<&str> = text
                    .lines()
                    .map(str::trim)
                    .filter(|l| {
                        !l.is_empty()
                            && !l.starts_with("Usage:")
                            && !l.starts_with("For more information")
                    })
                    .collect();
                eprintln!("{} (see millimpact --help)", line.join(" "));
                Err(ExitCode::from(2))
            }
        },
    }
}

/// millimpact: checks the contact law of grinding bodies against exact closed forms and
/// against the DEM codes LIGGGHTS, YADE, LAMMPS and Kratos.
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
    /// A grid sweep from a sweep file (rows as they finish), or one impact per loss
    /// coefficient over a range (the paper's Figure 3).
    Sweep(SweepArgs),
    /// Every case in cases/ by every method against the closed forms, and the stored DEM-code
    /// references; exit 1 if anything disagrees beyond its stated tolerance.
    Verify(VerifyArgs),
    /// Run one case in a DEM code on the equivalent setup.
    Reference(ReferenceArgs),
    /// Each case by each source (paper law, DEM codes, their own laws, elastic Hertz), side by
    /// side, with the differences attributed to model and integration.
    Compare(CompareArgs),
    /// Error against cost for each method and DEM code: the work–precision picture.
    Precision(PrecisionArgs),
    /// A built-in grid of stiff and extreme cases by every method.
    Stability(StabilityArgs),
    /// From a measured COR to η, the absorbed energy, and a card per DEM code with the
    /// settings that realise that COR.
    Calibrate(CalibrateArgs),
    /// A self-contained report (index.html, index.md, and the CSV and JSON behind every
    /// figure and table) from the stored references, or the codes run now.
    Report(ReportArgs),
    /// Join the shard outputs of one sweep into one file.
    Merge(MergeArgs),
    /// Check a user's own DEM setup: each pair of particle types (and each type against each
    /// wall) as one normal impact, run in the user's code with the user's contact lines and
    /// time step, against the COR entered and the code's own law.
    Deck(DeckArgs),
    /// Measure a build's conventions with short probe runs (LAMMPS builds): each item with
    /// the measured number, the value each hypothesis predicts, and the verdict.
    Probe(ProbeArgs),
    /// A published benchmark (Chung & Ooi's tests 1–8) by the exact solution, the paper's law,
    /// the tangential solver and each code asked for, every figure against its published value
    /// or closed form.
    Benchmark(BenchmarkArgs),
    /// Run a user's whole LIGGGHTS mill deck twice at once: as written and with every contact
    /// line switched between damped Hertz and the paper's law at each pair's COR; the power
    /// draw, kinetic energy, collision spectra and contacts at rest under each, with the
    /// difference and its standard error.
    Mill(MillArgs),
}

/// The benchmarks `millimpact benchmark` runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchmarkName {
    /// Chung & Ooi (2011), tests 1–3: two spheres head on, a sphere on a rigid plane, the COR
    /// set from 0.2 to 1.0; tests 4–8: oblique and spinning impacts on a plane and between two
    /// spheres.
    ChungOoi,
}

/// `millimpact benchmark`.
#[derive(Debug, Args)]
pub struct BenchmarkArgs {
    /// The benchmark.
    #[arg(value_enum)]
    pub benchmark: BenchmarkName,
    /// A DEM code to run now, on its own rigid plane, instead of the stored runs; repeat for
    /// several.
    #[arg(long = "code", value_parser = code_parser())]
    pub codes: Vec<CodeName>,
    /// Run every code build now instead of reading the stored runs (with --code: those codes).
    #[arg(long)]
    pub live: bool,
    /// Folder of stored DEM-code references, whose `benchmarks/` holds the benchmark's runs
    /// [default: ./reference, else the `reference/` of the repository this build was made from].
    #[arg(long, conflicts_with_all = ["live", "codes"])]
    pub reference: Option<PathBuf>,
    /// Steps per elastic contact time of each code's run now (the stored runs are at 1000).
    #[arg(long, default_value = "1000", value_parser = clap::value_parser!(u32).range(10..=10_000_000))]
    pub steps_per_contact: u32,
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
    /// Kill a code after this many seconds.
    #[arg(long, default_value = "300", value_parser = parse_timeout)]
    pub timeout: f64,
    /// Write test 3's COR chart into this folder (it must exist): `cor-chart-<case>.svg` and
    /// `.csv` per material, every source's COR against the COR set, and `cor-chart-typed.svg`
    /// and `.csv`, each code's law with the COR typed in directly; and one chart per test 4–8,
    /// `oblique-chart-test-<N>.svg` and `.csv`.
    #[arg(long, value_name = "DIR")]
    pub chart: Option<PathBuf>,
}

fn method_parser() -> impl TypedValueParser<Value = Method> {
    PossibleValuesParser::new(Method::names())
        .map(|name| Method::from_name(&name).expect("a listed method"))
}

fn code_parser() -> impl TypedValueParser<Value = CodeName> {
    PossibleValuesParser::new(CodeName::names())
        .map(|name| CodeName::from_name(&name).expect("a listed code"))
}

fn format_parser() -> impl TypedValueParser<Value = Format> {
    PossibleValuesParser::new(Format::ALL.map(Format::name))
        .map(|name| Format::from_name(&name).expect("a listed format"))
}

/// Fewest steps per contact a DEM code is run at: below it the contact is a handful of steps and
/// its figures mean nothing (at 20 the COR is off by 7e-3; at 1 a code reports a COR of 18.7).
pub const MIN_STEPS_PER_CONTACT: u32 = 20;

/// Most undamped periods a bilateral run follows (each costs ~1000 steps).
pub const MAX_PERIODS: f64 = 1000.0;

/// `text` as a number, or why not (`what`: a number, or a number of seconds).
fn number(text: &str, what: &str) -> Result<f64, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("`{text}` is not {what}"))
}

fn parse_periods(text: &str) -> Result<f64, String> {
    let periods = number(text, "a number")?;
    if periods.is_finite() && periods > 0.0 && periods <= MAX_PERIODS {
        Ok(periods)
    } else {
        Err(format!("must be a number of periods in (0, {MAX_PERIODS}]"))
    }
}

fn parse_rtol(text: &str) -> Result<f64, String> {
    let rtol = number(text, "a number")?;
    let min = millimpact::analysis::run::MIN_RTOL;
    if (min..1.0).contains(&rtol) {
        Ok(rtol)
    } else {
        Err(format!(
            "must be a relative tolerance in [{min:e}, 1) (the spacing of doubles near 1 and up)"
        ))
    }
}

/// A COR tolerance: a number the choice of a method can meet.
fn parse_tolerance(text: &str) -> Result<f64, String> {
    let tolerance = number(text, "a number")?;
    millimpact::analysis::precision::choice::choose(tolerance)
        .map(|_| tolerance)
        .map_err(|e| format!("must be {e}"))
}

/// Largest time limit for an external code, s (a day): beyond it a run is not a check.
pub const MAX_TIMEOUT: f64 = 86_400.0;

/// A time limit in seconds: finite, above zero, at most [`MAX_TIMEOUT`].
fn parse_timeout(text: &str) -> Result<f64, String> {
    let seconds = number(text, "a number of seconds")?;
    if seconds.is_finite() && seconds > 0.0 && seconds <= MAX_TIMEOUT {
        Ok(seconds)
    } else {
        Err(format!("must be a number of seconds in (0, {MAX_TIMEOUT}]"))
    }
}

/// Integration settings shared by the commands that integrate.
#[derive(Debug, Args, Clone)]
pub struct IntegrationArgs {
    /// Integration method.
    #[arg(long, value_parser = method_parser(), default_value = "rk4-event")]
    pub method: Method,
    /// Fixed-step methods: steps per undamped oscillation period [default: 1000].
    #[arg(long, value_parser = clap::value_parser!(u32).range(
        i64::from(millimpact::analysis::run::MIN_STEPS_PER_PERIOD)
            ..=i64::from(millimpact::analysis::run::MAX_STEPS_PER_PERIOD)
    ))]
    pub steps_per_period: Option<u32>,
    /// Fixed-step methods: the step in seconds instead (checked against the stability limit).
    #[arg(long, conflicts_with = "steps_per_period")]
    pub timestep: Option<f64>,
    /// Adaptive method: relative tolerance, in [2.2e-16, 1) [default: 1e-12].
    #[arg(long, value_parser = parse_rtol)]
    pub rtol: Option<f64>,
    /// Bilateral contact: undamped periods to follow (at most 1000).
    #[arg(long, default_value_t = 3.0, value_parser = parse_periods)]
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
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
    /// Write the trajectory (t, y, ẏ, forces, energy) to this CSV file.
    #[arg(long)]
    pub trajectory: Option<PathBuf>,
}

/// `millimpact sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// A sweep file (TOML with a base case and [axes]), or a case file swept over
    /// --loss-coefficient.
    pub case: PathBuf,
    /// With a case file: range of η as START:STOP:STEP, STOP included, all in [0, 1).
    #[arg(long)]
    pub loss_coefficient: Option<String>,
    /// Also draw COR against η, with the closed form, to this SVG file.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Integration settings.
    #[command(flatten)]
    pub integration: IntegrationArgs,
    /// With a case file: a relative COR error to meet instead of a method and resolution; the
    /// cheapest method and resolution known to meet it is chosen and named on standard error
    /// (a sweep file says `tolerance = ...`).
    #[arg(long, value_parser = parse_tolerance, conflicts_with_all = ["method", "steps_per_period", "timestep", "rtol"])]
    pub tolerance: Option<f64>,
    /// Output format (a sweep file's rows: csv or jsonl).
    #[arg(long, value_parser = PossibleValuesParser::new(["table", "json", "csv", "markdown", "jsonl"]), default_value = "csv")]
    pub format: String,
    /// Sweep file: append rows to this file as they finish (standard output otherwise).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Sweep file: continue --out: keep the points computed there (matched by their
    /// parameters), run the failed and missing ones again.
    #[arg(long, requires = "out")]
    pub resume: bool,
    /// Sweep file: exit 0 even when points failed (their rows hold the errors; exit 1
    /// otherwise).
    #[arg(long)]
    pub allow_failures: bool,
    /// Worker threads for our methods and (sweep file) most live DEM-code processes [default:
    /// the number of cores].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub jobs: Option<u32>,
    /// Sweep file: run only the K-th of N deterministic slices of the grid (K/N, 1-based).
    #[arg(long, value_parser = parse_shard)]
    pub shard: Option<(usize, usize)>,
    /// Sweep file: kill a DEM-code process after this many seconds.
    #[arg(long, default_value = "300", value_parser = parse_timeout)]
    pub timeout: f64,
    /// Sweep file: most impacts per DEM-code process (1: one process per impact).
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub batch: u32,
}

/// `K/N` with 1 <= K <= N.
fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let parsed = text
        .split_once('/')
        .and_then(|(k, n)| Some((k.trim().parse().ok()?, n.trim().parse().ok()?)));
    match parsed {
        Some((k, n)) if k >= 1 && k <= n => Ok((k, n)),
        _ => Err(format!("`{text}` is not K/N with 1 <= K <= N")),
    }
}

/// `millimpact merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The merged output.
    pub out: PathBuf,
    /// Shard outputs of one sweep (`sweep --shard K/N --out ...`).
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
}

/// `millimpact verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// Folder of case files [default: ./cases, else the `cases/` of the repository this build
    /// was made from].
    #[arg(long)]
    pub cases: Option<PathBuf>,
    /// Folder of stored DEM-code references [default: ./reference, else the `reference/` of the
    /// repository this build was made from].
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
}

/// `millimpact probe`.
#[derive(Debug, Args)]
pub struct ProbeArgs {
    /// Which build.
    #[arg(long, value_parser = code_parser())]
    pub code: CodeName,
    /// Probe this executable instead of the build's own (run as it is, with no environment
    /// added).
    #[arg(long)]
    pub binary: Option<PathBuf>,
    /// Probe the build again even if a probe of it is kept in the cache folder (see
    /// `MILLIMPACT_CACHE_DIR`), and keep the new one.
    #[arg(long)]
    pub refresh: bool,
    /// Output format (markdown gives the table kept in `reference/<code>/CONVENTIONS.md`).
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
}

/// `millimpact reference`.
#[derive(Debug, Args)]
pub struct ReferenceArgs {
    /// Which code.
    #[arg(long, value_parser = code_parser())]
    pub code: CodeName,
    /// The case file (TOML).
    pub case: PathBuf,
    /// Steps per (estimated) contact time.
    #[arg(long, conflicts_with = "timestep")]
    #[arg(value_parser = clap::value_parser!(u32).range(i64::from(MIN_STEPS_PER_CONTACT)..=10_000_000))]
    pub steps_per_contact: Option<u32>,
    /// The code's time step in seconds instead.
    #[arg(long)]
    pub timestep: Option<f64>,
    /// Replace the case's η (to store references at several η).
    #[arg(long)]
    pub loss_coefficient: Option<f64>,
    /// Kill the code after this many seconds.
    #[arg(long, default_value = "300", value_parser = parse_timeout)]
    pub timeout: f64,
    /// Let the code cut off attractive contact force (LIGGGHTS limitForce on, LAMMPS
    /// limit_damping; YADE always does): the COR then rises above the target, to the clamped
    /// law's, which is reported as the expected COR.
    #[arg(long)]
    pub clamp: bool,
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
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
    /// Case files [default: the canonical ones, as shipped in cases/ and built in].
    pub cases: Vec<PathBuf>,
    /// Run the codes now instead of reading reference/.
    #[arg(long)]
    pub live: bool,
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
    /// Folder of stored references [default: ./reference, else the `reference/` of the
    /// repository this build was made from].
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Kill a code after this many seconds (with --live).
    #[arg(long, default_value = "300", value_parser = parse_timeout)]
    pub timeout: f64,
}

/// `millimpact precision`.
#[derive(Debug, Args)]
pub struct PrecisionArgs {
    /// The case file (TOML).
    pub case: PathBuf,
    /// Methods to sweep (default: every integrating method).
    #[arg(long, value_parser = method_parser(), num_args = 1.., value_delimiter = ',')]
    pub methods: Vec<Method>,
    /// DEM codes to sweep over their time step (default: none).
    #[arg(long, value_parser = code_parser(), num_args = 1.., value_delimiter = ',')]
    pub codes: Vec<CodeName>,
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
    /// Write the work–precision diagram here (SVG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Timed repetitions per point (the median is reported).
    #[arg(long, default_value_t = 7, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub repeats: u32,
}

/// `millimpact stability`.
#[derive(Debug, Args)]
pub struct StabilityArgs {
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
}

/// A COR: a number in (0, 1].
fn parse_cor(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(e) if e > 0.0 && e <= 1.0 => Ok(e),
        _ => Err(format!(
            "`{text}` is not a COR; allowed: a number in (0, 1]"
        )),
    }
}

/// A measured COR range `A:B`, 0 < A < B <= 1.
fn parse_cor_range(text: &str) -> Result<(f64, f64), String> {
    let allowed = "allowed: A:B with 0 < A < B <= 1";
    let (a, b) = text
        .split_once(':')
        .ok_or_else(|| format!("`{text}` is not a range; {allowed}"))?;
    match (parse_cor(a), parse_cor(b)) {
        (Ok(a), Ok(b)) if a < b => Ok((a, b)),
        _ => Err(format!("`{text}`: {allowed}")),
    }
}

/// A positive, finite number.
fn parse_positive(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x > 0.0 && x.is_finite() => Ok(x),
        _ => Err(format!("`{text}`: allowed: a positive number")),
    }
}

/// Impact speeds given at once: one, or `A:B:N`, N log-spaced from A to B, m/s.
#[derive(Clone, Debug, PartialEq)]
pub struct Speeds(pub Vec<f64>);

/// Most speeds one `A:B:N` may ask for: each is one run per pair.
const MAX_SPEEDS: u32 = 1000;

/// `V` or `A:B:N`: `A` and `B` positive speeds, `B > A`, `2 <= N <= 1000`; the speeds are
/// `A (B/A)^(i/(N−1))`, the last exactly `B`.
fn parse_speeds(text: &str) -> Result<Speeds, String> {
    let parts: Vec<&str> = text.split(':').collect();
    let [a, b, n] = parts.as_slice() else {
        return match parts.as_slice() {
            [one] => parse_positive(one)
                .map(|v| Speeds(vec![v]))
                .map_err(|_| format!("`{text}`: allowed: a positive speed, m/s, or A:B:N")),
            _ => Err(format!(
                "`{text}`: allowed: a positive speed, m/s, or A:B:N (N speeds log-spaced from A to B m/s)"
            )),
        };
    };
    let speed = |what: &str, part: &str| {
        parse_positive(part).map_err(|_| {
            format!("`{text}`: {what} of A:B:N is `{part}`; allowed: a positive speed, m/s")
        })
    };
    let (low, high) = (speed("A", a)?, speed("B", b)?);
    if high <= low {
        return Err(format!(
            "`{text}`: B = {high} m/s is not above A = {low} m/s; allowed: A < B"
        ));
    }
    let count: u32 = n
        .trim()
        .parse()
        .ok()
        .filter(|k| (2..=MAX_SPEEDS).contains(k))
        .ok_or_else(|| {
            format!("`{text}`: N of A:B:N is `{n}`; allowed: a whole number from 2 to {MAX_SPEEDS}")
        })?;
    let last = f64::from(count - 1);
    Ok(Speeds(
        (0..count)
            .map(|i| {
                if i == count - 1 {
                    high
                } else {
                    low * (high / low).powf(f64::from(i) / last)
                }
            })
            .collect(),
    ))
}

/// `millimpact calibrate`.
#[derive(Debug, Args)]
pub struct CalibrateArgs {
    /// The case file (TOML) [default: cases/ball_plate.toml].
    pub case: Option<PathBuf>,
    /// The COR to realise.
    #[arg(long, value_parser = parse_cor, required_unless_present = "cor_range", conflicts_with = "cor_range")]
    pub cor: Option<f64>,
    /// A measured COR range `A:B`: cards for both ends.
    #[arg(long, value_parser = parse_cor_range)]
    pub cor_range: Option<(f64, f64)>,
    /// The codes' time step, s, the cards predict for [default: elastic contact time / 1000].
    #[arg(long, value_parser = parse_positive)]
    pub timestep: Option<f64>,
    /// Relative COR offset the recommended time step keeps.
    #[arg(long, default_value = "1e-3", value_parser = parse_positive)]
    pub tolerance: f64,
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
}

/// `millimpact report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Case files [default: the canonical ones, as shipped in cases/ and built in].
    pub cases: Vec<PathBuf>,
    /// Folder to write the report into: a new or empty one, or an earlier report's (replaced
    /// whole); a folder of other files is refused.
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// Run the codes now instead of reading reference/.
    #[arg(long)]
    pub live: bool,
    /// Folder of stored references [default: ./reference, else the `reference/` of the
    /// repository this build was made from].
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Kill a code after this many seconds (with --live, and the decks' runs).
    #[arg(long, default_value = "300", value_parser = parse_timeout)]
    pub timeout: f64,
    /// A deck of your own to check as `deck` checks it (its code runs now), in a part of its
    /// own; repeat for several.
    #[arg(long = "deck", value_name = "FILE")]
    pub decks: Vec<PathBuf>,
    /// Impact speed for the decks, m/s; repeat for several [default: as `deck`].
    #[arg(long = "deck-impact-velocity", value_name = "V", value_parser = parse_positive)]
    pub deck_impact_velocity: Vec<f64>,
    /// A particle the decks compute at run time, `TYPE:RADIUS:DENSITY`, as `deck --particle`.
    #[arg(long = "deck-particle", value_name = "TYPE:RADIUS:DENSITY", value_parser = parse_particle)]
    pub deck_particle: Vec<millimpact::codes::deck::GivenParticle>,
    /// A variable defined before each deck is read, `NAME=VALUE`, as `deck --var`.
    #[arg(long = "deck-var", value_name = "NAME=VALUE", value_parser = parse_variable)]
    pub deck_variables: Vec<(String, String)>,
    /// A LIGGGHTS mill deck of your own to run under both laws as `mill` runs it (its code runs
    /// now), in a part of its own; repeat for several.
    #[arg(long = "mill", value_name = "FILE")]
    pub mills: Vec<PathBuf>,
    /// Rotation time to run of each mill, s, as `mill --time` [default: the deck's own].
    #[arg(long = "mill-time", value_name = "SECONDS", value_parser = parse_positive)]
    pub mill_time: Option<f64>,
    /// Runs per law of each mill, as `mill --seeds`.
    #[arg(long = "mill-seeds", value_name = "N", default_value = "1")]
    pub mill_seeds: usize,
    /// Kill a mill's run after this many seconds, as `mill --timeout`.
    #[arg(long = "mill-timeout", value_name = "SECONDS", default_value = "3600", value_parser = parse_timeout)]
    pub mill_timeout: f64,
}

/// `TYPE:RADIUS:DENSITY`: a particle size and density for a deck that computes them.
fn parse_particle(text: &str) -> Result<millimpact::codes::deck::GivenParticle, String> {
    let allowed = "allowed: TYPE:RADIUS:DENSITY, a whole type (an atom type from 1, a YADE O.materials id from 0), radius (m) and density (kg/m³) positive";
    let parts: Vec<&str> = text.split(':').collect();
    let [t, r, rho] = parts[..] else {
        return Err(format!("`{text}`: {allowed}"));
    };
    match (
        t.trim().parse::<u32>(),
        parse_positive(r),
        parse_positive(rho),
    ) {
        (Ok(type_id), Ok(radius), Ok(density)) => Ok(millimpact::codes::deck::GivenParticle {
            type_id,
            radius,
            density,
        }),
        _ => Err(format!("`{text}`: {allowed}")),
    }
}

/// `NAME=VALUE`: a variable defined before the deck is read.
fn parse_variable(text: &str) -> Result<(String, String), String> {
    match text.split_once('=') {
        Some((name, value))
            if !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') =>
        {
            Ok((name.to_string(), value.to_string()))
        }
        _ => Err(format!(
            "`{text}`: allowed: NAME=VALUE, NAME of letters, digits and _"
        )),
    }
}

/// `millimpact deck`.
#[derive(Debug, Args)]
pub struct DeckArgs {
    /// The deck: a LIGGGHTS or LAMMPS input script, a Kratos MaterialsDEM.json or
    /// ProjectParametersDEM.json, or a YADE Python script.
    pub deck: PathBuf,
    /// Impact speed, m/s, or `A:B:N`, N speeds log-spaced from A to B m/s (the COR against
    /// speed); repeat for several [default: half, once and twice a representative speed: the
    /// deck's own, else 2 m/s].
    #[arg(long = "impact-velocity", value_name = "V|A:B:N", value_parser = parse_speeds)]
    pub impact_velocity: Vec<Speeds>,
    /// The code (build) that reads and runs the deck [default: the first whose input it is].
    #[arg(long, value_parser = code_parser())]
    pub code: Option<CodeName>,
    /// A particle the deck computes at run time, `TYPE:RADIUS:DENSITY` (m, kg/m³; Kratos: TYPE
    /// is the material id); repeat for several; it replaces the deck's own sizes of that type.
    #[arg(long, value_parser = parse_particle)]
    pub particle: Vec<millimpact::codes::deck::GivenParticle>,
    /// A variable defined before the deck is read, `NAME=VALUE` (as `-var NAME VALUE`).
    #[arg(long = "var", value_parser = parse_variable)]
    pub variables: Vec<(String, String)>,
    /// Kill a code after this many seconds.
    #[arg(long, default_value = "300", value_parser = parse_timeout)]
    pub timeout: f64,
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
}

/// `millimpact mill`.
#[derive(Debug, Args)]
pub struct MillArgs {
    /// The deck: a LIGGGHTS input script with a drum turned by `fix move/mesh … rotate` and a
    /// `run` after it (model hertz or model paper).
    pub deck: PathBuf,
    /// The build that runs the damped-Hertz runs (the paper's law always runs in
    /// liggghts-paper).
    #[arg(long, value_parser = code_parser(), default_value = "liggghts")]
    pub code: CodeName,
    /// Rotation time to run, s [default: the deck's own runs after the fix move/mesh].
    #[arg(long, value_parser = parse_positive)]
    pub time: Option<f64>,
    /// Runs per law, each with its own insertion seeds (1: the deck's own seeds).
    #[arg(long, default_value = "1")]
    pub seeds: usize,
    /// Rotation time left out of the power and energy means, s [default: one revolution, or
    /// half the rotation if shorter].
    #[arg(long)]
    pub transient: Option<f64>,
    /// Rotation time at the end over which contacts are recorded for the spectra, s (0: none)
    /// [default: 0.1 s, or half the rotation if that is shorter].
    #[arg(long = "spectra-time")]
    pub spectra_time: Option<f64>,
    /// Record contacts every this many steps.
    #[arg(long = "contact-every", default_value_t = millimpact::analysis::mill::DEFAULT_CONTACT_EVERY)]
    pub contact_every: u64,
    /// Kill a run after this many seconds.
    #[arg(long, default_value = "3600", value_parser = parse_timeout)]
    pub timeout: f64,
    /// Keep every run's folder (its input, log and the files it wrote) in this folder
    /// [default: a run's folder is removed once read, kept only when the run fails].
    #[arg(long, value_name = "DIR")]
    pub keep: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_parser = format_parser(), default_value = "table")]
    pub format: Format,
}
