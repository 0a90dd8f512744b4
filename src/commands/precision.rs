//! `millimpact precision`.

use super::Result;

use super::render;
use super::{CommandOutput, check_output, write_output};
use crate::cli::PrecisionArgs;
use millimpact::analysis::precision::{code_steps_sweep, precision_report};
use millimpact::error::UserError;
use millimpact::model::case::Case;
use millimpact::output::work_precision_plot::work_precision_svg;
use millimpact::solve::Method;

pub(super) fn precision(args: &PrecisionArgs) -> Result<CommandOutput> {
    let case = Case::load(&args.case)?;
    case.refuse_oblique("precision")?;
    check_output("--plot", args.plot.as_deref(), &[&args.case])?;
    let methods: Vec<Method> = if args.methods.is_empty() {
        Method::ALL
            .iter()
            .copied()
            .filter(|m| m.integrates())
            .collect()
    } else {
        args.methods.clone()
    };
    if let Some(closed) = methods.iter().find(|m| !m.integrates()) {
        return Err(UserError::argument(
            "--methods",
            closed,
            "an integrating method: the closed forms have no error to sweep",
        )
        .into());
    }
    let report = precision_report(
        &case,
        &methods,
        &args.codes,
        args.repeats,
        &code_steps_sweep(),
    )?;
    if let Some(path) = &args.plot {
        let svg = work_precision_svg(&report.case, &report.series())?;
        write_output(path, svg.as_bytes(), "diagram")?;
    }
    Ok(CommandOutput::passed(render(&report, args.format)?))
}
