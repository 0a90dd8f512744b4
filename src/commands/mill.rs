//! `millimpact mill`.

use std::time::Duration;

use super::Result;

use super::CommandOutput;
use super::render;
use crate::cli::MillArgs;
use millimpact::analysis::mill::{MillError, MillOptions, mill_builds, run_mill};
use millimpact::codes::liggghts::mill::MillDeck;
use millimpact::error::UserError;

pub(super) fn mill(args: &MillArgs) -> Result<CommandOutput> {
    if args.code.driver().mill_paper_build().is_none() {
        return Err(UserError::argument("--code", args.code, mill_builds()).into());
    }
    let deck = MillDeck::read(&args.deck).map_err(MillError::from)?;
    let options = MillOptions {
        time: args.time,
        seeds: args.seeds,
        transient: args.transient,
        spectra_time: args.spectra_time,
        contact_every: args.contact_every,
        timeout: Duration::from_secs_f64(args.timeout),
        jobs: 2,
        hertz_code: args.code,
        keep: args.keep.clone(),
    };
    let report = run_mill(&deck, &options, &|_| {})?;
    Ok(CommandOutput::passed(render(&report, args.format)?))
}
