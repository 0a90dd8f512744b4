//! LIGGGHTS batches: many impacts in one process, one after another, in any scene. The batch
//! input is the single runs' inputs in sequence, each but the last followed by `clear` (which
//! deletes every atom, fix and setting and restores the defaults, as a fresh start would), each
//! writing its own trajectory file; so every impact steps through its single run's input and
//! state and gives its trajectory to the last bit (tested for every scene), while the process's
//! start-up is paid once.
//!
//! One line differs from the single input: the row of the initial state. The single input
//! prints it before its `run`, when no force has been computed yet, so its force column reads
//! `fz` as LIGGGHTS allocated it: zero in a fresh process, but, after a `clear`, whatever the
//! freed memory held (1.6e-322 was seen). The batch prints the 0 a fresh process prints there.
//!
//! Impacts side by side in one run were the other way (one atom type per sphere, its
//! restitution against the plate per type pair): it held plates only, and needs a type pair
//! table per law parameter for two balls and rods. In sequence every scene runs as it runs
//! alone.

use std::path::Path;

use crate::codes::batch::{SEQUENCE_INPUT_FILE, render_in_sequence};
use crate::codes::batch_fns::BatchFns;
use crate::codes::liggghts::{Liggghts, TRAJECTORY_FILE, parse_trajectory_file, version};
use crate::codes::parse::ParseError;
use crate::codes::{BatchError, CodeDriver, CodeSetup, ParsedRun, RenderedInput};

/// Most impacts in one batch: each run adds about 1 kB to the screen output, which is kept
/// whole up to [`crate::codes::runner::MAX_LOG_BYTES`].
pub(crate) const MAX_BATCH: usize = 256;

/// The batch input file.
pub(crate) const BATCH_INPUT_FILE: &str = SEQUENCE_INPUT_FILE;

/// The trajectory file of impact `i` (from 0) of a batch.
pub(crate) fn batch_trajectory_file(i: usize) -> String {
    format!("traj-{}.txt", i + 1)
}

/// The single input's row of the initial state, and the batch's (its force column 0).
const INITIAL_ROW: (&str, &str) = (
    "print           \"${t} ${overlap} ${approach} ${force}\" file ",
    "print           \"${t} ${overlap} ${approach} 0\" file ",
);

/// The batch input of `driver`, a LIGGGHTS build whose single inputs are the stock deck with
/// its own contact lines (the stock build, the paper build), for `setups`: their single inputs
/// in sequence, or why they cannot run so.
pub(crate) fn render_batch(
    driver: &dyn CodeDriver,
    setups: &[CodeSetup],
) -> Result<RenderedInput, BatchError> {
    render_in_sequence(
        "LIGGGHTS",
        "src/codes/liggghts/batch.rs",
        setups,
        MAX_BATCH,
        |i, setup| {
            let single = driver.render(setup)?.text;
            if !single.contains(INITIAL_ROW.0) {
                return Err(BatchError::Differ {
                    what: "the input's initial row (not the template's)",
                });
            }
            Ok(single
                .replace(INITIAL_ROW.0, INITIAL_ROW.1)
                .replace(TRAJECTORY_FILE, &batch_trajectory_file(i)))
        },
        &["-in", BATCH_INPUT_FILE, "-log", "none", "-echo", "none"],
    )
}

/// Each impact's run from a batch: its own trajectory, and its own run's loop time and step
/// count (the `Loop time of` lines, one per run, in order).
pub(crate) fn parse_batch(
    setups: &[CodeSetup],
    workdir: &Path,
    log: &str,
) -> Vec<Result<ParsedRun, ParseError>> {
    let code_version = version(log);
    let loops: Vec<&str> = log
        .lines()
        .filter(|l| l.starts_with("Loop time of "))
        .collect();
    setups
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let line = loops.get(i).copied().unwrap_or_default();
            let run = parse_trajectory_file(s, &workdir.join(batch_trajectory_file(i)), line)?;
            Ok(ParsedRun {
                version: code_version.clone(),
                ..run
            })
        })
        .collect()
}

/// The stock build's batches: many impacts in one process, in sequence.
pub(crate) static LIGGGHTS_BATCH: BatchFns = BatchFns::new(
    MAX_BATCH,
    |setups| render_batch(&Liggghts, setups),
    parse_batch,
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::CodeName;
    use crate::codes::batch_fns::check_runs_in_sequence;
    use crate::codes::setup::shipped_setups;

    #[test]
    fn a_batch_is_the_single_inputs_in_sequence_each_writing_its_own_file() {
        check_runs_in_sequence(CodeName::Liggghts, |scene, i, run, single| {
            let own = run
                .replace(&batch_trajectory_file(i), TRAJECTORY_FILE)
                .replace(INITIAL_ROW.1, INITIAL_ROW.0);
            assert!(own.ends_with(single), "{scene} {i}: the single input");
            assert_eq!(run.matches(INITIAL_ROW.1).count(), 1, "{scene} {i}");
            assert!(!run.contains(TRAJECTORY_FILE), "{scene} {i}: its own file");
        });
    }

    #[test]
    fn each_run_of_a_batch_gets_its_own_loop_time_and_step_count() {
        let dir = tempfile::tempdir().unwrap();
        let setups = shipped_setups(CodeName::Liggghts, "rod_end");
        for i in 0..setups.len() {
            std::fs::write(
                dir.path().join(batch_trajectory_file(i)),
                format!("0 0 1 0\n1e-6 {i}e-9 1 5\n"),
            )
            .unwrap();
        }
        let loop_line = |t: f64, s: &CodeSetup| {
            format!(
                "Loop time of {t} on 1 procs for {} steps with 1 atoms\n",
                s.steps
            )
        };
        let header = "LIGGGHTS (Version LIGGGHTS-PUBLIC 3.8.0, compiled today)\n";
        let mut log = String::from(header);
        for (i, s) in setups.iter().enumerate() {
            log += &loop_line(0.5 * (i + 1) as f64, s);
        }
        for (i, run) in parse_batch(&setups, dir.path(), &log)
            .into_iter()
            .enumerate()
        {
            let run = run.unwrap();
            assert_eq!(run.loop_time, Some(0.5 * (i + 1) as f64));
            let written: f64 = format!("{i}e-9").parse().unwrap();
            assert_eq!(run.trajectory.overlap[1].to_bits(), written.to_bits());
            assert!(run.version.unwrap().starts_with("LIGGGHTS-PUBLIC"));
        }
        // A run that stopped short is refused, as a single run is.
        let mut stopped = setups.clone();
        stopped[1].steps -= 1;
        let mut short = String::from(header);
        for s in &stopped {
            short += &loop_line(0.5, s);
        }
        let runs = parse_batch(&setups, dir.path(), &short);
        assert!(
            matches!(runs[1], Err(ParseError::StepCount { .. })),
            "{runs:?}"
        );
    }
}
