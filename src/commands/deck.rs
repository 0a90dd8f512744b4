//! `millimpact deck`.

use std::time::Duration;

use anyhow::Result;

use super::CommandOutput;
use crate::cli::DeckArgs;
use millimpact::analysis::deck::{LiveRunner, check_deck, failures, read_deck, velocities};
use millimpact::codes::RunOptions;
use millimpact::codes::deck::DeckOptions;
use millimpact::error::{CheckFailed, UserError};
use millimpact::output::export;

pub(super) fn deck(args: &DeckArgs) -> Result<CommandOutput> {
    let options = DeckOptions {
        particles: args.particle.clone(),
        variables: args.variables.clone(),
    };
    let (code, deck) = read_deck(&args.deck, args.code, &options).map_err(UserError::from)?;
    let speeds = velocities(&deck, &args.impact_velocity);
    let runner = LiveRunner {
        options: RunOptions {
            timeout: Duration::from_secs_f64(args.timeout),
            scratch_parent: None,
        },
    };
    let mut report = check_deck(code, &deck, speeds, &runner)?;
    report.given = args
        .particle
        .iter()
        .map(|p| {
            (
                "--particle",
                format!("{}:{}:{}", p.type_id, p.radius, p.density),
            )
        })
        .chain(
            args.variables
                .iter()
                .map(|(n, v)| ("--var", format!("{n}={v}"))),
        )
        .collect();
    let text = export(&report, args.format)?;
    let failed = failures(&report);
    Ok(CommandOutput {
        text,
        failure: (!failed.is_empty()).then(|| {
            CheckFailed(format!(
                "deck: {} of {} impacts failed: {}",
                failed.len(),
                report.impacts.len(),
                failed.join("; ")
            ))
        }),
        warnings: Vec::new(),
    })
}
