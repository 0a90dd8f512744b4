//! One file per subcommand: validated arguments → the library → an exporter. A command
//! returns its text and, for a check, its verdict; only `main` prints and exits.

mod calibrate;
mod compare;
mod deck;
mod merge;
mod precision;
mod probe;
mod reference;
mod report;
mod run;
mod stability;
mod sweep;
mod verify;

use std::path::Path;

use anyhow::{Context, Result};

use crate::cli::Command;
use millimpact::error::CheckFailed;
use millimpact::output::files::write_atomic;

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
        Command::Deck(args) => deck::deck(args),
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
