//! The `millimpact` command: the library's command line, run.

use std::process::ExitCode;

fn main() -> ExitCode {
    millimpact::run_command_line()
}
