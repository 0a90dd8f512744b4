//! `millimpact calibrate`.

use super::Result;

use super::CommandOutput;
use super::render;
use crate::cli::CalibrateArgs;
use millimpact::analysis::calibrate::{CalibrateOptions, calibrate as calibrate_case};
use millimpact::model::case::Case;
use millimpact::model::shipped::shipped_case;

pub(super) fn calibrate(args: &CalibrateArgs) -> Result<CommandOutput> {
    let case = match &args.case {
        Some(path) => {
            let case = Case::load(path)?;
            case.refuse_oblique("calibrate")?;
            case
        }
        None => shipped_case("ball_plate")?,
    };
    let restitutions = match (args.cor, args.cor_range) {
        (Some(e), _) => vec![e],
        (None, Some((a, b))) => vec![a, b],
        (None, None) => unreachable!("clap requires --cor or --cor-range"),
    };
    let options = CalibrateOptions {
        restitutions,
        timestep: args.timestep,
        tolerance: args.tolerance,
    };
    let report = calibrate_case(&case, &options)?;
    Ok(CommandOutput::passed(render(&report, args.format)?))
}
