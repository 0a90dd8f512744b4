//! Sweep rows on disk: CSV or JSON lines, appended and flushed as they come; read back for
//! `--resume` (rows matched by their parameters) and for `merge` (shards of one sweep).

use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

use super::error::SweepError;
use super::failed::FailedRows;
use super::row::{RowStatus, SweepRow};
use crate::error::UserError;
use crate::output::csv_record::CsvRecords;

/// How rows are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RowFormat {
    /// Comma-separated values with a header line.
    Csv,
    /// One JSON object per line.
    Jsonl,
}

impl RowFormat {
    /// The format called `name` (`csv`, `jsonl`).
    pub(crate) fn from_name(name: &str) -> Option<RowFormat> {
        match name {
            "csv" => Some(RowFormat::Csv),
            "jsonl" => Some(RowFormat::Jsonl),
            _ => None,
        }
    }
}

/// Lines of one row in `format` (the CSV header is [`header`]).
pub(crate) fn encode(format: RowFormat, columns: &[String], cells: &[String]) -> String {
    match format {
        RowFormat::Csv => csv_line(cells),
        RowFormat::Jsonl => {
            let mut text = String::from("{");
            for (i, (c, v)) in columns.iter().zip(cells).enumerate() {
                if i > 0 {
                    text.push(',');
                }
                text += &serde_json::to_string(c).unwrap_or_default();
                text.push(':');
                text += &json_value(v);
            }
            text + "}\n"
        }
    }
}

/// The header line (CSV only; JSON lines carry their keys).
pub(crate) fn header(format: RowFormat, columns: &[String]) -> String {
    match format {
        RowFormat::Csv => csv_line(columns),
        RowFormat::Jsonl => String::new(),
    }
}

fn csv_line(cells: &[String]) -> String {
    let mut w = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    let _ = w.write_record(cells);
    String::from_utf8(w.into_inner().unwrap_or_default()).unwrap_or_default()
}

fn json_value(v: &str) -> String {
    if v.is_empty() {
        return "null".into();
    }
    match v.parse::<f64>() {
        Ok(x) if x.is_finite() && !v.starts_with('+') && !v.contains(['i', 'n', 'N']) => {
            v.to_string()
        }
        _ => serde_json::to_string(v).unwrap_or_default(),
    }
}

/// A JSON object's members in their written order.
struct Ordered(Vec<(String, serde_json::Value)>);

impl<'de> serde::Deserialize<'de> for Ordered {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Ordered;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a JSON object")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> Result<Ordered, A::Error> {
                let mut pairs = Vec::new();
                while let Some(pair) = map.next_entry()? {
                    pairs.push(pair);
                }
                Ok(Ordered(pairs))
            }
        }
        d.deserialize_map(Visitor)
    }
}

/// Rows read back: the columns and each row's cells (numbers in their written form).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Rows {
    /// Column names.
    pub columns: Vec<String>,
    /// Cells, one vector per row, in column order.
    pub rows: Vec<Vec<String>>,
    /// The format they were written in.
    pub format: Option<RowFormat>,
}

impl Rows {
    /// The index of column `name`.
    pub(crate) fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }
}

/// The complete lines of `text`: a last line without its newline is a row cut off while it
/// was being written, and is left out.
pub(crate) fn complete_lines(text: &str) -> &str {
    match text.rfind('\n') {
        Some(at) => &text[..=at],
        None => "",
    }
}

/// A JSON value as a cell: null empty, a string bare, a number in its written form.
pub(crate) fn json_cell(value: &serde_json::Value) -> String {
    match value {
        serde_json::Value::Null => String::new(),
        serde_json::Value::String(s) => s.clone(),
        serde_json::Value::Number(x) => x
            .as_f64()
            .filter(|_| !x.is_u64() && !x.is_i64())
            .map(crate::analysis::sweep::grid::number)
            .unwrap_or_else(|| x.to_string()),
        other => other.to_string(),
    }
}

/// Read the rows of a sweep output (CSV or JSON lines, told apart by the first character).
pub(crate) fn read_rows(path: &Path) -> Result<Rows, SweepError> {
    let text = std::fs::read_to_string(path).map_err(|source| SweepError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(parse_rows(
        complete_lines(&text),
        &path.display().to_string(),
    )?)
}

/// Parse rows from `text`; `file` names it in errors.
pub(crate) fn parse_rows(text: &str, file: &str) -> Result<Rows, UserError> {
    let bad = |what: String| UserError::argument(file, "(rows)", what);
    let trimmed = text.trim_start();
    if trimmed.is_empty() {
        return Ok(Rows::default());
    }
    if trimmed.starts_with('{') {
        let mut rows = Rows {
            format: Some(RowFormat::Jsonl),
            ..Rows::default()
        };
        for (n, line) in text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty())
        {
            let Ordered(pairs) = serde_json::from_str(line)
                .map_err(|e| bad(format!("line {}: not a JSON object: {e}", n + 1)))?;
            if rows.columns.is_empty() {
                rows.columns = pairs.iter().map(|(k, _)| k.clone()).collect();
            }
            let object: std::collections::HashMap<String, serde_json::Value> =
                pairs.into_iter().collect();
            let cells = rows
                .columns
                .iter()
                .map(|c| object.get(c).map(json_cell).unwrap_or_default())
                .collect();
            rows.rows.push(cells);
        }
        Ok(rows)
    } else {
        let mut reader = csv::ReaderBuilder::new().from_reader(text.as_bytes());
        let columns: Vec<String> = reader
            .headers()
            .map_err(|e| bad(format!("not CSV: {e}")))?
            .iter()
            .map(String::from)
            .collect();
        let mut rows = Rows {
            columns,
            format: Some(RowFormat::Csv),
            rows: Vec::new(),
        };
        for record in reader.records() {
            let record = record.map_err(|e| bad(format!("not CSV: {e}")))?;
            rows.rows.push(record.iter().map(String::from).collect());
        }
        Ok(rows)
    }
}

/// About the bytes of one row of a sweep of our methods.
const ROW_BYTES: usize = 640;

/// Rows encoded in their format, ready to be written: what a worker hands the one writer.
/// CSV rows go through [`CsvRecords`] (the csv crate's bytes, numbers by ryu and itoa straight
/// into this one buffer); JSON lines through serde_json.
pub struct EncodedRows {
    encoding: Encoding,
    /// Rows held.
    pub rows: usize,
    /// The rows whose status is not `ok`: the lines before theirs among these rows (a CSV
    /// record may span lines), their point and their status.
    pub failed: Vec<(usize, usize, String)>,
}

/// The bytes of rows in one format, and what they hold.
enum Encoding {
    Csv(CsvRecords),
    /// JSON lines: one line per row (serde_json escapes a line break inside text).
    Jsonl(Vec<u8>),
}

impl EncodedRows {
    /// An empty run of rows in `format`.
    pub(crate) fn new(format: RowFormat) -> EncodedRows {
        EncodedRows {
            encoding: match format {
                // About a chunk of rows, so that the buffer is not regrown.
                RowFormat::Csv => {
                    Encoding::Csv(CsvRecords::with_capacity(ROW_BYTES * super::CHUNK))
                }
                RowFormat::Jsonl => Encoding::Jsonl(Vec::new()),
            },
            rows: 0,
            failed: Vec::new(),
        }
    }

    /// The lines held so far.
    pub(crate) fn lines(&self) -> usize {
        match &self.encoding {
            Encoding::Csv(records) => records.lines(),
            Encoding::Jsonl(_) => self.rows,
        }
    }

    /// Append `row`.
    pub(crate) fn push(&mut self, row: &SweepRow) -> std::io::Result<()> {
        if !row.status.is_ok() {
            self.failed
                .push((self.lines(), row.identity.point, row.status.status.clone()));
        }
        match &mut self.encoding {
            Encoding::Csv(records) => row.write_csv(records)?,
            Encoding::Jsonl(bytes) => row.write_json_line(bytes)?,
        }
        self.rows += 1;
        Ok(())
    }

    /// The rows' bytes.
    pub fn into_bytes(self) -> Vec<u8> {
        match self.encoding {
            Encoding::Csv(records) => records.into_bytes(),
            Encoding::Jsonl(bytes) => bytes,
        }
    }
}

/// Rows to a writer, flushed as they come (at most every `flush_every` for fast rows).
pub struct RowWriter<W: Write> {
    out: W,
    format: RowFormat,
    last_flush: std::time::Instant,
    flush_every: std::time::Duration,
    /// Lines already in the output before this writer's first (a resumed file's kept part).
    lines_before: usize,
    /// Lines this writer has written (the header, then the rows').
    lines: usize,
    /// Rows written.
    pub written: usize,
    /// The rows written whose status is not `ok`, and where they are.
    pub failed: FailedRows,
}

impl<W: Write> RowWriter<W> {
    /// A writer of rows with `columns`; the CSV header is written unless `resume`.
    /// `lines_before` lines are in the output already (what a resumed file keeps).
    pub fn new(
        mut out: W,
        format: RowFormat,
        columns: &[String],
        resume: bool,
        flush_every: std::time::Duration,
        lines_before: usize,
    ) -> std::io::Result<Self> {
        let mut lines = 0;
        if format == RowFormat::Csv && !resume {
            out.write_all(header(format, columns).as_bytes())?;
            lines = 1;
        }
        out.flush()?;
        Ok(RowWriter {
            out,
            format,
            last_flush: std::time::Instant::now(),
            flush_every,
            lines_before,
            lines,
            written: 0,
            failed: FailedRows::default(),
        })
    }

    /// Append one row.
    pub fn write(&mut self, row: &SweepRow) -> std::io::Result<()> {
        let mut rows = EncodedRows::new(self.format);
        rows.push(row)?;
        self.write_encoded(rows)
    }

    /// Append rows already encoded (in this writer's format), noting where the failed ones
    /// are.
    pub(crate) fn write_encoded(&mut self, rows: EncodedRows) -> std::io::Result<()> {
        let first_line = self.lines_before + self.lines + 1;
        for (before, point, status) in &rows.failed {
            self.failed.record(first_line + before, *point, status);
        }
        let (count, lines) = (rows.rows, rows.lines());
        self.out.write_all(&rows.into_bytes())?;
        self.lines += lines;
        self.written += count;
        if self.last_flush.elapsed() >= self.flush_every {
            self.flush()?;
            self.last_flush = std::time::Instant::now();
        }
        Ok(())
    }

    /// Flush what is buffered.
    pub(crate) fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

/// Shards joined by [`merge`]: the text, and where its failed rows are.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Merged {
    /// The joined rows in the shards' format.
    pub text: String,
    /// Points in it.
    pub points: usize,
    /// Its failed rows.
    pub failed: FailedRows,
}

/// Join shard outputs: every shard must hold rows of one sweep (same columns and
/// fingerprint); rows are sorted by point. A point given more than once is kept once: a row
/// that computed it before one that failed, else the first given.
pub fn merge(shards: &[&Path]) -> Result<Merged, SweepError> {
    let mut joined: Option<Rows> = None;
    let mut fingerprint: Option<(String, String)> = None;
    // Each point's row in `joined`, and whether it is ok.
    let mut seen: HashMap<usize, (usize, bool)> = HashMap::new();
    for path in shards {
        let file = path.display().to_string();
        let rows = read_rows(path)?;
        if rows.rows.is_empty() && rows.columns.is_empty() {
            continue;
        }
        let sweep = rows.column("sweep").ok_or_else(|| {
            UserError::argument("SHARDS", &file, "not a sweep's output (no `sweep` column)")
        })?;
        let point = rows.column("point").ok_or_else(|| {
            UserError::argument("SHARDS", &file, "not a sweep's output (no `point` column)")
        })?;
        let status = rows.column("status");
        if let Some(first) = &joined
            && (first.columns != rows.columns || first.format != rows.format)
        {
            return Err(UserError::argument(
                "SHARDS",
                &file,
                "its columns or format differ from the first shard's: shards of different sweeps",
            )
            .into());
        }
        let target = joined.get_or_insert_with(|| Rows {
            columns: rows.columns.clone(),
            rows: Vec::new(),
            format: rows.format,
        });
        for r in rows.rows {
            let f = r[sweep].clone();
            match &fingerprint {
                None => fingerprint = Some((f, file.clone())),
                Some((g, first)) if *g != f => {
                    return Err(UserError::argument(
                        "SHARDS",
                        &file,
                        format!(
                            "holds rows of sweep {f}, {first} of sweep {g}: shards of different sweeps cannot be merged"
                        ),
                    )
                    .into());
                }
                _ => {}
            }
            let index: usize = r[point].parse().map_err(|_| {
                UserError::argument(
                    "SHARDS",
                    &file,
                    format!("point `{}` is not a number", r[point]),
                )
            })?;
            let ok = status.is_some_and(|s| r[s] == RowStatus::OK);
            match seen.get(&index) {
                None => {
                    seen.insert(index, (target.rows.len(), ok));
                    target.rows.push(r);
                }
                Some(&(at, false)) if ok => {
                    seen.insert(index, (at, true));
                    target.rows[at] = r;
                }
                Some(_) => {}
            }
        }
    }
    let Some(mut rows) = joined else {
        return Err(UserError::argument("SHARDS", "(all)", "no rows in any shard").into());
    };
    let point = rows.column("point").unwrap_or(1);
    rows.rows
        .sort_by_key(|r| r[point].parse::<usize>().unwrap_or(usize::MAX));
    let format = rows.format.unwrap_or(RowFormat::Csv);
    let status = rows.column("status");
    let mut merged = Merged {
        text: header(format, &rows.columns),
        points: rows.rows.len(),
        failed: FailedRows::default(),
    };
    let mut lines = merged.text.matches('\n').count();
    for r in &rows.rows {
        let line = encode(format, &rows.columns, r);
        if let Some(s) = status.filter(|&s| r[s] != RowStatus::OK) {
            merged
                .failed
                .record(lines + 1, r[point].parse().unwrap_or_default(), &r[s]);
        }
        lines += line.matches('\n').count();
        merged.text += &line;
    }
    Ok(merged)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_round_trip_in_both_formats() {
        let columns: Vec<String> = ["sweep", "point", "x", "status"].map(String::from).to_vec();
        let cells: Vec<String> = ["ab12", "3", "0.35", "file: a, b = \"c\": d"]
            .map(String::from)
            .to_vec();
        for format in [RowFormat::Csv, RowFormat::Jsonl] {
            let text = header(format, &columns) + &encode(format, &columns, &cells);
            let rows = parse_rows(&text, "t").unwrap();
            assert_eq!(rows.columns, columns);
            assert_eq!(rows.rows, vec![cells.clone()]);
        }
    }

    #[test]
    fn a_cut_last_line_is_left_out() {
        assert_eq!(complete_lines("a\nb\nc"), "a\nb\n");
        assert_eq!(complete_lines("a"), "");
    }
}
