//! `millimpact stability`.

use super::Result;

use super::CommandOutput;
use super::render;
use crate::cli::StabilityArgs;
use millimpact::analysis::stability::stability_report;
use millimpact::error::CheckFailed;

pub(super) fn stability(args: &StabilityArgs) -> Result<CommandOutput> {
    let report = stability_report();
    let failures = report.accurate_method_failures().len();
    Ok(CommandOutput {
        warnings: Vec::new(),
        text: render(&report, args.format)?,
        failure: (failures > 0).then(|| {
            CheckFailed(format!(
                "stability: {failures} rk4-event or dopri5 case(s) fail"
            ))
        }),
    })
}
