//! `millimpact probe`.

use super::{Context, Result};

use super::CommandOutput;
use super::render;
use crate::cli::ProbeArgs;
use millimpact::codes::{CodeName, Executable};
use millimpact::error::{CheckFailed, UserError};
use millimpact::output::Format;

pub(super) fn probe(args: &ProbeArgs) -> Result<CommandOutput> {
    let driver = args.code.driver();
    let Some(prober) = driver.prober() else {
        let covered: Vec<&str> = CodeName::ALL
            .iter()
            .filter(|c| c.driver().prober().is_some())
            .map(|c| c.name())
            .collect();
        return Err(UserError::argument(
            "--code",
            driver.name(),
            format!("has no probe; the probe covers {}", covered.join(", ")),
        )
        .into());
    };
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
        None => driver.locate().context(driver.name())?,
    };
    let report = if args.refresh {
        prober.probe_afresh(&executable)
    } else {
        prober.probe(&executable)
    }
    .with_context(|| driver.name())?;
    let text = if args.format == Format::Markdown {
        millimpact::analysis::probe::conventions_markdown(&report)? + "\n"
    } else {
        render(&report, args.format)?
    };
    // The table is printed either way; a build whose conventions stay open is one the drivers
    // will not plan for, which is a failed check (exit 1), not bad input.
    Ok(CommandOutput {
        text,
        failure: report
            .conventions()
            .err()
            .map(|e| CheckFailed(e.to_string())),
        warnings: Vec::new(),
    })
}
