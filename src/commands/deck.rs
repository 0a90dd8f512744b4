//! `millimpact deck`.

use std::path::Path;
use std::time::{Duration, Instant};

use super::Result;

use super::{CommandOutput, render};
use crate::cli::DeckArgs;
use millimpact::analysis::deck::{
    DeckReport, ImpactRun, ImpactRunner, LiveRunner, check_deck, failures, read_deck,
    velocities as deck_velocities,
};
use millimpact::codes::CodeError;
use millimpact::codes::deck::DeckImpactInput;
use millimpact::codes::deck::{DeckOptions, GivenParticle, Partner, UserDeck};
use millimpact::codes::{CodeName, RunOptions};
use millimpact::error::CheckFailed;
use millimpact::model::law::CodeLaw;

pub(super) fn deck(args: &DeckArgs) -> Result<CommandOutput> {
    let given = Given {
        particles: &args.particle,
        variables: &args.variables,
        time_limit: Duration::from_secs_f64(args.timeout),
    };
    let (code, deck) = read(&args.deck, args.code, &given)?;
    let velocities: Vec<f64> = args
        .impact_velocity
        .iter()
        .flat_map(|speeds| speeds.0.iter().copied())
        .collect();
    let report = check_with_progress(code, &deck, &velocities, &given, args.timeout)?;
    let text = render(&report, args.format)?;
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
    /// The time limit of every code process, the one that reads the deck included.
    pub time_limit: Duration,
}

/// Read the deck at `path` (bad input: a [`UserError`], before anything runs; a code that reads
/// the deck and could not run, as YADE setting up a script, is the code's fault: exit 1).
pub(super) fn read(
    path: &Path,
    code: Option<CodeName>,
    given: &Given,
) -> Result<(CodeName, UserDeck)> {
    let options = DeckOptions {
        particles: given.particles.to_vec(),
        variables: given.variables.to_vec(),
        time_limit: Some(given.time_limit),
    };
    // A deck error states its own exit code: the deck's fault, or the reading code's.
    Ok(read_deck(path, code, &options)?)
}

/// Check `deck` in its code, now, at `velocities` (empty: the default ones).
pub(super) fn check(
    code: CodeName,
    deck: &UserDeck,
    velocities: &[f64],
    given: &Given,
    timeout: f64,
) -> Result<DeckReport> {
    check_with(code, deck, velocities, given, &live_runner(timeout))
}

fn live_runner(timeout: f64) -> LiveRunner {
    LiveRunner {
        options: RunOptions {
            timeout: Duration::from_secs_f64(timeout),
            scratch_parent: None,
        },
    }
}

/// [`check`] with a progress bar on standard error while the runs take longer than a second,
/// when standard error is a terminal (and `CI` is not set).
fn check_with_progress(
    code: CodeName,
    deck: &UserDeck,
    velocities: &[f64],
    given: &Given,
    timeout: f64,
) -> Result<DeckReport> {
    let live = live_runner(timeout);
    // Each wall with friction adds its oblique impact (walls merged as identical run once, and
    // the bar ends short of its length, cleared).
    let oblique = deck
        .contacts
        .iter()
        .filter(|c| c.friction.is_some() && matches!(c.partner, Partner::Wall(_)))
        .count();
    let runs = deck.contacts.len() * deck_velocities(deck, velocities).0.len() + oblique;
    let template = "{bar:40} {pos}/{len} impacts  {per_sec}  ETA {eta}";
    let Some(bar) = super::progress_bar(runs as u64, template) else {
        return check_with(code, deck, velocities, given, &live);
    };
    // Hidden until the runs have taken a second.
    bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    let runner = Progress {
        inner: &live,
        bar: bar.clone(),
        started: Instant::now(),
    };
    let report = check_with(code, deck, velocities, given, &runner);
    bar.finish_and_clear();
    report
}

/// A runner that counts its runs on a bar, shown once the runs have taken a second.
struct Progress<'a> {
    inner: &'a dyn ImpactRunner,
    bar: indicatif::ProgressBar,
    started: Instant,
}

impl ImpactRunner for Progress<'_> {
    fn run(
        &self,
        code: CodeName,
        impact: &DeckImpactInput,
        law: &CodeLaw,
    ) -> Result<ImpactRun, CodeError> {
        let run = self.inner.run(code, impact, law);
        self.bar.inc(1);
        if self.bar.is_hidden() && self.started.elapsed() > Duration::from_secs(1) {
            self.bar
                .set_draw_target(indicatif::ProgressDrawTarget::stderr());
        }
        run
    }
}

fn check_with(
    code: CodeName,
    deck: &UserDeck,
    velocities: &[f64],
    given: &Given,
    runner: &dyn ImpactRunner,
) -> Result<DeckReport> {
    let mut report = check_deck(code, deck, deck_velocities(deck, velocities), runner)?;
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
