//! `millimpact benchmark`.

use std::time::Duration;

use anyhow::Result;

use super::CommandOutput;
use crate::cli::{BenchmarkArgs, BenchmarkName};
use millimpact::analysis::benchmark::{BenchmarkOptions, chung_ooi};
use millimpact::analysis::store::ReferenceOptions;
use millimpact::error::CheckFailed;
use millimpact::output::export;

pub(super) fn benchmark(args: &BenchmarkArgs) -> Result<CommandOutput> {
    let options = BenchmarkOptions {
        codes: args.codes.clone(),
        reference: ReferenceOptions {
            steps_per_contact: Some(args.steps_per_contact),
            timeout: Duration::from_secs_f64(args.timeout),
            ..ReferenceOptions::default()
        },
    };
    let report = match args.benchmark {
        BenchmarkName::ChungOoi => chung_ooi(&options)?,
    };
    let failures = report.failures();
    let failure = (!failures.is_empty()).then(|| {
        CheckFailed(format!(
            "benchmark {}: {} of {} rows outside their tolerance",
            report.benchmark,
            failures.len(),
            report.rows.len()
        ))
    });
    Ok(CommandOutput {
        text: export(&report, args.format)?,
        failure,
        warnings: Vec::new(),
    })
}
