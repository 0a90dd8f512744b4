//! `millimpact calibrate`.

use std::path::PathBuf;

use anyhow::Result;

use super::CommandOutput;
use crate::cli::CalibrateArgs;
use millimpact::analysis::calibrate::{CalibrateOptions, calibrate as calibrate_case};
use millimpact::model::case::Case;
use millimpact::output::export;

pub(super) fn calibrate(args: &CalibrateArgs) -> Result<CommandOutput> {
    let path = args
        .case
        .clone()
        .unwrap_or_else(|| PathBuf::from("cases/ball_plate.toml"));
    let case = Case::load(&path)?;
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
    Ok(CommandOutput::passed(export(&report, args.format)?))
}
