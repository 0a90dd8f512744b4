//! `millimpact run`.

use super::Result;
use serde::Serialize;

use super::render;
use super::{CommandOutput, check_output, write_output};
use crate::cli::{IntegrationArgs, RunArgs};
use millimpact::analysis::run::{
    IntegrationOptions, RunRecord, RunReport, reproduce_arguments, run_case, trajectory_rows,
};
use millimpact::error::UserError;
use millimpact::model::case::Case;
use millimpact::output::{Section, Summary, csv_string};

/// The integration options the arguments name.
pub(super) fn integration_options(args: &IntegrationArgs) -> IntegrationOptions {
    IntegrationOptions {
        method: args.method,
        steps_per_period: args.steps_per_period,
        timestep: args.timestep,
        rtol: args.rtol,
        periods: args.periods,
    }
}

/// A run with the command that reproduces it.
#[derive(Serialize)]
struct RunSummary {
    #[serde(flatten)]
    report: RunReport,
    #[serde(skip)]
    reproduce: String,
}

impl Summary for RunSummary {
    type Record = RunRecord;

    fn records(&self) -> Vec<RunRecord> {
        self.report.records()
    }

    fn sections(&self) -> Vec<Section> {
        self.report.sections()
    }

    fn footer(&self) -> Vec<String> {
        vec![format!("reproduce: millimpact run {}", self.reproduce)]
    }
}

pub(super) fn run(args: &RunArgs) -> Result<CommandOutput> {
    let case = Case::load(&args.case)?;
    check_output("--trajectory", args.trajectory.as_deref(), &[&args.case])?;
    let options = integration_options(&args.integration);
    if let Some(path) = &args.trajectory
        && !options.method.integrates()
    {
        return Err(UserError::argument(
            "--trajectory",
            path.display(),
            format!(
                "the {} method has no time history; use an integrating method",
                options.method
            ),
        )
        .into());
    }
    let settings = options.settings(&case, args.trajectory.is_some())?;
    let (report, outcome) = run_case(&case, &settings)?;
    let warnings = report.warnings.clone();
    let summary = RunSummary {
        report,
        reproduce: reproduce_arguments(&case, &settings),
    };
    let text = render(&summary, args.format)?;
    if let Some(path) = &args.trajectory {
        let csv = csv_string(&trajectory_rows(&case, &outcome.trajectory))?;
        write_output(path, csv.as_bytes(), "trajectory")?;
    }
    Ok(CommandOutput {
        warnings,
        ..CommandOutput::passed(text)
    })
}
