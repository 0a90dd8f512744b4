use std::process::ExitCode;

use clap::Parser;
use millimpact::app::{self, CheckFailed, UserError};
use millimpact::case::CaseError;
use millimpact::cli::{Cli, Command};

fn main() -> ExitCode {
    let cli = Cli::parse();
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
