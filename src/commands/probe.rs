//! `millimpact probe`.

use anyhow::Result;

use super::CommandOutput;
use crate::cli::ProbeArgs;
use crate::codes::{CodeName, Executable};
use crate::error::{CheckFailed, UserError};
use crate::output::{Format, export};

pub(super) fn probe(args: &ProbeArgs) -> Result<CommandOutput> {
    let driver = args.code.driver();
    if !driver.probes() {
        let covered: Vec<&str> = CodeName::ALL
            .iter()
            .filter(|c| c.driver().probes())
            .map(|c| c.name())
            .collect();
        return Err(UserError::argument(
            "--code",
            driver.name(),
            format!("has no probe; the probe covers {}", covered.join(", ")),
        )
        .into());
    }
    let executable = match &args.binary {
        Some(path) if !path.is_file() => {
            return Err(UserError::argument("--binary", path.display(), "is not a file").into());
        }
        // The probe runs in a scratch directory: a relative path must not be read from there.
        Some(path) => Executable::plain(std::fs::canonicalize(path).map_err(|e| {
            UserError::argument(
                "--binary",
                path.display(),
                format!("cannot be resolved: {e}"),
            )
        })?),
        None => driver
            .locate()
            .map_err(|looked| anyhow::anyhow!("{}: {looked}", driver.name()))?,
    };
    let report = driver
        .probe(&executable)
        .unwrap_or_else(|| Err("no probe".into()))
        .map_err(|reason| anyhow::anyhow!("{}: {reason}", driver.name()))?;
    let text = if args.format == Format::Markdown {
        crate::analysis::probe::conventions_markdown(&report).map_err(anyhow::Error::msg)? + "\n"
    } else {
        export(&report, args.format)?
    };
    // The table is printed either way; a build whose conventions stay open is one the drivers
    // will not plan for, which is a failed check (exit 1), not bad input.
    Ok(CommandOutput {
        text,
        failure: report.conventions().err().map(CheckFailed),
        warnings: Vec::new(),
    })
}
