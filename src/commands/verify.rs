//! `millimpact verify`.

use super::Result;

use super::CommandOutput;
use super::render;
use crate::cli::VerifyArgs;
use millimpact::analysis::store::verify::verify as verify_all;
use millimpact::error::CheckFailed;

pub(super) fn verify(args: &VerifyArgs) -> Result<CommandOutput> {
    let mut warnings = Vec::new();
    let cases = super::shipped_folder(args.cases.as_deref(), "--cases", "cases", &mut warnings)?;
    let reference = super::reference_folder(args.reference.as_deref(), false, &mut warnings)?;
    let report = verify_all(&cases, &reference)?;
    let failed = report.failed();
    Ok(CommandOutput {
        warnings,
        text: render(&report, args.format)?,
        failure: (failed > 0).then(|| {
            CheckFailed(format!(
                "verify: {failed} of {} checks disagree",
                report.rows.len()
            ))
        }),
    })
}
