//! `millimpact compare`.

use std::time::Duration;

use super::Result;

use super::CommandOutput;
use super::render;
use crate::cli::CompareArgs;
use millimpact::analysis::compare::{CompareOptions, compare as compare_cases};
use millimpact::error::CheckFailed;

pub(super) fn compare(args: &CompareArgs) -> Result<CommandOutput> {
    let cases = super::cases_or_canonical(&args.cases, "compare")?;
    let mut warnings = Vec::new();
    let options = CompareOptions {
        live: args.live,
        reference: super::reference_folder(args.reference.as_deref(), args.live, &mut warnings)?,
        timeout: Duration::from_secs_f64(args.timeout),
    };
    let report = compare_cases(&cases, &options)?;
    let failures = report.failures();
    Ok(CommandOutput {
        warnings,
        text: render(&report, args.format)?,
        failure: (!failures.is_empty())
            .then(|| CheckFailed(format!("compare --live: {}", failures.join("; ")))),
    })
}
