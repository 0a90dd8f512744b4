//! One point of a sweep computed alone: by a method, or by a code in a process of its own
//! with the fault containment of `reference`.

use std::time::Duration;

use super::grid::{Point, SweepFile};
use super::row::{CodeFigures, PointFigures, SweepRow};
use crate::analysis::run::{IntegrationOptions, run_case};
use crate::analysis::source::{Resolution, Source};
use crate::analysis::store::{ReferenceOptions, run_reference};

/// How to run a sweep.
#[derive(Clone, Debug)]
pub struct GridOptions {
    /// Worker threads for our methods, and most live code processes.
    pub jobs: usize,
    /// Time limit of one code process.
    pub timeout: Duration,
    /// Bilateral contact: undamped periods to follow.
    pub periods: f64,
    /// Most impacts per code process (1: no batching).
    pub batch: usize,
}

/// Evaluate one point alone, whoever computes it.
pub fn single_point(sweep: &SweepFile, point: &Point, options: &GridOptions) -> SweepRow {
    let outcome = (|| -> anyhow::Result<PointFigures> {
        let case = sweep.case(point)?;
        match point.source.source {
            Source::Method(method) => {
                let integration = IntegrationOptions {
                    method,
                    steps_per_period: Resolution::steps_per_period(point.source.resolution),
                    rtol: Resolution::rtol(point.source.resolution),
                    periods: options.periods,
                    ..IntegrationOptions::default()
                };
                let settings = integration.settings(&case, false)?;
                Ok(PointFigures::of_method(&run_case(&case, &settings)?.0))
            }
            Source::Code(code) => {
                let reference = ReferenceOptions {
                    steps_per_contact: Resolution::steps_per_contact(point.source.resolution),
                    timeout: options.timeout,
                    ..ReferenceOptions::default()
                };
                let record = run_reference(code, &case, &reference)?;
                Ok(PointFigures::of_code(&CodeFigures::from_record(
                    &case, &record,
                )))
            }
        }
    })();
    sweep.outcome_row(point, outcome)
}
