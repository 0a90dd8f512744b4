//! `sweep CASE --loss-coefficient START:STOP:STEP` (the paper's Figure 3): the grid of one case
//! file over one axis, η, by one method, run as a sweep file's method points are; its rows are
//! the records `run` gives, as a table, JSON, CSV or Markdown.
//!
//! Rows stream: they are computed in chunks on several threads, written in η order as each
//! chunk is done, and not kept (but for the table format, whose column widths need every row).

use std::io::Write;
use std::ops::Range;
use std::sync::atomic::AtomicBool;

use serde::Serialize;
use toml::Table;

use super::error::SweepError;
use super::grid::{Axis, GridPoint, PointCases, ResolvedSource, SweepFile};
use super::point::{GridOptions, method_settings, solve_points};
use crate::analysis::run::{IntegrationOptions, RunRecord, RunReport, solve_failure};
use crate::analysis::source::{Resolution, Source};
use crate::error::UserError;
use crate::model::case::Case;
use crate::output::csv_record::{CsvRecords, header_of};
use crate::output::{Format, Section, Summary, export, markdown_row, sci, signed};
use crate::solve::Method;
use crate::solve::paper::check_step;

/// The loss-coefficient axis that `START:STOP:STEP` names, STOP included; refused as
/// `--loss-coefficient` of the case at `case` (its file).
pub fn loss_coefficient_axis(text: &str, case: &str) -> Result<Axis, UserError> {
    let refuse = |allowed: &str| UserError::CaseArgument {
        case: case.to_string(),
        option: "--loss-coefficient".into(),
        value: text.to_string(),
        allowed: allowed.to_string(),
    };
    let numbers: Option<Vec<f64>> = text.split(':').map(|p| p.trim().parse().ok()).collect();
    let Some([start, stop, step]) = numbers
        .as_deref()
        .and_then(|v| <[f64; 3]>::try_from(v).ok())
        .filter(|v| v.iter().all(|x| x.is_finite()))
        .filter(|&[start, stop, step]| 0.0 <= start && start <= stop && stop < 1.0 && step > 0.0)
    else {
        return Err(refuse(
            "START:STOP:STEP with 0 <= START <= STOP < 1 and STEP > 0",
        ));
    };
    Ok(Axis {
        key: "loss_coefficient".into(),
        values: super::grid::stepped(start, stop, step)
            .ok_or_else(|| refuse(&format!("at most {} values", super::grid::MAX_POINTS)))?,
    })
}

/// The rows of a case over η, as a report (the table format's, which needs every row).
#[derive(Clone, Debug, PartialEq, Serialize)]
struct SweepReport {
    /// One row per η.
    rows: Vec<RunRecord>,
    /// The command that reproduces it.
    command: String,
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

/// η values per chunk.
const CHUNK: usize = 64;

/// About the bytes of one CSV row.
const CSV_ROW_BYTES: usize = 400;

/// A chunk of rows done: its bytes in the format, its rows (the table format's), and its
/// points (η, COR) when they are to be drawn.
struct Chunk {
    bytes: Vec<u8>,
    rows: Vec<RunRecord>,
    points: Vec<(f64, f64)>,
}

/// A case over a range of η by one method, its rows streamed.
pub struct EtaSweep {
    /// The grid: the case over its η axis, one source.
    sweep: SweepFile,
    /// The method.
    method: Method,
    /// The options as given (checked before the first row is written).
    integration: IntegrationOptions,
    /// How the grid runs.
    options: GridOptions,
    /// The command that reproduces it.
    command: String,
}

impl EtaSweep {
    /// `case`, read from its TOML table `base`, over the loss coefficients of `axis`
    /// ([`loss_coefficient_axis`]) by `integration`, on `jobs` threads; `command` reproduces it.
    pub fn new(
        case: Case,
        base: Table,
        axis: Axis,
        integration: IntegrationOptions,
        jobs: usize,
        command: String,
    ) -> EtaSweep {
        // A knob the method does not take is refused by the check, before any row.
        let resolution = match (integration.steps_per_period, integration.rtol) {
            (Some(n), _) => Some(Resolution::StepsPerPeriod(n)),
            (None, Some(r)) => Some(Resolution::Rtol(r)),
            (None, None) => None,
        };
        let source = ResolvedSource {
            source: Source::Method(integration.method),
            resolution,
        };
        EtaSweep {
            sweep: SweepFile::of_case(case, base, axis, source),
            method: integration.method,
            options: GridOptions {
                jobs,
                timeout: std::time::Duration::ZERO,
                periods: integration.periods,
                batch: 1,
                timestep: integration.timestep,
            },
            integration,
            command,
        }
    }

    /// Check the options and every point's step: a bad option, or a step beyond the
    /// stability limit at any η, is refused before a row is written.
    fn check(&self) -> Result<(), SweepError> {
        let case = &self.sweep.base_case;
        self.integration.settings(case, false)?;
        let mut cases = PointCases::new(&self.sweep);
        let mut point = self.sweep.point(0);
        for i in 0..self.sweep.len() {
            self.sweep.point_into(i, &mut point);
            let at = cases.case(&point)?;
            let settings = method_settings(&point, at, &self.options)?;
            check_step(&at.law(), at.impact_velocity, &settings)
                .map_err(|e| solve_failure(&case.path, e))?;
        }
        Ok(())
    }

    /// The records of the points in `range`, in order; the first failure ends them.
    fn records(
        &self,
        range: Range<usize>,
        stop: &AtomicBool,
    ) -> Result<Vec<RunRecord>, SweepError> {
        let points: Vec<GridPoint> = range.map(|i| self.sweep.point(i)).collect();
        let solved = solve_points(&self.sweep, &points, &self.options, stop);
        let mut cases = PointCases::new(&self.sweep);
        points
            .iter()
            .zip(solved)
            .map(|(point, solved)| {
                let (_, _, outcome) = solved?;
                Ok(RunReport::new(cases.case(point)?, self.method, &outcome).row())
            })
            .collect()
    }

    /// The rows of `range` in `format` (the table's kept whole, not written), and their
    /// points when `points` is asked for.
    fn chunk(
        &self,
        range: Range<usize>,
        format: Format,
        points: bool,
        stop: &AtomicBool,
    ) -> Result<Chunk, SweepError> {
        let first = range.start == 0;
        let rows = self.records(range, stop)?;
        let points = match points {
            true => rows
                .iter()
                .map(|r| (r.loss_coefficient, r.figures.cor))
                .collect(),
            false => Vec::new(),
        };
        let mut bytes = Vec::new();
        match format {
            Format::Table => {
                return Ok(Chunk {
                    bytes,
                    rows,
                    points,
                });
            }
            Format::Csv => {
                // The header as the csv crate writes it, then the records in the same bytes
                // (`CsvRecords`).
                let mut records = CsvRecords::with_capacity(CSV_ROW_BYTES * rows.len());
                for row in &rows {
                    records.push(row)?;
                }
                if let Some(row) = rows.first().filter(|_| first) {
                    bytes = header_of(row)?;
                }
                bytes.extend(records.into_bytes());
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
            Format::Markdown => {
                for row in &rows {
                    bytes.extend_from_slice(markdown_row(&cells(row)).as_bytes());
                }
            }
        }
        Ok(Chunk {
            bytes,
            rows: Vec::new(),
            points,
        })
    }

    /// Write the rows to `out` in `format` as they are done, once the options and every
    /// point's step are checked; returns the points (η, COR) when `points` is asked for (to
    /// draw them).
    pub fn write(
        &self,
        format: Format,
        out: &mut dyn Write,
        points: bool,
    ) -> Result<Vec<(f64, f64)>, SweepError> {
        self.check()?;
        let head = match format {
            Format::Json => "{\n  \"rows\": [\n".to_string(),
            Format::Markdown => {
                let headers: Vec<String> = HEADERS.iter().map(|h| h.to_string()).collect();
                format!(
                    "### {}\n\n{}|{}\n",
                    title(&self.sweep.base_case.name, self.method.name()),
                    markdown_row(&headers),
                    "---|".repeat(HEADERS.len())
                )
            }
            _ => String::new(),
        };
        out.write_all(head.as_bytes())?;
        let stop = AtomicBool::new(false);
        let work = |range: Range<usize>| self.chunk(range, format, points, &stop);
        let (mut rows, mut plotted, mut failure) = (Vec::new(), Vec::new(), None);
        super::ordered_chunks(
            self.sweep.len(),
            CHUNK,
            self.options.jobs,
            &stop,
            &work,
            &mut |chunk| match chunk {
                Ok(chunk) => {
                    rows.extend(chunk.rows);
                    plotted.extend(chunk.points);
                    out.write_all(&chunk.bytes)
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
            Format::Table => export(
                &SweepReport {
                    rows,
                    command: self.command.clone(),
                },
                format,
            )?,
            Format::Json => format!(
                "\n  ],\n  \"command\": {}\n}}\n",
                serde_json::to_string(&self.command)?
            ),
            Format::Markdown => format!("\nreproduce: {}\n", self.command),
            Format::Csv => String::new(),
        };
        out.write_all(tail.as_bytes())?;
        Ok(plotted)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(text: &str) -> Result<Vec<f64>, UserError> {
        let axis = loss_coefficient_axis(text, "case.toml")?;
        Ok(axis
            .values
            .iter()
            .map(|v| v.as_float().unwrap_or(f64::NAN))
            .collect())
    }

    #[test]
    fn range_includes_its_stop() {
        let v = values("0:0.9:0.1").unwrap();
        assert_eq!(v.len(), 10);
        assert!((v[9] - 0.9).abs() < 1e-12);
        assert_eq!(values("0.35:0.35:0.1").unwrap(), vec![0.35]);
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
            assert!(values(bad).is_err(), "{bad}");
        }
    }
}
