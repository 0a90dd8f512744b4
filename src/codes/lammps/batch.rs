//! LAMMPS batches: many impacts in one process, one after another, in any scene. The batch
//! input is the single runs' inputs in sequence, each but the last followed by `clear` (which
//! deletes every atom, fix, group and setting and restores the defaults, as a fresh start
//! would); each writes its own trajectory file. So every impact steps through the very input and
//! the very state of its single run and gives its trajectory to the last bit (tested for every
//! scene and both builds), while the process's start-up is paid once.
//!
//! Impacts side by side in one run were the other way: each sphere then needs its own group for
//! its own `fix wall/gran`, LAMMPS allows 32 groups, and two balls need a pair style whose
//! coefficients differ per pair. In sequence there is no such limit.

use std::path::Path;

use crate::codes::batch::{SEQUENCE_INPUT_FILE, render_in_sequence};
use crate::codes::lammps::{
    LOG_FILE, TRAJECTORY_FILE, parse_loop_time, parse_trajectory, parse_version, run_args,
};
use crate::codes::parse::{ParseError, read_output};
use crate::codes::{BatchError, CodeError, CodeSetup, ParsedRun, RenderedInput};

/// Most impacts in one batch: each run adds about 2.5 kB to the screen output, which is kept
/// whole up to [`crate::codes::runner::MAX_LOG_BYTES`].
pub(crate) const MAX_BATCH: usize = 256;

/// The batch input file.
pub(crate) const BATCH_INPUT_FILE: &str = SEQUENCE_INPUT_FILE;

/// The trajectory file of impact `i` (from 0) of a batch.
pub(crate) fn batch_trajectory_file(i: usize) -> String {
    format!("trajectory-{}.txt", i + 1)
}

/// The batch input of the single inputs `single` renders for `setups`, in sequence, each
/// writing its own trajectory file; `source` names the file that made it.
pub(crate) fn render_sequence(
    source: &str,
    setups: &[CodeSetup],
    single: impl Fn(&CodeSetup) -> Result<RenderedInput, CodeError>,
) -> Result<RenderedInput, BatchError> {
    let own_file = format!(" file {TRAJECTORY_FILE} ");
    render_in_sequence(
        "LAMMPS",
        source,
        setups,
        MAX_BATCH,
        // The single input names its trajectory file once, in its `fix print`.
        |i, setup| {
            Ok(single(setup)?.text.replacen(
                &own_file,
                &format!(" file {} ", batch_trajectory_file(i)),
                1,
            ))
        },
        &run_args(BATCH_INPUT_FILE),
    )
}

/// The `Loop time of` seconds of every run in `log`, in order.
fn loop_times(log: &str) -> Vec<Option<f64>> {
    log.lines()
        .filter(|l| l.trim_start().starts_with("Loop time of "))
        .map(parse_loop_time)
        .collect()
}

/// Each impact's run from a batch: its own trajectory, and its own run's loop time.
pub(crate) fn parse_batch(
    setups: &[CodeSetup],
    workdir: &Path,
    log: &str,
) -> Vec<Result<ParsedRun, ParseError>> {
    let file_log = std::fs::read_to_string(workdir.join(LOG_FILE)).unwrap_or_default();
    let version = parse_version(log).or_else(|| parse_version(&file_log));
    let mut loops = loop_times(log);
    if loops.len() != setups.len() {
        loops = loop_times(&file_log);
    }
    setups
        .iter()
        .enumerate()
        .map(|(i, _)| {
            let text = read_output(workdir.join(batch_trajectory_file(i)))?;
            Ok(ParsedRun {
                trajectory: parse_trajectory(&text)?,
                loop_time: loops.get(i).copied().flatten(),
                version: version.clone(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::CodeName;
    use crate::codes::batch_fns::check_runs_in_sequence;
    use crate::codes::setup::shipped_setups;

    #[test]
    fn a_batch_is_the_single_inputs_in_sequence_each_writing_its_own_file() {
        check_runs_in_sequence(CodeName::Lammps, |scene, i, run, single| {
            let own = run.replace(&batch_trajectory_file(i), TRAJECTORY_FILE);
            assert!(own.ends_with(single), "{scene} {i}: the single input");
            assert!(run.contains(&format!(" file {} ", batch_trajectory_file(i))));
        });
    }

    #[test]
    fn each_run_of_a_batch_gets_its_own_loop_time() {
        let dir = tempfile::tempdir().unwrap();
        let setups = shipped_setups(CodeName::Lammps, "ball_ball");
        for i in 0..setups.len() {
            std::fs::write(
                dir.path().join(batch_trajectory_file(i)),
                format!(
                    "# time overlap approach_velocity normal_force\n0 0 1 0\n1e-6 {i}e-9 1 5\n"
                ),
            )
            .unwrap();
        }
        let log = "LAMMPS (29 Sep 2021 - Update 2)\nLoop time of 0.25 on 1 procs for 2 steps with 2 atoms\n\
                   Loop time of 0.5 on 1 procs for 2 steps with 2 atoms\nLoop time of 0.75 on 1 procs for 2 steps with 2 atoms\n";
        let runs = parse_batch(&setups, dir.path(), log);
        for (i, run) in runs.into_iter().enumerate() {
            let run = run.unwrap();
            assert_eq!(run.loop_time, Some(0.25 * (i + 1) as f64));
            assert_eq!(run.version.as_deref(), Some("29 Sep 2021 - Update 2"));
            let written: f64 = format!("{i}e-9").parse().unwrap();
            assert_eq!(run.trajectory.overlap[1].to_bits(), written.to_bits());
        }
        assert_eq!(
            CodeName::Lammps.driver().batch().unwrap().max_batch(),
            MAX_BATCH
        );
    }
}
