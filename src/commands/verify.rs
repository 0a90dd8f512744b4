//! `millimpact verify`.

use anyhow::Result;

use super::CommandOutput;
use crate::cli::VerifyArgs;
use millimpact::analysis::store::verify::verify as verify_all;
use millimpact::error::CheckFailed;
use millimpact::output::export;

pub(super) fn verify(args: &VerifyArgs) -> Result<CommandOutput> {
    let report = verify_all(&args.cases, &args.reference)?;
    let failed = report.failed();
    Ok(CommandOutput {
        warnings: Vec::new(),
        text: export(&report, args.format)?,
        failure: (failed > 0).then(|| {
            CheckFailed(format!(
                "verify: {failed} of {} checks disagree",
                report.rows.len()
            ))
        }),
    })
}
