//! Resuming a sweep's output file: the rows that computed their point are kept as written; a
//! failed row, a row cut off mid-line by a kill, and a row a later row of the same point
//! replaced are dropped, and the points without a kept row run again. The file is read as a
//! stream (one pass to decide, one to copy), so resuming a large output holds a hash per
//! point, not its rows.

use std::collections::{HashMap, HashSet};
use std::io::{BufRead, BufReader, Read, Seek, SeekFrom, Write};
use std::path::Path;

use sha2::{Digest, Sha256};

use super::error::SweepError;
use super::grid::{GridPoint, SweepFile, normal_cell};
use super::row::{PointFigures, RowStatus};
use super::rows::{RowFormat, json_cell};
use crate::error::UserError;
use crate::output::csv_record::CsvRecords;

/// A point's parameters as one number: a hash of its key cells in normal form (128 bits, so
/// that ten million points collide with a chance below 1e-24).
pub(crate) type PointKey = u128;

/// The key of a row whose key cells (in [`SweepFile::key_columns`] order) are `cells`, each
/// already in normal form.
fn key_of<'a>(cells: impl IntoIterator<Item = &'a str>) -> PointKey {
    let mut hash = Sha256::new();
    for cell in cells {
        // Length-prefixed, so that no two lists of cells hash the same bytes.
        hash.update((cell.len() as u64).to_le_bytes());
        hash.update(cell.as_bytes());
    }
    let digest = hash.finalize();
    let mut first = [0u8; 16];
    first.copy_from_slice(&digest[..16]);
    u128::from_le_bytes(first)
}

/// The keys of `points` of `sweep`, as their rows' keys would be: each point's row written
/// as the CSV rows are written and read back (through one buffer and one reader per
/// thousands of points: building a CSV reader costs more than a point's row).
pub fn point_keys(sweep: &SweepFile, points: &[GridPoint]) -> Result<Vec<PointKey>, SweepError> {
    let columns = sweep.columns();
    let at: Vec<usize> = sweep
        .key_columns()
        .iter()
        .filter_map(|k| columns.iter().position(|c| c == k))
        .collect();
    let mut keys = Vec::with_capacity(points.len());
    for chunk in points.chunks(4096) {
        let mut records = CsvRecords::default();
        for p in chunk {
            sweep
                .row(p, PointFigures::default(), RowStatus::default())
                .write_csv(&mut records)?;
        }
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(records.as_bytes());
        for record in reader.records() {
            let record = record?;
            let cells: Vec<String> = at
                .iter()
                .map(|&i| normal_cell(record.get(i).unwrap_or_default()))
                .collect();
            keys.push(key_of(cells.iter().map(String::as_str)));
        }
    }
    Ok(keys)
}

/// What a resumed output holds, and what resuming it does.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Resumed {
    /// The format the file was written in (`None`: it holds no complete line).
    pub format: Option<RowFormat>,
    /// Whether the kept part starts with a CSV header (so none is written again).
    pub has_header: bool,
    /// The keys of the points whose rows are kept: they do not run again.
    pub done: HashSet<PointKey>,
    /// Rows kept, as written.
    pub kept_rows: usize,
    /// Lines of the kept part (the header included): the line after which new rows go.
    pub kept_lines: usize,
    /// Points that have failed rows and no row that computed them: they run again.
    pub retried: usize,
    /// Complete rows dropped: failed ones, and those a later row of their point replaced.
    pub dropped_rows: usize,
    /// Whether a last row cut off mid-line was dropped.
    pub torn: bool,
    /// Byte ranges of the complete part to keep, in order (the header, then each kept row).
    keep: Vec<std::ops::Range<u64>>,
    /// Bytes of the complete part.
    complete: u64,
}

impl Resumed {
    /// Whether the file must be rewritten to hold only what is kept (a row dropped, a torn
    /// last line, a blank line).
    pub(crate) fn rewrites(&self) -> bool {
        let kept: u64 = self.keep.iter().map(|r| r.end - r.start).sum();
        self.torn || kept != self.complete
    }

    /// Copy the kept part of `source` (the file [`read_resumed`] read) to `out`.
    pub(crate) fn copy_kept(&self, source: &Path, out: &mut dyn Write) -> std::io::Result<()> {
        let mut file = std::fs::File::open(source)?;
        // Neighbouring ranges are copied in one read.
        let mut ranges: Vec<std::ops::Range<u64>> = Vec::new();
        for r in &self.keep {
            match ranges.last_mut() {
                Some(last) if last.end == r.start => last.end = r.end,
                _ => ranges.push(r.clone()),
            }
        }
        for r in ranges {
            file.seek(SeekFrom::Start(r.start))?;
            let copied = std::io::copy(&mut (&mut file).take(r.end - r.start), out)?;
            if copied != r.end - r.start {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::UnexpectedEof,
                    format!("{} changed while it was being resumed", source.display()),
                ));
            }
        }
        Ok(())
    }
}

/// The length of the complete part of `file` (up to and with its last newline).
fn complete_length(file: &mut std::fs::File) -> std::io::Result<u64> {
    let length = file.metadata()?.len();
    let mut end = length;
    let mut chunk = vec![0u8; 64 * 1024];
    while end > 0 {
        let start = end.saturating_sub(chunk.len() as u64);
        let n = usize::try_from(end - start).unwrap_or(chunk.len());
        file.seek(SeekFrom::Start(start))?;
        file.read_exact(&mut chunk[..n])?;
        if let Some(at) = chunk[..n].iter().rposition(|&b| b == b'\n') {
            return Ok(start + at as u64 + 1);
        }
        end = start;
    }
    Ok(0)
}

/// One complete row as read: its key cells, its sweep cell, whether it is ok, its bytes.
struct ReadRow {
    key: PointKey,
    sweep: String,
    ok: bool,
    span: std::ops::Range<u64>,
    lines: usize,
}

/// Read the output at `path` of `sweep` for resuming: which points are done, and what is
/// kept. Rows of another sweep, or a file that is not a sweep's output, are refused (exit 2)
/// naming the file.
pub fn read_resumed(path: &Path, sweep: &SweepFile) -> Result<Resumed, SweepError> {
    let name = path.display().to_string();
    let refuse = |allowed: String| UserError::argument("--resume", &name, allowed);
    let read = |source| SweepError::Read {
        path: path.to_path_buf(),
        source,
    };
    let mut file = std::fs::File::open(path).map_err(read)?;
    let complete = complete_length(&mut file).map_err(read)?;
    let total = file.metadata().map_err(read)?.len();
    file.seek(SeekFrom::Start(0)).map_err(read)?;
    let mut reader = BufReader::new(file.take(complete));
    let first = reader
        .fill_buf()
        .map_err(read)?
        .iter()
        .find(|b| !b.is_ascii_whitespace())
        .copied();
    let mut resumed = Resumed {
        torn: complete != total,
        complete,
        ..Resumed::default()
    };
    let key_columns = sweep.key_columns();
    let mut rows = Vec::new();
    match first {
        None => return Ok(resumed),
        Some(b'{') => {
            resumed.format = Some(RowFormat::Jsonl);
            let mut at = 0u64;
            let mut line = String::new();
            let mut number = 0usize;
            loop {
                line.clear();
                let n = reader.read_line(&mut line).map_err(read)? as u64;
                if n == 0 {
                    break;
                }
                number += 1;
                let span = at..at + n;
                at += n;
                if line.trim().is_empty() {
                    continue;
                }
                let object: HashMap<String, serde_json::Value> = serde_json::from_str(&line)
                    .map_err(|e| refuse(format!("line {number}: not a JSON object: {e}")))?;
                let cell = |column: &str| object.get(column).map(json_cell);
                let sweep_cell = cell("sweep").ok_or_else(|| {
                    refuse(format!(
                        "line {number} has no `sweep` key: it is not a sweep's output"
                    ))
                })?;
                let mut cells = Vec::with_capacity(key_columns.len());
                for k in &key_columns {
                    let value = cell(k).ok_or_else(|| {
                        refuse(format!(
                            "line {number} has no `{k}` key: it is the output of another sweep"
                        ))
                    })?;
                    cells.push(normal_cell(&value));
                }
                rows.push(ReadRow {
                    key: key_of(cells.iter().map(String::as_str)),
                    sweep: sweep_cell,
                    ok: cell("status").as_deref() == Some(RowStatus::OK),
                    span,
                    lines: 1,
                });
            }
        }
        Some(_) => {
            resumed.format = Some(RowFormat::Csv);
            resumed.has_header = true;
            let mut csv = csv::ReaderBuilder::new().from_reader(reader);
            let headers = csv
                .headers()
                .map_err(|e| refuse(format!("not CSV: {e}")))?
                .clone();
            let column = |name: &str| headers.iter().position(|h| h == name);
            let sweep_at = column("sweep").ok_or_else(|| {
                refuse("the file has no `sweep` column: it is not a sweep's output".into())
            })?;
            let status_at = column("status");
            let mut key_at = Vec::with_capacity(key_columns.len());
            for k in &key_columns {
                key_at.push(column(k).ok_or_else(|| {
                    refuse(format!(
                        "the file has no `{k}` column: it is the output of another sweep"
                    ))
                })?);
            }
            check_column_order(&headers, &sweep.columns()).map_err(|e| refuse(e.to_string()))?;
            let header_end = csv.position().byte();
            resumed.keep.push(0..header_end);
            resumed.kept_lines = usize::try_from(csv.position().line()).unwrap_or(1) - 1;
            let mut record = csv::StringRecord::new();
            loop {
                let start = csv.position().clone();
                if !csv
                    .read_record(&mut record)
                    .map_err(|e| refuse(format!("not CSV: {e}")))?
                {
                    break;
                }
                let end = csv.position();
                let cell = |i: usize| record.get(i).unwrap_or_default();
                let cells: Vec<String> = key_at.iter().map(|&i| normal_cell(cell(i))).collect();
                rows.push(ReadRow {
                    key: key_of(cells.iter().map(String::as_str)),
                    sweep: cell(sweep_at).to_string(),
                    ok: status_at.is_some_and(|i| cell(i) == RowStatus::OK),
                    span: start.byte()..end.byte(),
                    lines: usize::try_from(end.line() - start.line()).unwrap_or(1),
                });
            }
        }
    }
    keep_latest(&rows, &sweep.fingerprint, &mut resumed).map_err(|e| refuse(e.to_string()))?;
    Ok(resumed)
}

/// Why an existing output cannot be resumed, as what `--resume` allows.
#[derive(Debug, thiserror::Error)]
enum Unresumable {
    /// A column other than this version writes at its place.
    #[error(
        "a file whose columns are this sweep's, in its order; column {column} is `{found}` where this version writes `{expected}`: start a new output"
    )]
    ColumnOrder {
        /// The column's place, from 1.
        column: usize,
        /// The file's header there.
        found: String,
        /// This version's.
        expected: String,
    },
    /// A row of another sweep.
    #[error("holds rows of sweep {found}, not of this sweep ({expected})")]
    OtherSweep {
        /// The row's sweep fingerprint.
        found: String,
        /// This sweep's.
        expected: String,
    },
}

/// Rows are appended in this version's column order, so a header in another order (an output
/// of an older version) would put values under others' labels: the first column that differs
/// is refused.
fn check_column_order(headers: &csv::StringRecord, columns: &[String]) -> Result<(), Unresumable> {
    let width = headers.len().max(columns.len());
    match (0..width).find(|&i| headers.get(i) != columns.get(i).map(String::as_str)) {
        Some(i) => Err(Unresumable::ColumnOrder {
            column: i + 1,
            found: headers.get(i).unwrap_or_default().to_string(),
            expected: columns.get(i).cloned().unwrap_or_default(),
        }),
        None => Ok(()),
    }
}

/// Keep the latest row that computed each point and drop every other, counting them into
/// `resumed`; a row of another sweep than `fingerprint` is refused.
fn keep_latest(
    rows: &[ReadRow],
    fingerprint: &str,
    resumed: &mut Resumed,
) -> Result<(), Unresumable> {
    let mut latest: HashMap<PointKey, usize> = HashMap::new();
    for (i, row) in rows.iter().enumerate() {
        if row.sweep != fingerprint {
            return Err(Unresumable::OtherSweep {
                found: row.sweep.clone(),
                expected: fingerprint.to_string(),
            });
        }
        if row.ok {
            latest.insert(row.key, i);
        }
    }
    let mut retried = HashSet::new();
    for (i, row) in rows.iter().enumerate() {
        if latest.get(&row.key) == Some(&i) {
            resumed.keep.push(row.span.clone());
            resumed.kept_rows += 1;
            resumed.kept_lines += row.lines;
        } else {
            resumed.dropped_rows += 1;
            if !latest.contains_key(&row.key) {
                retried.insert(row.key);
            }
        }
    }
    resumed.retried = retried.len();
    resumed.done = latest.into_keys().collect();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::sweep::row::SweepRow;
    use crate::analysis::sweep::rows::RowWriter;

    fn grid() -> SweepFile {
        SweepFile::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps/grid.toml")).unwrap()
    }

    /// Rows of every point of `sweep`: ok, but failed where `failed` says; the case name of
    /// point 1 spans two lines (a CSV record over two lines).
    fn rows(sweep: &SweepFile, failed: &[usize]) -> Vec<SweepRow> {
        sweep
            .points(None)
            .iter()
            .map(|p| {
                if failed.contains(&p.index) {
                    sweep.row(p, PointFigures::default(), RowStatus::failed("it broke"))
                } else {
                    let figures = PointFigures {
                        case: Some(if p.index == 1 { "two\nlines" } else { "one" }.into()),
                        measured: crate::model::figures::Figures {
                            cor: Some(0.5),
                            ..Default::default()
                        },
                        ..PointFigures::default()
                    };
                    sweep.row(p, figures, RowStatus::ok())
                }
            })
            .collect()
    }

    fn written(
        sweep: &SweepFile,
        format: RowFormat,
        rows: &[SweepRow],
    ) -> (String, super::super::failed::FailedRows) {
        let mut bytes = Vec::new();
        let failed = {
            let mut writer = RowWriter::new(
                &mut bytes,
                format,
                &sweep.columns(),
                false,
                std::time::Duration::ZERO,
                0,
            )
            .unwrap();
            for r in rows {
                writer.write(r).unwrap();
            }
            writer.flush().unwrap();
            writer.failed.clone()
        };
        (String::from_utf8(bytes).unwrap(), failed)
    }

    #[test]
    fn failed_rows_are_named_by_their_lines_and_dropped_on_resume() {
        let sweep = grid();
        let dir = tempfile::tempdir().unwrap();
        for format in [RowFormat::Csv, RowFormat::Jsonl] {
            let all = rows(&sweep, &[2, 4]);
            let (text, failed) = written(&sweep, format, &all);
            // The lines the writer named hold the failed rows, after a CSV record of two lines
            // (JSON escapes the newline).
            assert_eq!(failed.count, 2);
            let lines: Vec<&str> = text.lines().collect();
            assert_eq!(lines.len(), 6 + 2 * usize::from(format == RowFormat::Csv));
            for &line in &failed.lines {
                let at = lines[line - 1];
                assert!(
                    at.ends_with(",it broke") || at.ends_with("\"it broke\"}"),
                    "{format:?} line {line}: {at}"
                );
            }
            let path = dir.path().join("rows");
            // A blank line, and a row cut off at the end.
            std::fs::write(&path, format!("{text}\n{}", &lines[2][..10])).unwrap();
            let resumed = read_resumed(&path, &sweep).unwrap();
            assert_eq!(resumed.format, Some(format));
            assert!(resumed.torn && resumed.rewrites());
            assert_eq!((resumed.kept_rows, resumed.retried), (4, 2));
            let points = sweep.points(None);
            for (p, key) in points.iter().zip(point_keys(&sweep, &points).unwrap()) {
                assert_eq!(resumed.done.contains(&key), ![2, 4].contains(&p.index));
            }
            // What is kept is what was written of the other points, byte for byte.
            let mut kept = Vec::new();
            resumed.copy_kept(&path, &mut kept).unwrap();
            let kept = String::from_utf8(kept).unwrap();
            let others: Vec<SweepRow> = all
                .into_iter()
                .filter(|r| ![2, 4].contains(&r.identity.point))
                .collect();
            assert_eq!(kept, written(&sweep, format, &others).0);
            assert_eq!(kept.lines().count(), resumed.kept_lines);
            // A whole output is kept as it is.
            std::fs::write(&path, &kept).unwrap();
            let whole = read_resumed(&path, &sweep).unwrap();
            assert!(!whole.rewrites());
            assert_eq!(whole.kept_lines, resumed.kept_lines);
        }
    }

    #[test]
    fn a_points_key_is_the_key_of_its_parameter_cells() {
        let sweep =
            SweepFile::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps/codes.toml"))
                .unwrap();
        let points = sweep.points(None);
        let keys = point_keys(&sweep, &points).unwrap();
        assert_eq!(keys.len(), points.len());
        for (p, key) in points.iter().zip(&keys) {
            assert_eq!(*key, key_of(sweep.key_cells(p).iter().map(String::as_str)));
        }
        let distinct: HashSet<_> = keys.iter().collect();
        assert_eq!(distinct.len(), keys.len());
    }

    #[test]
    fn a_csv_output_with_its_columns_in_another_order_is_refused() {
        let sweep = grid();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rows.csv");
        let (text, _) = written(&sweep, RowFormat::Csv, &rows(&sweep, &[]));
        std::fs::write(&path, &text).unwrap();
        assert!(read_resumed(&path, &sweep).is_ok());
        // The order an older version wrote: each measured figure beside its reference.
        let (header, body) = text.split_once('\n').unwrap();
        let older = header.replacen(
            "cor,peak_deformation",
            "cor,cor_target,cor_error,peak_deformation",
            1,
        );
        std::fs::write(&path, format!("{older}\n{body}")).unwrap();
        let e = read_resumed(&path, &sweep).unwrap_err().to_string();
        assert!(
            e.contains("is `cor_target` where this version writes `peak_deformation`"),
            "{e}"
        );
    }

    #[test]
    fn rows_of_another_sweep_or_not_of_a_sweep_are_refused() {
        let sweep = grid();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rows.csv");
        std::fs::write(&path, "a,b\n1,2\n").unwrap();
        let e = read_resumed(&path, &sweep).unwrap_err().to_string();
        assert!(e.contains("no `sweep` column"), "{e}");
        let (text, _) = written(&sweep, RowFormat::Csv, &rows(&sweep, &[]));
        let text = text.replace(&sweep.fingerprint, "0123456789abcdef");
        std::fs::write(&path, text).unwrap();
        let e = read_resumed(&path, &sweep).unwrap_err().to_string();
        assert!(e.contains("holds rows of sweep 0123456789abcdef"), "{e}");
    }
}
