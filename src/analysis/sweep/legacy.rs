//! `sweep`: one impact per loss coefficient over a range (the paper's Figure 3).
//!
//! Rows stream: they are computed in chunks on several threads, written in η order as each
//! chunk is done, and not kept (but for the table format, whose column widths need every row).

use std::io::Write;
use std::sync::atomic::AtomicBool;

use serde::Serialize;

use super::error::SweepError;
use crate::analysis::run::{IntegrationOptions, RunRecord, RunReport, solve_failure};
use crate::error::UserError;
use crate::model::case::Case;
use crate::model::count::round_count;
use crate::model::law::PaperLaw;
use crate::output::csv_record::{CsvRecords, header_of};
use crate::output::{Format, Section, Summary, export, markdown_row, sci, signed};
use crate::solve::paper::{Settings, check_step, solve_many};

/// Most values a sweep may have (a sweep file's limit).
pub(crate) const MAX_SWEEP_POINTS: usize = super::grid::MAX_POINTS;

/// Loss coefficients `start + i × step` for `i` below `count`, made on demand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EtaRange {
    /// The first.
    pub start: f64,
    /// The spacing.
    pub step: f64,
    /// How many.
    pub count: usize,
}

impl EtaRange {
    /// Value `i`.
    pub(crate) fn get(&self, i: usize) -> f64 {
        self.start + i as f64 * self.step
    }

    /// The values of `range`.
    pub(crate) fn values(&self, range: std::ops::Range<usize>) -> Vec<f64> {
        range.map(|i| self.get(i)).collect()
    }
}

/// Parse `START:STOP:STEP` into the values of η it names, STOP included.
#[cfg(test)]
pub(crate) fn parse_range(text: &str) -> Result<Vec<f64>, UserError> {
    let range = parse_eta_range(text)?;
    Ok(range.values(0..range.count))
}

/// Parse `START:STOP:STEP` into the range of η it names, STOP included.
pub(crate) fn parse_eta_range(text: &str) -> Result<EtaRange, UserError> {
    let allowed = "START:STOP:STEP with 0 <= START <= STOP < 1 and STEP > 0";
    let refuse = |allowed: &str| UserError::argument("--loss-coefficient", text, allowed);
    let numbers: Option<Vec<f64>> = text.split(':').map(|p| p.trim().parse().ok()).collect();
    let Some([start, stop, step]) = numbers
        .as_deref()
        .and_then(|v| <[f64; 3]>::try_from(v).ok())
    else {
        return Err(refuse(allowed));
    };
    let finite = start.is_finite() && stop.is_finite() && step.is_finite();
    if !finite || start < 0.0 || stop >= 1.0 || start > stop || step <= 0.0 {
        return Err(refuse(allowed));
    }
    // The count is checked as a float before it becomes an integer: a tiny step must be
    // refused, not wrap.
    let count = ((stop - start) / step + 1e-9).floor() + 1.0;
    if !(count.is_finite() && count <= MAX_SWEEP_POINTS as f64) {
        return Err(refuse(&format!("at most {MAX_SWEEP_POINTS} values")));
    }
    let count = round_count(count)
        .and_then(|n| usize::try_from(n).ok())
        .ok_or_else(|| refuse(&format!("at most {MAX_SWEEP_POINTS} values")))?;
    Ok(EtaRange { start, step, count })
}

/// The rows of a sweep.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepReport {
    /// One row per η.
    pub rows: Vec<RunRecord>,
    /// The command that reproduces it.
    pub command: String,
}

/// The headers of the table people read.
const HEADERS: [&str; 6] = [
    "η",
    "COR",
    "exact",
    "COR error",
    "peak (m)",
    "contact time (s)",
];

/// The title of the table people read.
fn title(case: &str, method: &str) -> String {
    format!("{case}: COR against η by {method}")
}

/// A row's cells in the table people read.
fn cells(r: &RunRecord) -> Vec<String> {
    vec![
        r.loss_coefficient.to_string(),
        sci(r.figures.cor),
        sci(r.exact.cor),
        signed(r.error.cor),
        sci(r.figures.peak_deformation),
        sci(r.figures.contact_time),
    ]
}

impl Summary for SweepReport {
    type Record = RunRecord;

    fn records(&self) -> Vec<RunRecord> {
        self.rows.clone()
    }

    fn sections(&self) -> Vec<Section> {
        let mut t = Section::new(
            self.rows.first().map(|r| title(&r.case, r.method)),
            &HEADERS,
        );
        t.rows = self.rows.iter().map(cells).collect();
        vec![t]
    }

    fn footer(&self) -> Vec<String> {
        vec![format!("reproduce: {}", self.command)]
    }
}

/// The rows of `case` at the loss coefficients `values` with `settings`, in order: each the
/// row of [`run_case`] at that η (rk4-event solves them in lanes, to the same bits).
pub(crate) fn rows_at(
    case: &Case,
    values: &[f64],
    settings: &Settings,
) -> Result<Vec<RunRecord>, SweepError> {
    let mut at = case.clone();
    let items: Vec<(PaperLaw, f64)> = values
        .iter()
        .map(|&eta| {
            at.loss_coefficient = eta;
            (at.law(), at.impact_velocity)
        })
        .collect();
    values
        .iter()
        .zip(solve_many(&items, settings))
        .map(|(&eta, outcome)| {
            at.loss_coefficient = eta;
            let outcome = outcome.map_err(|e| solve_failure(&case.path, e))?;
            Ok(RunReport::new(&at, settings.method, &outcome).row())
        })
        .collect()
}

/// A chunk of rows written out, and its points (η, COR) when they are to be drawn.
type EncodedChunk = (Vec<u8>, Vec<(f64, f64)>);

/// η values per chunk of a streamed sweep.
const CHUNK: usize = 64;

/// About the bytes of one CSV row.
const CSV_ROW_BYTES: usize = 400;

/// A case over a range of η, its rows streamed.
pub struct Streamed<'a> {
    /// The case.
    pub case: &'a Case,
    /// The loss coefficients.
    pub values: EtaRange,
    /// The integration options (checked for every η before the first row is written).
    pub options: IntegrationOptions,
    /// The command that reproduces it.
    pub command: String,
    /// Worker threads.
    pub jobs: usize,
}

impl Streamed<'_> {
    /// Check the options at every η: a bad option or a step beyond the stability limit at any
    /// η is refused before a row is written.
    pub fn settings(&self) -> Result<Settings, SweepError> {
        let mut at = self.case.clone();
        let mut settings = None;
        for eta in (0..self.values.count).map(|i| self.values.get(i)) {
            at.loss_coefficient = eta;
            let s = match settings {
                Some(s) => s,
                None => *settings.insert(self.options.settings(&at, false)?),
            };
            check_step(&at.law(), at.impact_velocity, &s)
                .map_err(|e| solve_failure(&self.case.path, e))?;
        }
        settings.ok_or(SweepError::NoValues)
    }

    /// Write the rows to `out` in `format`, as they are done; returns the points (η, COR) when
    /// `points` is asked for (to draw them).
    pub fn write(
        &self,
        format: Format,
        out: &mut dyn Write,
        points: bool,
    ) -> Result<Vec<(f64, f64)>, SweepError> {
        let settings = self.settings()?;
        let stop = AtomicBool::new(false);
        let mut plotted = Vec::new();
        if format == Format::Table {
            // Column widths need every row.
            let mut rows = Vec::new();
            let work = |range: std::ops::Range<usize>| {
                rows_at(self.case, &self.values.values(range), &settings)
            };
            let mut failure = None;
            super::ordered_chunks(
                self.values.count,
                CHUNK,
                self.jobs,
                &stop,
                &work,
                &mut |chunk| match chunk {
                    Ok(chunk) => {
                        rows.extend(chunk);
                        Ok(())
                    }
                    Err(e) => {
                        failure = Some(e);
                        Err(std::io::Error::other("stopped"))
                    }
                },
            )
            .or_else(|e| if failure.is_some() { Ok(()) } else { Err(e) })?;
            if let Some(e) = failure {
                return Err(e);
            }
            if points {
                plotted = rows
                    .iter()
                    .map(|r| (r.loss_coefficient, r.figures.cor))
                    .collect();
            }
            let report = SweepReport {
                rows,
                command: self.command.clone(),
            };
            out.write_all(export(&report, format)?.as_bytes())?;
            return Ok(plotted);
        }
        let head = match format {
            Format::Json => "{\n  \"rows\": [\n".to_string(),
            Format::Markdown => {
                let headers: Vec<String> = HEADERS.iter().map(|h| h.to_string()).collect();
                format!(
                    "### {}\n\n{}|{}\n",
                    title(&self.case.name, settings.method.name()),
                    markdown_row(&headers),
                    "---|".repeat(HEADERS.len())
                )
            }
            _ => String::new(),
        };
        out.write_all(head.as_bytes())?;
        let work = |range: std::ops::Range<usize>| -> Result<EncodedChunk, SweepError> {
            let first = range.start == 0;
            let rows = rows_at(self.case, &self.values.values(range), &settings)?;
            let plotted = if points {
                rows.iter()
                    .map(|r| (r.loss_coefficient, r.figures.cor))
                    .collect()
            } else {
                Vec::new()
            };
            let mut bytes = Vec::new();
            match format {
                Format::Csv => {
                    // The header as the csv crate writes it, then the records in the same
                    // bytes (`CsvRecords`).
                    let mut records = CsvRecords::with_capacity(CSV_ROW_BYTES * rows.len());
                    for row in &rows {
                        records.push(row)?;
                    }
                    bytes = match rows.first().filter(|_| first) {
                        Some(row) => [header_of(row)?, records.into_bytes()].concat(),
                        None => records.into_bytes(),
                    };
                }
                Format::Json => {
                    for (i, row) in rows.iter().enumerate() {
                        if !(first && i == 0) {
                            bytes.extend_from_slice(b",\n");
                        }
                        let text = serde_json::to_string_pretty(row)?;
                        for (j, line) in text.lines().enumerate() {
                            if j > 0 {
                                bytes.push(b'\n');
                            }
                            bytes.extend_from_slice(b"    ");
                            bytes.extend_from_slice(line.as_bytes());
                        }
                    }
                }
                _ => {
                    for row in &rows {
                        bytes.extend_from_slice(markdown_row(&cells(row)).as_bytes());
                    }
                }
            }
            Ok((bytes, plotted))
        };
        let mut failure = None;
        super::ordered_chunks(
            self.values.count,
            CHUNK,
            self.jobs,
            &stop,
            &work,
            &mut |chunk| match chunk {
                Ok((bytes, chunk_points)) => {
                    plotted.extend(chunk_points);
                    out.write_all(&bytes)
                }
                Err(e) => {
                    failure = Some(e);
                    Err(std::io::Error::other("stopped"))
                }
            },
        )
        .or_else(|e| if failure.is_some() { Ok(()) } else { Err(e) })?;
        if let Some(e) = failure {
            return Err(e);
        }
        let tail = match format {
            Format::Json => format!(
                "\n  ],\n  \"command\": {}\n}}\n",
                serde_json::to_string(&self.command)?
            ),
            Format::Markdown => format!("\nreproduce: {}\n", self.command),
            _ => String::new(),
        };
        out.write_all(tail.as_bytes())?;
        Ok(plotted)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_includes_its_stop() {
        let v = parse_range("0:0.9:0.1").unwrap();
        assert_eq!(v.len(), 10);
        assert!((v[9] - 0.9).abs() < 1e-12);
        assert_eq!(parse_range("0.35:0.35:0.1").unwrap(), vec![0.35]);
    }

    #[test]
    fn range_refuses_what_is_not_allowed() {
        for bad in [
            "0:1:0.1",
            "0.5:0.1:0.1",
            "0:0.5:0",
            "-0.1:0.5:0.1",
            "0:0.5",
            "a:b:c",
            "0:nan:0.1",
            "0:0.9:1e-300",
            "0:0.9:1e-8",
        ] {
            assert!(parse_range(bad).is_err(), "{bad}");
        }
    }
}
