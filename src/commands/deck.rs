//! `millimpact deck`.

use std::path::Path;
use std::time::Duration;

use anyhow::Result;

use super::CommandOutput;
use crate::cli::DeckArgs;
use millimpact::analysis::deck::{
    DeckReport, LiveRunner, check_deck, failures, read_deck, velocities as deck_velocities,
};
use millimpact::codes::deck::{DeckOptions, GivenParticle, UserDeck};
use millimpact::codes::{CodeName, RunOptions};
use millimpact::error::{CheckFailed, UserError};
use millimpact::output::export;

pub(super) fn deck(args: &DeckArgs) -> Result<CommandOutput> {
    let given = Given {
        particles: &args.particle,
        variables: &args.variables,
    };
    let (code, deck) = read(&args.deck, args.code, &given)?;
    let report = check(code, &deck, &args.impact_velocity, &given, args.timeout)?;
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

/// What the command line adds to a deck.
pub(super) struct Given<'a> {
    pub particles: &'a [GivenParticle],
    pub variables: &'a [(String, String)],
}

/// Read the deck at `path` (bad input: a [`UserError`], before anything runs).
pub(super) fn read(
    path: &Path,
    code: Option<CodeName>,
    given: &Given,
) -> Result<(CodeName, UserDeck)> {
    let options = DeckOptions {
        particles: given.particles.to_vec(),
        variables: given.variables.to_vec(),
    };
    Ok(read_deck(path, code, &options).map_err(UserError::from)?)
}

/// Check `deck` in its code, now, at `velocities` (empty: the default ones).
pub(super) fn check(
    code: CodeName,
    deck: &UserDeck,
    velocities: &[f64],
    given: &Given,
    timeout: f64,
) -> Result<DeckReport> {
    let runner = LiveRunner {
        options: RunOptions {
            timeout: Duration::from_secs_f64(timeout),
            scratch_parent: None,
        },
    };
    let mut report = check_deck(code, deck, deck_velocities(deck, velocities), &runner)?;
    report.given = given
        .particles
        .iter()
        .map(|p| {
            (
                "--particle",
                format!("{}:{}:{}", p.type_id, p.radius, p.density),
            )
        })
        .chain(
            given
                .variables
                .iter()
                .map(|(n, v)| ("--var", format!("{n}={v}"))),
        )
        .collect();
    Ok(report)
}
