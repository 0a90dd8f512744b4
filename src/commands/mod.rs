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

use anyhow::{Context, Result};

use crate::cli::{Cli, Command};
use millimpact::analysis::benchmark::BenchmarkError;
use millimpact::analysis::compare::CompareError;
use millimpact::analysis::deck::DeckCheckError;
use millimpact::analysis::mill::MillError;
use millimpact::analysis::report::ReportError;
use millimpact::analysis::run::RunError;
use millimpact::analysis::store::StoreError;
use millimpact::analysis::sweep::SweepError;
use millimpact::error::{Blame, CheckFailed, UserError};
use millimpact::model::case::CaseError;
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
        Err(error) => {
            let code = exit_code(&error);
            if code == 2 {
                eprintln!("error: {error}");
            } else {
                eprintln!("error: {error:#}");
            }
            ExitCode::from(code)
        }
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

/// The exit code of a failed command: 2 for bad input, 1 for everything else (a check that
/// disagreed among them). Each error in the failure's chain of causes is asked whether it is
/// the user's ([`Blame`]): a library error that wraps a user error says so, wherever the
/// command's context put it.
pub fn exit_code(error: &anyhow::Error) -> u8 {
    if !error.is::<CheckFailed>() && error.chain().any(is_user_error) {
        2
    } else {
        1
    }
}

/// Whether one error of a chain is the user's: asked of every library error type that can
/// hold a user error (a type missing here would make its user errors exit 1; the
/// exit-code tests of each type below keep the list whole).
fn is_user_error(cause: &(dyn std::error::Error + 'static)) -> bool {
    macro_rules! ask {
        ($($error:ty),+ $(,)?) => {
            $(
                if let Some(e) = cause.downcast_ref::<$error>() {
                    return e.is_user_error();
                }
            )+
        };
    }
    ask!(
        UserError,
        CaseError,
        RunError,
        StoreError,
        SweepError,
        CompareError,
        ReportError,
        BenchmarkError,
        DeckCheckError,
        MillError,
    );
    false
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

    use anyhow::Context;
    use millimpact::analysis::run::RunError;
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
        let user: Vec<anyhow::Error> = vec![
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
            anyhow::Error::from(SweepError::from(no_reference_folder())).context("sweeping"),
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
        for error in &user {
            assert_eq!(exit_code(error), 2, "{error:#}");
        }
        let failed = RunError::Failed {
            case: PathBuf::from("cases/ball_plate.toml"),
            source: SolveError::StepBudget {
                method: "rk4",
                steps: 10,
            },
        };
        let other: Vec<anyhow::Error> = vec![
            SweepError::from(failed).into(),
            StoreError::Read {
                path: PathBuf::from("reference/lammps/ball_plate.json"),
                source: std::io::Error::from(std::io::ErrorKind::PermissionDenied),
            }
            .into(),
            CheckFailed("2 checks disagree".into()).into(),
            DeckCheckError::NoReader(millimpact::codes::CodeName::Lammps).into(),
        ];
        for error in &other {
            assert_eq!(exit_code(error), 1, "{error:#}");
        }
    }
}
