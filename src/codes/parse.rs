//! Reading a code's output back: the errors a parser reports, the column reader the LIGGGHTS
//! and LAMMPS drivers share, and the readers of what the Python drivers' scripts (YADE's,
//! Kratos') print and write.

use std::path::PathBuf;

use thiserror::Error;

use crate::model::tangential::PlaneMotion;
use crate::model::trajectory::{CodeTrajectory, TrajectoryError};

/// Output of a code that cannot be read as the run asked.
#[derive(Debug, Error)]
pub enum ParseError {
    /// A file the run should have written cannot be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file the run wrote is empty.
    #[error("{file} is empty")]
    Empty {
        /// The file.
        file: String,
    },
    /// A row that is not what the format says.
    #[error("{file} line {line}: {reason}")]
    Row {
        /// The file.
        file: String,
        /// Line number, from 1.
        line: usize,
        /// What is wrong with it, with the text.
        reason: String,
    },
    /// A column the header should name is missing.
    #[error("{file}: header lacks `{column}`: {header}")]
    MissingColumn {
        /// The file.
        file: String,
        /// The column.
        column: &'static str,
        /// The header as written.
        header: String,
    },
    /// The trajectory has a different number of rows than the steps asked for.
    #[error("{file} has {rows} rows, expected {expected} (the initial state and every step)")]
    RowCount {
        /// The file.
        file: String,
        /// Rows found.
        rows: u64,
        /// Rows expected.
        expected: u64,
    },
    /// The code ran a different number of steps than asked.
    #[error("the code ran {ran} steps, {asked} asked")]
    StepCount {
        /// Steps the code reports.
        ran: u64,
        /// Steps asked.
        asked: u64,
    },
    /// An oblique impact's run printed no motion along the contact plane after its steps
    /// (no line `MILLIMPACT_TANGENTIAL VT OMEGA`, or one that does not read as numbers).
    #[error("no line `{word} VT OMEGA` with the motion along the contact plane after the run")]
    NoPlaneMotion {
        /// The line's first word.
        word: &'static str,
    },
    /// A reported value is not a number.
    #[error("bad {field} `{value}`")]
    BadValue {
        /// Which value.
        field: &'static str,
        /// As written.
        value: String,
    },
    /// A force the run should not have had: a stock contact law acted beside a force the
    /// harness applies itself (kratos-paper), by up to `mismatch` N beyond the rounding of the
    /// code's own sum.
    #[error(
        "a stock contact law acted: a node's total force differed from the applied force by {mismatch:e} N beyond rounding"
    )]
    ForeignForce {
        /// The largest difference beyond rounding, N.
        mismatch: f64,
    },
    /// The trajectory cannot give an impact's figures.
    #[error(transparent)]
    Trajectory(#[from] TrajectoryError),
}

/// The text of the file at `path` that a run wrote, or why it cannot be read.
pub(crate) fn read_output(path: PathBuf) -> Result<String, ParseError> {
    std::fs::read_to_string(&path).map_err(|source| ParseError::Read { path, source })
}

/// Read a trajectory written as whitespace-separated columns `time overlap approach_velocity
/// normal_force`, one row per line; blank lines and `#` comments are skipped. `file` names the
/// file in error messages.
pub(crate) fn parse_columns(text: &str, file: &str) -> Result<CodeTrajectory, ParseError> {
    let mut out = CodeTrajectory::default();
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let row_error = |reason: String| ParseError::Row {
            file: file.to_string(),
            line: number + 1,
            reason,
        };
        let values: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|e| row_error(format!("{e}: {line:?}")))?;
        let [t, overlap, approach, force] = values[..] else {
            return Err(row_error(format!(
                "expected 4 columns, found {}",
                values.len()
            )));
        };
        out.push_row(t, overlap, approach, force);
    }
    Ok(out)
}

/// The value after `key` on the `MILLIMPACT` lines a driver's Python script prints (YADE's and
/// Kratos' scripts report their figures so), up to the next blank.
pub(crate) fn log_value<'a>(log: &'a str, key: &str) -> Option<&'a str> {
    log.lines()
        .filter_map(|l| l.trim().strip_prefix("MILLIMPACT "))
        .flat_map(|rest| rest.split_whitespace())
        .find_map(|field| field.strip_prefix(key))
}

/// The trajectory file a Python driver's single script writes (YADE's, Kratos').
pub(crate) const CSV_TRAJECTORY_FILE: &str = "trajectory.csv";

/// Read a trajectory written as comma-separated columns under a header that names them
/// (`time`, `overlap`, `approach_velocity`, `normal_force`, in any order, among others), as
/// the Python drivers' scripts write it. `file` names the file in error messages.
pub(crate) fn parse_csv_columns(text: &str, file: &str) -> Result<CodeTrajectory, ParseError> {
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header = lines.next().ok_or_else(|| ParseError::Empty {
        file: file.to_string(),
    })?;
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |name: &'static str| {
        columns
            .iter()
            .position(|c| *c == name)
            .ok_or_else(|| ParseError::MissingColumn {
                file: file.to_string(),
                column: name,
                header: header.to_string(),
            })
    };
    let (it, iy, iv, iff) = (
        find("time")?,
        find("overlap")?,
        find("approach_velocity")?,
        find("normal_force")?,
    );
    let mut t = CodeTrajectory::default();
    for (row, line) in lines.enumerate() {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != columns.len() {
            return Err(ParseError::Row {
                file: file.to_string(),
                line: row + 2,
                reason: format!("{} fields, header has {}", fields.len(), columns.len()),
            });
        }
        let value = |i: usize| {
            fields[i].parse::<f64>().map_err(|e| ParseError::Row {
                file: file.to_string(),
                line: row + 2,
                reason: format!("`{}`: {e}", fields[i]),
            })
        };
        t.push_row(value(it)?, value(iy)?, value(iv)?, value(iff)?);
    }
    Ok(t)
}

/// What a run of an oblique impact leaves with along the contact plane: the ball's motion and,
/// for a pair, the partner's (as the code printed them after its steps).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TangentialRun {
    /// The moving ball.
    pub ball: PlaneMotion,
    /// The partner ball, for a pair.
    pub partner: Option<PlaneMotion>,
}

impl TangentialRun {
    /// The motions on the last line starting with `word` in `log` (`WORD VT OMEGA [VT2
    /// OMEGA2]`); `None` where there is none or it does not read as numbers.
    pub fn from_log(log: &str, word: &str) -> Option<TangentialRun> {
        let line = log
            .lines()
            .rev()
            .find_map(|l| l.trim().strip_prefix(word))?;
        let values: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .ok()?;
        let motion = |k: usize| PlaneMotion {
            tangential_velocity: values[k],
            angular_velocity: values[k + 1],
        };
        match values.len() {
            2 => Some(TangentialRun {
                ball: motion(0),
                partner: None,
            }),
            4 => Some(TangentialRun {
                ball: motion(0),
                partner: Some(motion(2)),
            }),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_columns_reads_rows_and_names_bad_lines() {
        let t = parse_columns("# t d v f\n0 0 2 0\n\n1e-7 2e-7 1.9 5\n", "traj").unwrap();
        assert_eq!(t.time, vec![0.0, 1e-7]);
        assert_eq!(t.normal_force, vec![0.0, 5.0]);
        let err = parse_columns("0 0 2\n", "traj").unwrap_err().to_string();
        assert!(
            err.contains("traj line 1") && err.contains("4 columns"),
            "{err}"
        );
        assert!(parse_columns("0 0 x 1\n", "traj").is_err());
    }
}
