//! `millimpact reference`.

use std::time::Duration;

use super::Result;

use super::CommandOutput;
use super::render;
use crate::cli::ReferenceArgs;
use millimpact::analysis::store::{ReferenceOptions, run_reference, save};
use millimpact::codes::CodeName;
use millimpact::error::{CheckFailed, UserError};
use millimpact::model::case::Case;
use millimpact::output::Format;

pub(super) fn reference(args: &ReferenceArgs) -> Result<CommandOutput> {
    let mut case = Case::load(&args.case)?;
    case.refuse_oblique_in(
        args.code.name(),
        args.code.driver().runs_oblique(),
        &CodeName::oblique_builds(),
    )?;
    if let Some(eta) = args.loss_coefficient {
        if !(0.0..1.0).contains(&eta) {
            return Err(UserError::argument("--loss-coefficient", eta, "must be in [0, 1)").into());
        }
        case = case.with_loss_coefficient(eta);
    }
    if let Some(dt) = args.timestep
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(
            UserError::argument("--timestep", dt, "must be a finite number > 0 (seconds)").into(),
        );
    }
    if args.clamp
        && let Some(why) = args.code.driver().clamp_refusal()
    {
        return Err(UserError::argument("--clamp", args.code, why).into());
    }
    if args.clamp && args.save {
        return Err(UserError::argument(
            "--save",
            "with --clamp",
            "reference/ stores the equivalent setups only; run --clamp without --save",
        )
        .into());
    }
    let options = ReferenceOptions {
        steps_per_contact: args.steps_per_contact,
        timestep: args.timestep,
        clamp_attractive: args.clamp,
        timeout: Duration::from_secs_f64(args.timeout),
    };
    let record = run_reference(args.code, &case, &options)?;
    let missed = record.tangential.as_ref().filter(|t| t.missed()).map(|t| {
        CheckFailed(format!(
            "reference --code {} {}: {}",
            args.code,
            args.case.display(),
            t.verdict()
        ))
    });
    let mut text = render(&record, args.format)?;
    if args.save {
        let path = save(&args.reference, &record)?;
        if matches!(args.format, Format::Table | Format::Markdown) {
            text += &format!("stored in {}\n", path.display());
        }
    }
    Ok(CommandOutput {
        warnings: Vec::new(),
        text,
        failure: missed,
    })
}
