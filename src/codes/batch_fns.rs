//! A code's batches as a table: what limits them and the functions that render, parse and
//! start them. Every code's batches differ only in these, so each driver lists its own in a
//! [`BatchFns`] rather than writing out a [`BatchRunner`] that forwards to them.

use std::path::Path;

use super::batch::BatchError;
pub(crate) use super::batch::check_batch_size;
use super::{BatchRunner, CodeSetup, Executable, Launch, ParseError, ParsedRun, RenderedInput};

/// Renders one input for the independent impacts of its setups, or says why they cannot run
/// together ([`BatchRunner::render_batch`]).
pub(crate) type RenderBatch = fn(&[CodeSetup]) -> Result<RenderedInput, BatchError>;

/// Parses a batch's runs in its scratch folder, given the batch's log: one result per setup, in
/// order ([`BatchRunner::parse_batch`]).
pub(crate) type ParseBatch = fn(&[CodeSetup], &Path, &str) -> Vec<Result<ParsedRun, ParseError>>;

/// Starts a rendered batch with the build's located executable ([`BatchRunner::launch`]).
pub(crate) type LaunchBatch = fn(Executable, &RenderedInput) -> Launch;

/// One code's batches: its limits and its functions.
#[derive(Clone, Copy)]
pub(crate) struct BatchFns {
    /// Most impacts one batch input may hold.
    pub max_batch: usize,
    /// How many impacts' steps cost what one start of the code's process does (1 where a
    /// start is as cheap as an impact).
    pub impacts_per_start: usize,
    /// The batch input.
    pub render: RenderBatch,
    /// The batch's runs.
    pub parse: ParseBatch,
    /// How the batch is started, where not by the executable itself with the input's
    /// arguments.
    pub launch: Option<LaunchBatch>,
}

impl BatchFns {
    /// Batches of at most `max_batch` impacts, rendered by `render` and parsed by `parse`,
    /// whose start costs what an impact does, started by the executable itself.
    pub(crate) const fn new(max_batch: usize, render: RenderBatch, parse: ParseBatch) -> Self {
        BatchFns {
            max_batch,
            impacts_per_start: 1,
            render,
            parse,
            launch: None,
        }
    }

    /// The same batches, a start of whose process costs what `impacts` impacts do.
    pub(crate) const fn costing(self, impacts: usize) -> Self {
        BatchFns {
            impacts_per_start: impacts,
            ..self
        }
    }

    /// The same batches, started by `launch`.
    pub(crate) const fn launched_by(self, launch: LaunchBatch) -> Self {
        BatchFns {
            launch: Some(launch),
            ..self
        }
    }
}

impl BatchRunner for BatchFns {
    fn max_batch(&self) -> usize {
        self.max_batch
    }

    fn impacts_per_start(&self) -> usize {
        self.impacts_per_start
    }

    fn render_batch(&self, setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
        (self.render)(setups)
    }

    fn parse_batch(
        &self,
        setups: &[CodeSetup],
        workdir: &Path,
        log: &str,
    ) -> Vec<Result<ParsedRun, ParseError>> {
        (self.parse)(setups, workdir, log)
    }

    fn launch(&self, executable: Executable, input: &RenderedInput) -> Launch {
        match self.launch {
            Some(launch) => launch(executable, input),
            None => Launch {
                executable,
                args: input.args.clone(),
            },
        }
    }
}

/// Checks `code`'s batch of [`shipped_setups`](super::setup::shipped_setups) in every scene
/// is one run per setup, in order, each but the last followed by `clear` (a batch made by
/// `render_in_sequence`), and hands each run to `check` with its scene, its index and its single
/// run's input.
#[cfg(test)]
pub(crate) fn check_runs_in_sequence(
    code: super::CodeName,
    check: impl Fn(&str, usize, &str, &str),
) {
    let driver = code.driver();
    for scene in ["ball_plate", "ball_ball", "rod_end"] {
        let setups = super::setup::shipped_setups(code, scene);
        let batch = driver.batch().unwrap().render_batch(&setups).unwrap();
        let runs: Vec<&str> = batch.text.split("clear\n").collect();
        assert_eq!(runs.len(), setups.len(), "{scene}");
        for (i, (run, setup)) in runs.iter().zip(&setups).enumerate() {
            check(scene, i, run, &driver.render(setup).unwrap().text);
        }
    }
}
