//! Running a batch of independent impacts in one process of a code: the same scratch
//! directory, time limit and kept log as [`super::run_code`], one parse per impact.

use std::path::{Path, PathBuf};

use super::parse::{CSV_TRAJECTORY_FILE, log_value, parse_csv_columns};
use super::runner::process::Process;
use super::runner::{RunOptions, whole_trajectory};
use super::{CodeDriver, CodeError, CodeSetup, Executable, ParseError, ParsedRun, RenderedInput};
use thiserror::Error;

/// Why impacts cannot run together in one process of a code.
#[derive(Debug, Error)]
pub enum BatchError {
    /// The code runs one impact per process.
    #[error("the code runs one impact per process (no batch input)")]
    OnePerProcess,
    /// No impacts.
    #[error("an empty batch")]
    Empty,
    /// More impacts than one input may hold.
    #[error("{count} impacts: a batch holds at most {most} ({why})")]
    TooMany {
        /// Impacts asked for.
        count: usize,
        /// Most one batch holds.
        most: usize,
        /// What limits it.
        why: &'static str,
    },
    /// An impact of a scene the code's batches do not hold.
    #[error("{case}: {scene} impacts run alone ({holds})")]
    Scene {
        /// The impact's case.
        case: String,
        /// Its scene.
        scene: &'static str,
        /// What a batch of this code holds.
        holds: &'static str,
    },
    /// The impacts differ where one process needs them alike.
    #[error("the impacts differ in {what}")]
    Differ {
        /// What differs.
        what: &'static str,
    },
    /// One impact cannot be set up in the code at all.
    #[error(transparent)]
    Impact(#[from] CodeError),
    /// No steps, or no positive time step.
    #[error("no steps or no positive time step")]
    NoSteps,
}

/// A finished batch: one parsed run (or why not) per impact.
#[derive(Debug)]
pub struct BatchRun {
    /// Per impact, in the order of the setups.
    pub runs: Vec<Result<ParsedRun, ParseError>>,
    /// Process wall time, s.
    pub wall_time: f64,
    /// The input it ran.
    pub input: String,
    /// Where the scratch directory was kept (when any impact failed to parse).
    pub kept: Option<PathBuf>,
}

/// Render, run and parse `setups` in one process of `driver`'s code, its located build. A
/// batch the driver cannot render is `Unsupported` with its reason; a crash or time-out fails
/// the whole batch, with the log kept.
pub fn run_batch(
    driver: &dyn CodeDriver,
    setups: &[CodeSetup],
    options: &RunOptions,
) -> Result<BatchRun, CodeError> {
    run_batch_with(driver, super::runner::locate(driver), setups, options)
}

/// [`run_batch`] with the build at `executable` (or why none was found, reported once the
/// batch is known to render).
pub fn run_batch_with(
    driver: &dyn CodeDriver,
    executable: Result<Executable, CodeError>,
    setups: &[CodeSetup],
    options: &RunOptions,
) -> Result<BatchRun, CodeError> {
    let code = driver.name();
    let unsupported = |reason: String| CodeError::Unsupported {
        code: code.to_string(),
        case: format!("a batch of {}", setups.len()),
        reason,
    };
    let Some(runner) = driver.batch() else {
        return Err(unsupported(BatchError::OnePerProcess.to_string()));
    };
    // A batch renders the normal half only: an oblique impact runs alone (`run_code`).
    if setups.iter().any(|s| s.oblique.is_some()) {
        return Err(unsupported(
            "an oblique impact runs alone, not in a batch".to_string(),
        ));
    }
    let input = runner
        .render_batch(setups)
        .map_err(|reason| unsupported(reason.to_string()))?;
    let executable = executable?;
    super::runner::check_conventions(driver, &executable, setups)?;
    let launch = runner.launch(executable, &input);
    let prefix = format!("millimpact-{code}-batch-");
    let parent = options.scratch_folder();
    let (ran, log) = Process::new(
        &launch.executable,
        &launch.args,
        (&input.file_name, &input.text),
        options.timeout,
        &prefix,
    )
    .in_folder(&parent)
    .run()
    .map_err(|e| e.code_error(code))?
    .succeeded(code)?;
    let runs: Vec<Result<ParsedRun, ParseError>> = runner
        .parse_batch(setups, ran.folder(), &log)
        .into_iter()
        .zip(setups)
        .enumerate()
        .map(|(i, (run, setup))| {
            // Read as a single run is read: its whole trajectory, no more, no less.
            whole_trajectory(driver, setup, run?, || {
                format!("the trajectory of impact {} of the batch", i + 1)
            })
        })
        .collect();
    let wall_time = ran.wall_time;
    let kept = runs.iter().any(Result::is_err).then(|| ran.keep());
    Ok(BatchRun {
        runs,
        wall_time,
        input: input.text,
        kept,
    })
}

/// Refuses a batch of no impacts, or of more than `most`, which `why` limits.
pub(crate) fn check_batch_size(
    setups: &[CodeSetup],
    most: usize,
    why: &'static str,
) -> Result<(), BatchError> {
    if setups.is_empty() {
        return Err(BatchError::Empty);
    }
    if setups.len() > most {
        return Err(BatchError::TooMany {
            count: setups.len(),
            most,
            why,
        });
    }
    Ok(())
}

/// A batch input made of single inputs in sequence, as LIGGGHTS and LAMMPS run them: each but
/// the last followed by `clear` (which deletes every atom, fix and setting and restores the
/// defaults, as a fresh start would), so that every impact steps through its single run's input
/// and state. `single(i, setup)` is impact `i`'s input, with its own trajectory file; `code`
/// and `source` name the code and the file that made the batch, in its first line.
pub(crate) fn render_in_sequence(
    code: &str,
    source: &str,
    setups: &[CodeSetup],
    most: usize,
    mut single: impl FnMut(usize, &CodeSetup) -> Result<String, BatchError>,
    args: &[&str],
) -> Result<RenderedInput, BatchError> {
    check_batch_size(setups, most, "the screen output kept whole")?;
    let mut decks = Vec::with_capacity(setups.len());
    for (i, setup) in setups.iter().enumerate() {
        let mut deck = single(i, setup)?;
        if !deck.ends_with('\n') {
            deck.push('\n');
        }
        decks.push(deck);
    }
    Ok(RenderedInput {
        file_name: SEQUENCE_INPUT_FILE.into(),
        text: format!(
            "# millimpact: {} impacts in one {code} run, one after another, each its single run's input ({source}).\n{}",
            setups.len(),
            decks.join("clear\n")
        ),
        args: args.iter().map(|a| a.to_string()).collect(),
    })
}

/// The input file of a batch made by [`render_in_sequence`].
pub(crate) const SEQUENCE_INPUT_FILE: &str = "batch.in";

/// The loop time of impact `index` (from 0) of a batch whose script prints one
/// `MILLIMPACT impact=K loop_time=T` line per impact (K from 1), s; `None` where it printed none.
pub(crate) fn marked_loop_time(log: &str, index: usize) -> Option<f64> {
    let key = format!("impact={}", index + 1);
    log.lines()
        .filter_map(|l| l.trim().strip_prefix("MILLIMPACT "))
        .find(|rest| rest.split_whitespace().next() == Some(key.as_str()))
        .and_then(|rest| {
            rest.split_whitespace()
                .find_map(|f| f.strip_prefix("loop_time="))
        })
        .and_then(|v| v.parse::<f64>().ok())
}

/// The trajectory file of impact `index` (from 0) of a batch whose script writes one
/// `trajectory-K.csv` per impact (K from 1), as YADE's and Kratos' do.
pub(crate) fn marked_trajectory_file(index: usize) -> String {
    format!("trajectory-{}.csv", index + 1)
}

/// Each run of a batch of `setups` whose script writes [`marked_trajectory_file`]s (read as the
/// single scripts' [`CSV_TRAJECTORY_FILE`] is read), prints one `MILLIMPACT impact=K
/// loop_time=T` line per impact ([`marked_loop_time`]) and the build's `version=`, as YADE's
/// and Kratos' scripts do.
pub(crate) fn parse_marked_batch(
    setups: &[CodeSetup],
    workdir: &Path,
    log: &str,
) -> Vec<Result<ParsedRun, ParseError>> {
    let version = log_value(log, "version=");
    (0..setups.len())
        .map(|i| {
            let path = workdir.join(marked_trajectory_file(i));
            let text = std::fs::read_to_string(&path)
                .map_err(|source| ParseError::Read { path, source })?;
            Ok(ParsedRun {
                trajectory: parse_csv_columns(&text, CSV_TRAJECTORY_FILE)?,
                loop_time: marked_loop_time(log, i),
                version: version.map(str::to_string),
            })
        })
        .collect()
}
