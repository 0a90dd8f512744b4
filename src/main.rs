mod cli;
mod commands;

use std::io::Write;
use std::process::ExitCode;

use clap::Parser;
use cli::Cli;
use commands::exit_code;

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

/// Write the command's text; a closed pipe or a full disk is one line and exit 1, not a panic.
fn print(text: &str) -> Result<(), std::io::Error> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()
}

fn main() -> ExitCode {
    let cli = match parse() {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    // Ctrl-C or SIGTERM ends the DEM codes running now (their whole process groups) and removes
    // their scratch directories; a sweep installs its own handler, which keeps its finished rows.
    if !matches!(cli.command, cli::Command::Sweep(_)) {
        let _ = ctrlc::set_handler(|| millimpact::codes::runner::stop_all_codes_and_exit(130));
    }
    match commands::dispatch(&cli.command) {
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
