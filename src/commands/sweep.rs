//! `millimpact sweep`.

use anyhow::Result;

use super::run::integration_options;
use super::{CommandOutput, check_output, write_output};
use crate::analysis::sweep::{parse_range, sweep as sweep_case};
use crate::cli::SweepArgs;
use crate::error::UserError;
use crate::model::case::Case;
use crate::model::exact;
use crate::output::export;
use crate::output::restitution_plot::restitution_svg;

pub(super) fn sweep(args: &SweepArgs) -> Result<CommandOutput> {
    let case = Case::load(&args.case)?;
    check_output("--plot", args.plot.as_deref(), &[&args.case])?;
    let values = parse_range(&args.loss_coefficient).map_err(|e| match e {
        UserError::Argument {
            option,
            value,
            allowed,
        } => UserError::CaseArgument {
            case: case.path.display().to_string(),
            option,
            value,
            allowed,
        },
        other => other,
    })?;
    let options = integration_options(&args.integration);
    let mut report = sweep_case(&case, &values, &options)?;
    report.command = format!(
        "millimpact sweep {} --loss-coefficient {} --method {}",
        case.path.display(),
        args.loss_coefficient,
        options.method
    );
    if let Some(path) = &args.plot {
        let points: Vec<(f64, f64)> = report
            .rows
            .iter()
            .map(|r| (r.loss_coefficient, r.cor))
            .collect();
        let svg = restitution_svg(
            &case.name,
            options.method.name(),
            &points,
            &exact::restitution,
        )?;
        write_output(path, svg.as_bytes(), "figure")?;
    }
    Ok(CommandOutput::passed(export(&report, args.format)?))
}
