use std::process::ExitCode;

use clap::Parser;
use millimpact::app::{self, CheckFailed, UserError};
use millimpact::case::CaseError;
use millimpact::cli::{Cli, Command};

/// Parse the command line; a usage error is reported on one line (exit 2), like every other
/// bad input, while help and version print as clap lays them out.
fn parse() -> Result<Cli, ExitCode> {
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

fn main() -> ExitCode {
    let cli = match parse() {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    let result = match &cli.command {
        Command::Run(args) => app::run(args),
        Command::Sweep(args) => app::sweep(args),
        Command::Verify(args) => app::verify(args),
        Command::Reference(args) => millimpact::references::reference_command(args),
        Command::Compare(args) => millimpact::compare::compare_command(args),
        Command::Precision(args) => millimpact::precision::precision_command(args),
        Command::Stability(args) => millimpact::stability::stability_command(args),
    };
    match result {
        Ok(text) => {
            print!("{text}");
            ExitCode::SUCCESS
        }
        Err(error) => {
            let user_error = error.downcast_ref::<UserError>().is_some()
                || error.downcast_ref::<CaseError>().is_some();
            if error.downcast_ref::<CheckFailed>().is_some() || !user_error {
                eprintln!("error: {error:#}");
                ExitCode::from(1)
            } else {
                eprintln!("error: {error}");
                ExitCode::from(2)
            }
        }
    }
}
