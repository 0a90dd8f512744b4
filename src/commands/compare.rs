//! `millimpact compare`.

use std::time::Duration;

use super::Result;

use super::CommandOutput;
use super::render;
use crate::cli::CompareArgs;
use millimpact::analysis::compare::{CompareOptions, compare as compare_cases};
use millimpact::error::CheckFailed;
use millimpact::model::case::Case;
use millimpact::model::shipped::canonical_cases;

pub(super) fn compare(args: &CompareArgs) -> Result<CommandOutput> {
    let cases = if args.cases.is_empty() {
        canonical_cases()?
    } else {
        args.cases
            .iter()
            .map(|p| Case::load(p).and_then(|c| c.refuse_oblique("compare").map(|_| c)))
            .collect::<Result<Vec<_>, _>>()?
    };
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
