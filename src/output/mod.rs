//! Everything a command hands to a person or a tool: one exporter per format (table, JSON,
//! CSV, Markdown) shared by every command, the plots, and safe file writes.
//!
//! A command's result is a typed, serialisable summary implementing [`Summary`]: JSON is its
//! serde form, CSV its flat records (one header, rows of constant width), and the table and
//! Markdown forms lay out the same [`Section`]s.

pub(crate) mod chart;
pub(crate) mod csv_record;
pub use csv_record::{CsvRecords, RecordError, header_of};
pub(crate) mod files;
mod fit;
pub use fit::{table_at_width, table_width};
pub(crate) mod invocation;
pub mod report_page;
pub(crate) mod restitution_plot;
pub(crate) mod work_precision_plot;

use comfy_table::{Table, presets::UTF8_FULL_CONDENSED};
use serde::Serialize;
use thiserror::Error;

/// Output format of a command.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// Aligned tables for people.
    Table,
    /// One JSON document.
    Json,
    /// CSV with a header row.
    Csv,
    /// Markdown tables.
    Markdown,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 4] = [Format::Table, Format::Json, Format::Csv, Format::Markdown];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Format::Table => "table",
            Format::Json => "json",
            Format::Csv => "csv",
            Format::Markdown => "markdown",
        }
    }

    /// The format called `name`, if there is one.
    pub(crate) fn from_name(name: &str) -> Option<Format> {
        Format::ALL.into_iter().find(|f| f.name() == name)
    }
}

impl std::fmt::Display for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A summary that cannot be written in a format.
#[derive(Debug, Error)]
pub enum OutputError {
    /// JSON serialisation failed.
    #[error("writing JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// CSV serialisation failed.
    #[error("writing CSV: {0}")]
    Csv(#[from] csv::Error),
    /// A CSV record could not be written.
    #[error(transparent)]
    Record(#[from] csv_record::RecordError),
    /// A figure could not be drawn.
    #[error("drawing the {figure} figure: {reason}")]
    Plot {
        /// Which figure.
        figure: &'static str,
        /// Why.
        reason: String,
    },
    /// A table's rows differ in width from its header.
    #[error("table `{title}` has a row of {found} cells under {expected} headers")]
    RaggedTable {
        /// The table's title.
        title: String,
        /// Headers.
        expected: usize,
        /// Cells in the offending row.
        found: usize,
    },
}

/// Output that could not be laid out is not the input's fault.
impl crate::error::Blame for OutputError {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// One table of a summary as people read it: a title line, a header, rows of formatted
/// cells, and lines of notes under it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Section {
    /// The line above the table (the Markdown heading).
    pub title: Option<String>,
    /// Column headers.
    pub headers: Vec<String>,
    /// Formatted cells, one row per line, as wide as the header.
    pub rows: Vec<Vec<String>>,
    /// Lines under the table.
    pub notes: Vec<String>,
}

impl Section {
    /// A section with `headers` and no rows yet.
    pub(crate) fn new(title: Option<String>, headers: &[&str]) -> Section {
        Section {
            title,
            headers: headers.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// Lines of text with no table (an empty header).
    pub(crate) fn text(lines: Vec<String>) -> Section {
        Section {
            notes: lines,
            ..Section::default()
        }
    }

    fn check(&self) -> Result<(), OutputError> {
        match self.rows.iter().find(|r| r.len() != self.headers.len()) {
            Some(row) => Err(OutputError::RaggedTable {
                title: self.title.clone().unwrap_or_default(),
                expected: self.headers.len(),
                found: row.len(),
            }),
            None => Ok(()),
        }
    }
}

/// A command's typed result, writable in every [`Format`].
pub trait Summary: Serialize {
    /// One CSV row: a flat struct whose fields are the columns.
    type Record: Serialize;
    /// The CSV rows.
    fn records(&self) -> Vec<Self::Record>;
    /// The tables people read (table and Markdown formats).
    fn sections(&self) -> Vec<Section>;
    /// Lines after every section (table and Markdown formats): how to reproduce it.
    fn footer(&self) -> Vec<String> {
        Vec::new()
    }
    /// How many leading columns name a row: a table split to fit a width repeats them in every
    /// part ([`table_at_width`]).
    fn key_columns(&self) -> usize {
        1
    }
}

/// Write `summary` in `format`.
pub fn export<S: Summary>(summary: &S, format: Format) -> Result<String, OutputError> {
    match format {
        Format::Json => Ok(serde_json::to_string_pretty(summary)? + "\n"),
        Format::Csv => csv_string(&summary.records()),
        Format::Table | Format::Markdown => {
            let markdown = format == Format::Markdown;
            let mut text = String::new();
            for section in summary.sections() {
                section.check()?;
                if let Some(title) = &section.title {
                    text += &if markdown {
                        format!("### {title}\n\n")
                    } else {
                        format!("{title}\n")
                    };
                }
                if !section.headers.is_empty() {
                    if markdown {
                        text += &markdown_table(&section.headers, &section.rows);
                        text.push('\n');
                    } else {
                        let mut table = new_table(&section.headers);
                        for row in &section.rows {
                            table.add_row(row.clone());
                        }
                        text += &format!("{table}\n");
                    }
                }
                for line in &section.notes {
                    text += &format!("{line}\n");
                }
                if markdown && !section.notes.is_empty() {
                    text.push('\n');
                }
            }
            for line in summary.footer() {
                text += &format!("{line}\n");
            }
            Ok(text)
        }
    }
}

/// A table in the crate's style.
fn new_table(headers: &[String]) -> Table {
    let mut t = Table::new();
    t.load_style(UTF8_FULL_CONDENSED);
    t.set_header(headers.to_vec());
    t
}

/// One line of a Markdown table; `|` inside a cell is escaped.
pub(crate) fn markdown_row(cells: &[String]) -> String {
    let escape = |cell: &String| cell.replace('|', "\\|");
    format!(
        "| {} |\n",
        cells.iter().map(escape).collect::<Vec<_>>().join(" | ")
    )
}

/// A table in Markdown.
fn markdown_table(headers: &[String], rows: &[Vec<String>]) -> String {
    let line = markdown_row;
    let mut text = line(headers);
    text += &format!("|{}\n", "---|".repeat(headers.len()));
    for row in rows {
        text += &line(row);
    }
    text
}

/// Serialise rows as CSV with a header; every row must have the header's width.
pub(crate) fn csv_string<T: Serialize>(rows: &[T]) -> Result<String, OutputError> {
    let Some(first) = rows.first() else {
        return Ok(String::new());
    };
    let mut records = csv_record::CsvRecords::default();
    for row in rows {
        records.push(row)?;
    }
    let bytes = [csv_record::header_of(first)?, records.into_bytes()].concat();
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Seven significant digits in scientific form (`n/a` for NaN).
pub(crate) fn sci(x: f64) -> String {
    if x.is_nan() {
        "n/a".to_string()
    } else {
        format!("{x:.6e}")
    }
}

/// A signed relative difference with three significant digits.
pub(crate) fn signed(x: f64) -> String {
    format!("{x:+.2e}")
}

/// An energy, J, in the unit that shows four decimals of it (J, mJ, µJ, nJ, pJ; scientific
/// below a picojoule), so that a small body's energy does not print as `0.0000 J`.
pub(crate) fn joules(x: f64) -> String {
    for (scale, unit) in [
        (1.0, "J"),
        (1e-3, "mJ"),
        (1e-6, "µJ"),
        (1e-9, "nJ"),
        (1e-12, "pJ"),
    ] {
        if x.abs() >= scale {
            return format!("{:.4} {unit}", x / scale);
        }
    }
    format!("{x:.4e} J")
}

/// A duration, s, in convenient units.
pub(crate) fn seconds(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.3} s")
    } else if s >= 1e-3 {
        format!("{:.3} ms", s * 1e3)
    } else {
        format!("{:.2} µs", s * 1e6)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Demo {
        rows: Vec<(String, f64)>,
    }

    #[derive(Serialize)]
    struct DemoRecord {
        name: String,
        value: f64,
    }

    impl Summary for Demo {
        type Record = DemoRecord;
        fn records(&self) -> Vec<DemoRecord> {
            self.rows
                .iter()
                .map(|(name, value)| DemoRecord {
                    name: name.clone(),
                    value: *value,
                })
                .collect()
        }
        fn sections(&self) -> Vec<Section> {
            let mut s = Section::new(Some("demo".into()), &["name", "value"]);
            for (name, value) in &self.rows {
                s.rows.push(vec![name.clone(), sci(*value)]);
            }
            vec![s]
        }
    }

    #[test]
    fn every_format_writes_the_same_rows() {
        let demo = Demo {
            rows: vec![("a|b".into(), 1.5), ("c".into(), -2.0)],
        };
        let csv = export(&demo, Format::Csv).unwrap();
        assert_eq!(csv, "name,value\na|b,1.5\nc,-2.0\n");
        let md = export(&demo, Format::Markdown).unwrap();
        assert!(
            md.starts_with("### demo\n\n| name | value |\n|---|---|\n| a\\|b |"),
            "{md}"
        );
        let json: serde_json::Value =
            serde_json::from_str(&export(&demo, Format::Json).unwrap()).unwrap();
        assert_eq!(json["rows"][1][1], -2.0);
        let table = export(&demo, Format::Table).unwrap();
        assert!(
            table.contains("1.500000e0") && table.starts_with("demo\n"),
            "{table}"
        );
    }

    #[test]
    fn a_ragged_table_is_an_error_not_a_shifted_column() {
        struct Ragged;
        impl Serialize for Ragged {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_unit()
            }
        }
        impl Summary for Ragged {
            type Record = ();
            fn records(&self) -> Vec<()> {
                Vec::new()
            }
            fn sections(&self) -> Vec<Section> {
                let mut s = Section::new(None, &["a", "b"]);
                s.rows.push(vec!["1".into()]);
                vec![s]
            }
        }
        assert!(matches!(
            export(&Ragged, Format::Table),
            Err(OutputError::RaggedTable { .. })
        ));
    }

    #[test]
    fn format_names_round_trip() {
        for f in Format::ALL {
            assert_eq!(Format::from_name(f.name()), Some(f));
        }
    }
}
