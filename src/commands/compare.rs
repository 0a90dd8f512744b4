//! `millimpact compare`.

use std::path::PathBuf;
use std::time::Duration;

use anyhow::Result;

use super::CommandOutput;
use crate::cli::CompareArgs;
use millimpact::analysis::compare::{CompareOptions, compare as compare_cases};
use millimpact::error::CheckFailed;
use millimpact::model::case::Case;
use millimpact::output::export;

/// The canonical cases compared by default.
pub const CANONICAL_CASES: [&str; 3] = [
    "cases/ball_plate.toml",
    "cases/ball_ball.toml",
    "cases/rod_end.toml",
];

pub(super) fn compare(args: &CompareArgs) -> Result<CommandOutput> {
    let paths: Vec<PathBuf> = if args.cases.is_empty() {
        CANONICAL_CASES.iter().map(PathBuf::from).collect()
    } else {
        args.cases.clone()
    };
    let cases = paths
        .iter()
        .map(|p| Case::load(p))
        .collect::<Result<Vec<_>, _>>()?;
    let options = CompareOptions {
        live: args.live,
        reference: args.reference.clone(),
        timeout: Duration::from_secs_f64(args.timeout),
    };
    let report = compare_cases(&cases, &options)?;
    let failures = report.failures();
    Ok(CommandOutput {
        warnings: Vec::new(),
        text: export(&report, args.format)?,
        failure: (!failures.is_empty())
            .then(|| CheckFailed(format!("compare --live: {}", failures.join("; ")))),
    })
}
