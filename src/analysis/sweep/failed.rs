//! Where a sweep's failed points are told: how many rows failed, the lines of the output they
//! are on, and the first one's error (a code's error names the log it kept).

use std::fmt::Write as _;

/// Most line numbers a summary lists.
pub(crate) const LISTED_LINES: usize = 10;

/// The first failed row of an output.
#[derive(Clone, Debug, PartialEq)]
pub struct FirstFailure {
    /// Its line in the output (1-based, a CSV header is line 1).
    pub line: usize,
    /// Its point's index in the grid.
    pub point: usize,
    /// Its `status` cell: the error.
    pub error: String,
}

/// The failed rows of a sweep's output.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FailedRows {
    /// How many rows failed.
    pub count: usize,
    /// The lines of the first [`LISTED_LINES`] of them.
    pub lines: Vec<usize>,
    /// The first of them.
    pub first: Option<FirstFailure>,
}

impl FailedRows {
    /// Note a failed row of `point` on `line` with the error `status`.
    pub(crate) fn record(&mut self, line: usize, point: usize, status: &str) {
        self.count += 1;
        if self.lines.len() < LISTED_LINES {
            self.lines.push(line);
        }
        if self.first.is_none() {
            self.first = Some(FirstFailure {
                line,
                point,
                error: status.to_string(),
            });
        }
    }

    /// Whether no row failed.
    pub(crate) fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// One line: how many of `points` failed, where their errors are in `place`, and the
    /// first error.
    pub(crate) fn summary(&self, points: usize, place: &str) -> String {
        let mut text = format!(
            "{} of {points} points failed; their errors are in the status column of {place}, line{} ",
            self.count,
            if self.count == 1 { "" } else { "s" }
        );
        let listed: Vec<String> = self.lines.iter().map(usize::to_string).collect();
        text += &listed.join(", ");
        if self.count > self.lines.len() {
            let _ = write!(text, " and {} more", self.count - self.lines.len());
        }
        if let Some(first) = &self.first {
            let _ = write!(
                text,
                "; the first (line {}, point {}): {}",
                first.line, first.point, first.error
            );
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_summary_lists_the_first_lines_and_counts_the_rest() {
        let mut failed = FailedRows::default();
        for i in 0..12 {
            failed.record(2 + i, 10 + i, &format!("error {i}"));
        }
        assert_eq!(
            failed.summary(30, "out.csv"),
            "12 of 30 points failed; their errors are in the status column of out.csv, lines \
             2, 3, 4, 5, 6, 7, 8, 9, 10, 11 and 2 more; the first (line 2, point 10): error 0"
        );
        let mut one = FailedRows::default();
        one.record(
            7,
            5,
            "lammps: exited with exit status: 3; log kept in /tmp/x/log.txt",
        );
        assert_eq!(
            one.summary(9, "standard output"),
            "1 of 9 points failed; their errors are in the status column of standard output, \
             line 7; the first (line 7, point 5): lammps: exited with exit status: 3; log kept \
             in /tmp/x/log.txt"
        );
    }
}
