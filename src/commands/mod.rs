//! One file per subcommand: validated arguments → the library → an exporter. A command
//! returns its text and, for a check, its verdict; only `main` prints and exits.

mod benchmark;
mod calibrate;
mod compare;
mod deck;
mod merge;
mod mill;
mod precision;
mod probe;
mod reference;
mod report;
mod run;
mod stability;
mod sweep;
mod verify;

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use std::fmt::Display;

use crate::cli::{Cli, Command};
use millimpact::error::{Blame, CheckFailed, UserError};
use millimpact::output::files::write_atomic;
use millimpact::output::{Format, OutputError, Summary, export, table_at_width, table_width};

/// `summary` in `format` for standard output: on a terminal a table fits its width (or
/// `COLUMNS`, where that is set); in a pipe or a file, and in every other format, it is
/// written whole.
fn render<S: Summary>(summary: &S, format: Format) -> Result<String, OutputError> {
    // comfy-table asks the terminal for its width.
    let terminal = std::io::stdout()
        .is_terminal()
        .then(|| comfy_table::Table::new().width());
    let columns = std::env::var("COLUMNS").ok();
    match (format, table_width(terminal, columns.as_deref())) {
        (Format::Table, Some(width)) => table_at_width(summary, width),
        (format, _) => export(summary, format),
    }
}

/// A progress bar of `len` steps drawn with `template` on standard error; none when standard
/// error is not a terminal or `CI` is set.
fn progress_bar(len: u64, template: &str) -> Option<indicatif::ProgressBar> {
    if !std::io::stderr().is_terminal() || std::env::var_os("CI").is_some() {
        return None;
    }
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) = indicatif::ProgressStyle::with_template(template) {
        bar.set_style(style);
    }
    Some(bar)
}

/// Write the command's text; a closed pipe or a full disk is one line and exit 1, not a panic.
fn print(text: &str) -> Result<(), std::io::Error> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()
}

/// Run the parsed command line: dispatch the command, print its output and warnings, and map
/// a failure to its exit code (2 for bad input, 1 for a failed check or a run that failed).
pub(crate) fn run(cli: &Cli) -> ExitCode {
    // Ctrl-C or SIGTERM ends the DEM codes running now (their whole process groups) and removes
    // their scratch directories; a sweep installs its own handler, which keeps its finished rows.
    if !matches!(cli.command, Command::Sweep(_)) {
        let _ = ctrlc::set_handler(|| crate::codes::runner::stop_all_codes_and_exit(130));
    }
    match dispatch(&cli.command) {
        Ok(output) => {
            for warning in &output.warnings {
                eprintln!("warning: {warning}");
            }
            if let Err(error) = print(&output.text) {
                if error.kind() == std::io::ErrorKind::BrokenPipe {
                    // The reader has gone (`| head`): what it read is what it wanted.
                    return ExitCode::from(141);
                }
                eprintln!("error: writing standard output: {error}");
                return ExitCode::from(1);
            }
            match output.failure {
                Some(failure) => {
                    eprintln!("error: {failure}");
                    ExitCode::from(1)
                }
                None => ExitCode::SUCCESS,
            }
        }
        Err(failure) => {
            let (error, code) = (&failure.error, failure.exit_code());
            if code == 2 {
                eprintln!("error: {error}");
            } else {
                eprintln!("error: {error:#}");
            }
            ExitCode::from(code)
        }
    }
}

/// Why a command failed: the error with its chain of causes, and the exit code its type
/// stated ([`Blame::exit_code`]) when it became a failure. Only a type that implements
/// [`Blame`] becomes one, so an error type cannot reach `main` without stating its code.
#[derive(Debug)]
pub struct Failure {
    /// The error, with the context the command added.
    error: anyhow::Error,
    /// The exit code.
    code: u8,
}

impl<E: Blame + std::error::Error + Send + Sync + 'static> From<E> for Failure {
    fn from(error: E) -> Self {
        Failure {
            code: error.exit_code(),
            error: error.into(),
        }
    }
}

impl Failure {
    /// The exit code.
    pub fn exit_code(&self) -> u8 {
        self.code
    }
}

/// A command's result: a failure carries its exit code.
pub type Result<T, E = Failure> = std::result::Result<T, E>;

/// What a command says it was doing when it failed, the exit code kept.
pub trait Context<T> {
    /// Put `context` before the failure.
    fn context<C: Display + Send + Sync + 'static>(self, context: C) -> Result<T>;
    /// Put `context()` before the failure (made only if it failed).
    fn with_context<C: Display + Send + Sync + 'static>(
        self,
        context: impl FnOnce() -> C,
    ) -> Result<T>;
}

impl<T, E: Into<Failure>> Context<T> for std::result::Result<T, E> {
    fn context<C: Display + Send + Sync + 'static>(self, context: C) -> Result<T> {
        self.with_context(|| context)
    }

    fn with_context<C: Display + Send + Sync + 'static>(
        self,
        context: impl FnOnce() -> C,
    ) -> Result<T> {
        self.map_err(|e| {
            let Failure { error, code } = e.into();
            Failure {
                error: error.context(context()),
                code,
            }
        })
    }
}

/// What a command hands back to `main`: the text for standard output, and whether a check it
/// ran disagreed (the text is printed either way).
#[derive(Debug)]
pub struct CommandOutput {
    /// Standard output.
    pub text: String,
    /// The disagreement, if a check failed (exit 1).
    pub failure: Option<CheckFailed>,
    /// Warnings for standard error (they do not change the exit code).
    pub warnings: Vec<String>,
}

impl CommandOutput {
    fn passed(text: String) -> Self {
        CommandOutput {
            text,
            failure: None,
            warnings: Vec::new(),
        }
    }
}

/// The folder of shipped data (`cases`, `reference`) a command reads: the one given with
/// `option`, else `./<name>` where the command runs, else the one in the repository this build
/// was made from (and a warning saying so), else a user error naming both places looked in.
fn shipped_folder(
    given: Option<&Path>,
    option: &str,
    name: &str,
    warnings: &mut Vec<String>,
) -> Result<PathBuf> {
    if let Some(folder) = given {
        if !folder.is_dir() {
            return Err(UserError::argument(
                option,
                folder.display(),
                format!("an existing folder (of {name} files)"),
            )
            .into());
        }
        return Ok(folder.to_path_buf());
    }
    let here = Path::new(name);
    if here.is_dir() {
        return Ok(here.to_path_buf());
    }
    let repository = Path::new(env!("CARGO_MANIFEST_DIR")).join(name);
    if repository.is_dir() {
        warnings.push(format!(
            "no `{name}/` here: reading {} (the repository this build was made from)",
            repository.display()
        ));
        return Ok(repository);
    }
    Err(UserError::argument(
        option,
        "(not given)",
        format!(
            "a folder; there is no `{name}/` here nor at {}: run from the repository folder or give {option} DIR",
            repository.display()
        ),
    )
    .into())
}

/// The stored references' folder for a command that reads them unless it runs the codes
/// `live` (then the folder is not read, and is not looked for).
fn reference_folder(
    given: Option<&Path>,
    live: bool,
    warnings: &mut Vec<String>,
) -> Result<PathBuf> {
    if live {
        return Ok(given.unwrap_or(Path::new("reference")).to_path_buf());
    }
    shipped_folder(given, "--reference", "reference", warnings)
}

/// The cases at `paths`, or the canonical ones (as shipped in cases/ and built in) when none
/// is given.
fn cases_or_canonical(
    paths: &[PathBuf],
    command: &str,
) -> Result<Vec<millimpact::model::case::Case>> {
    if paths.is_empty() {
        return Ok(millimpact::model::shipped::canonical_cases()?);
    }
    // The DEM codes run normal impacts only: an oblique case is refused before any work.
    let load = |p: &PathBuf| {
        let case = millimpact::model::case::Case::load(p)?;
        case.refuse_oblique(command).map(|()| case)
    };
    Ok(paths.iter().map(load).collect::<Result<_, _>>()?)
}

/// Run one parsed command.
pub fn dispatch(command: &Command) -> Result<CommandOutput> {
    match command {
        Command::Run(args) => run::run(args),
        Command::Sweep(args) => sweep::sweep(args),
        Command::Verify(args) => verify::verify(args),
        Command::Reference(args) => reference::reference(args),
        Command::Compare(args) => compare::compare(args),
        Command::Precision(args) => precision::precision(args),
        Command::Stability(args) => stability::stability(args),
        Command::Calibrate(args) => calibrate::calibrate(args),
        Command::Report(args) => report::report(args),
        Command::Merge(args) => merge::merge(args),
        Command::Probe(args) => probe::probe(args),
        Command::Benchmark(args) => benchmark::benchmark(args),
        Command::Deck(args) => deck::deck(args),
        Command::Mill(args) => mill::mill(args),
    }
}

/// Refuse, before any work, an output path that is not a new or ordinary file, or that is one
/// of the command's inputs (exit 2).
fn check_output(option: &'static str, path: Option<&Path>, inputs: &[&Path]) -> Result<()> {
    let Some(path) = path else { return Ok(()) };
    millimpact::output::files::check_output_path(option, path, inputs).map_err(|e| {
        millimpact::error::UserError::argument(option, path.display(), e.reason).into()
    })
}

/// Write a file a command was asked for (`what` names it in the error).
fn write_output(path: &Path, bytes: &[u8], what: &str) -> Result<()> {
    write_atomic(path, bytes).with_context(|| format!("writing the {what} to {}", path.display()))
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use millimpact::analysis::compare::CompareError;
    use millimpact::analysis::deck::DeckCheckError;
    use millimpact::analysis::report::ReportError;
    use millimpact::analysis::run::RunError;
    use millimpact::analysis::store::StoreError;
    use millimpact::analysis::sweep::SweepError;
    use millimpact::model::case::CaseError;
    use millimpact::solve::SolveError;

    use super::*;

    fn unstable() -> SolveError {
        SolveError::Unstable {
            method: "rk4",
            timestep: 2e-4,
            omega: 1e5,
            omega_dt: 20.0,
            limit: 2.78,
            max_timestep: 2.78e-5,
        }
    }

    fn unsolvable() -> RunError {
        RunError::Unsolvable {
            case: PathBuf::from("cases/ball_plate.toml"),
            source: unstable(),
        }
    }

    fn no_reference_folder() -> StoreError {
        StoreError::NoReferenceFolder {
            folder: PathBuf::from("no-such-store"),
        }
    }

    /// A user error exits 2 however deep a library error wraps it, with or without the
    /// command's context; every other failure exits 1.
    #[test]
    fn the_exit_code_sees_a_user_error_through_every_wrapper() {
        let user: Vec<Failure> = vec![
            UserError::argument("--rtol", 0, "a positive number").into(),
            CaseError::new("a.toml", "ball.radius", "-1", "a positive number").into(),
            unsolvable().into(),
            SweepError::from(unsolvable()).into(),
            SweepError::from(CaseError::new("s.toml", "axes", "x", "a table")).into(),
            no_reference_folder().into(),
            StoreError::from(unsolvable()).into(),
            CompareError::from(no_reference_folder()).into(),
            ReportError::from(CompareError::from(no_reference_folder())).into(),
            ReportError::from(no_reference_folder()).into(),
            Err::<(), _>(SweepError::from(no_reference_folder()))
                .context("sweeping")
                .unwrap_err(),
            Err::<(), _>(ReportError::from(no_reference_folder()))
                .context("building the report")
                .unwrap_err(),
            DeckCheckError::from(UserError::argument(
                "--impact-velocity",
                "1e9 m/s",
                "a speed",
            ))
            .into(),
        ];
        for failure in &user {
            assert_eq!(failure.exit_code(), 2, "{:#}", failure.error);
        }
        let failed = RunError::Failed {
            case: PathBuf::from("cases/ball_plate.toml"),
            source: SolveError::StepBudget {
                method: "rk4",
                steps: 10,
            },
        };
        let other: Vec<Failure> = vec![
            SweepError::from(failed).into(),
            StoreError::Read {
                path: PathBuf::from("reference/lammps/ball_plate.json"),
                source: std::io::Error::from(std::io::ErrorKind::PermissionDenied),
            }
            .into(),
            CheckFailed("2 checks disagree".into()).into(),
            DeckCheckError::NoReader(millimpact::codes::CodeName::Lammps).into(),
        ];
        for failure in &other {
            assert_eq!(failure.exit_code(), 1, "{:#}", failure.error);
        }
    }
}
