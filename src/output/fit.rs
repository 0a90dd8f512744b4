//! A summary's table laid out to fit the terminal it is printed on. A table wider than that is
//! split into tables of whole columns, each led by the columns that name a row
//! ([`Summary::key_columns`]), and the text under it is wrapped. A pipe or a file gets the full
//! table, so that a script, a file and a snapshot see the same text whatever the terminal.

use comfy_table::{ContentArrangement, Table, presets::UTF8_FULL_CONDENSED};

use super::{OutputError, Section, Summary};

/// The width a table is laid out in, in characters, where standard output is a terminal
/// (`terminal`, with the width it reports where it reports one): `COLUMNS` where it is set to
/// a number (`columns`), else the terminal's. None (the full table, as every other format
/// keeps it) in a pipe or a file, or where neither width is known.
pub fn table_width(terminal: Option<Option<u16>>, columns: Option<&str>) -> Option<u16> {
    let reported = terminal?;
    // A terminal that reports no columns (a pseudo-terminal given no size) is one of unknown
    // width.
    let known = |w: &u16| *w > 0;
    columns
        .and_then(|c| c.trim().parse::<u16>().ok())
        .filter(known)
        .or(reported.filter(known))
}

/// Narrowest layout a table is wrapped into: below it each cell would break inside numbers.
const NARROWEST_TABLE: u16 = 40;

/// `summary` as tables that fit `width` characters: its columns split into groups that each
/// fit (the key columns first in every group), a column too wide even beside the keys alone
/// wrapped in its cells (comfy-table's dynamic arrangement), and every title and line of text
/// under a table (notes, traps, warnings) wrapped at the width with its indent kept. The
/// footer (the command that reproduces it) is left whole, to be copied. Wide enough, it is the
/// table format's text.
pub fn table_at_width<S: Summary>(summary: &S, width: u16) -> Result<String, OutputError> {
    let width = width.max(NARROWEST_TABLE);
    let wrap = |line: &str, out: &mut String| {
        for piece in wrap_line(line, usize::from(width)) {
            out.push_str(&piece);
            out.push('\n');
        }
    };
    let keys = summary.key_columns();
    let mut text = String::new();
    for section in summary.sections() {
        section.check()?;
        if let Some(title) = &section.title {
            wrap(title, &mut text);
        }
        if !section.headers.is_empty() {
            match layout(&section, keys, usize::from(width)) {
                Layout::Tables(groups) => {
                    for columns in groups {
                        text += &part_table(&section, &columns, width);
                    }
                }
                Layout::Records => {
                    for line in records(&section, keys, usize::from(width)) {
                        text += &line;
                        text.push('\n');
                    }
                }
            }
        }
        for line in &section.notes {
            wrap(line, &mut text);
        }
    }
    for line in summary.footer() {
        text += &format!("{line}\n");
    }
    Ok(text)
}

/// How a section is laid out in a width.
enum Layout {
    /// Tables of these columns each (one, of all of them, where the whole table fits).
    Tables(Vec<Vec<usize>>),
    /// A block per row: its key cells on a line, then a line per other column.
    Records,
}

/// The columns of `section` in groups that each fit `width` as one table, its first `keys`
/// columns first in every group: all of them in one where the whole table fits. A column too
/// wide even beside the keys alone gets a group of its own, and its cells wrap. Where the keys
/// alone take more than half the width, parts would hold a column or two each beside them and
/// a narrow column's numbers would break: the rows are laid out as records instead.
fn layout(section: &Section, keys: usize, width: usize) -> Layout {
    // A column takes its widest cell, a space either side and one border.
    let column_width = |k: usize| {
        std::iter::once(&section.headers[k])
            .chain(section.rows.iter().map(|r| &r[k]))
            .map(|cell| cell.chars().count())
            .max()
            .unwrap_or(0)
            + 3
    };
    let widths: Vec<usize> = (0..section.headers.len()).map(column_width).collect();
    // The columns and the left border.
    if widths.iter().sum::<usize>() < width {
        return Layout::Tables(vec![(0..widths.len()).collect()]);
    }
    let keys = keys.min(widths.len());
    let key_width = 1 + widths[..keys].iter().sum::<usize>();
    if 2 * key_width > width {
        return Layout::Records;
    }
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut current: Vec<usize> = (0..keys).collect();
    let mut used = key_width;
    for (k, &column) in widths.iter().enumerate().skip(keys) {
        if current.len() > keys && used + column > width {
            groups.push(std::mem::replace(&mut current, (0..keys).collect()));
            used = key_width;
        }
        current.push(k);
        used += column;
    }
    groups.push(current);
    Layout::Tables(groups)
}

/// The table of `section`'s `columns`, at most `width` wide (a cell too wide wraps).
fn part_table(section: &Section, columns: &[usize], width: u16) -> String {
    let pick =
        |row: &[String]| -> Vec<String> { columns.iter().map(|&k| row[k].clone()).collect() };
    let mut table = Table::new();
    table
        .load_style(UTF8_FULL_CONDENSED)
        .set_content_arrangement(ContentArrangement::Dynamic)
        .set_width(width)
        .set_header(pick(&section.headers));
    for row in &section.rows {
        table.add_row(pick(row));
    }
    format!("{table}\n")
}

/// `section`'s rows as records: the key cells on a line (`header: cell`, joined by ` · `), then
/// each other column's non-empty cell on a line of its own under its header, aligned; every
/// line wrapped at `width`.
fn records(section: &Section, keys: usize, width: usize) -> Vec<String> {
    let keys = keys.min(section.headers.len());
    let label = section.headers[keys..]
        .iter()
        .map(|h| h.chars().count())
        .max()
        .unwrap_or(0)
        .min(width / 2);
    let mut lines = Vec::new();
    for row in &section.rows {
        let name: Vec<String> = (0..keys)
            .map(|k| format!("{}: {}", section.headers[k], row[k]))
            .collect();
        lines.extend(wrap_line(&format!("── {}", name.join(" · ")), width));
        for (header, cell) in section.headers.iter().zip(row).skip(keys) {
            if !cell.is_empty() {
                lines.extend(wrap_line(&format!("   {header:<label$}  {cell}"), width));
            }
        }
    }
    lines
}

/// `line` broken at spaces into lines of at most `width` characters (a word longer than that
/// stands alone), each continuation indented two more than the line's own indent.
fn wrap_line(line: &str, width: usize) -> Vec<String> {
    if line.chars().count() <= width {
        return vec![line.to_string()];
    }
    let indent = line.len() - line.trim_start().len();
    let hanging = " ".repeat(indent + 2);
    let mut lines = Vec::new();
    let mut current = line[..indent].to_string();
    let mut empty = true;
    for word in line.split_whitespace() {
        let length = current.chars().count() + usize::from(!empty) + word.chars().count();
        if !empty && length > width {
            lines.push(std::mem::replace(&mut current, hanging.clone()));
            empty = true;
        }
        if !empty {
            current.push(' ');
        }
        current.push_str(word);
        empty = false;
    }
    lines.push(current);
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn on_a_terminal_the_width_is_columns_else_the_terminals() {
        assert_eq!(table_width(Some(Some(80)), Some("100")), Some(100));
        assert_eq!(table_width(Some(Some(80)), None), Some(80));
        assert_eq!(table_width(Some(Some(80)), Some("wide")), Some(80));
        assert_eq!(table_width(Some(None), Some("120")), Some(120));
        assert_eq!(table_width(Some(None), Some("0")), None);
        assert_eq!(table_width(Some(None), None), None);
        assert_eq!(table_width(Some(Some(0)), None), None);
        assert_eq!(table_width(Some(Some(0)), Some("90")), Some(90));
        assert_eq!(table_width(Some(Some(80)), Some("0")), Some(80));
    }

    #[test]
    fn a_pipe_or_a_file_gets_the_full_table_whatever_columns_says() {
        assert_eq!(table_width(None, Some("100")), None);
        assert_eq!(table_width(None, None), None);
    }

    #[test]
    fn a_long_line_wraps_at_spaces_with_a_hanging_indent() {
        assert_eq!(wrap_line("  one two three", 9), ["  one two", "    three"]);
        assert_eq!(wrap_line("short", 9), ["short"]);
        assert_eq!(
            wrap_line("averyverylongword x", 5),
            ["averyverylongword", "  x"]
        );
    }

    fn section(headers: &[&str], rows: &[&[&str]]) -> Section {
        let mut section = Section::new(None, headers);
        section.rows = rows
            .iter()
            .map(|r| r.iter().map(|c| c.to_string()).collect())
            .collect();
        section
    }

    #[test]
    fn a_table_is_whole_where_it_fits_else_split_after_its_keys_else_records() {
        let s = section(&["name", "a", "b"], &[&["x", "1.0", "2.0"]]);
        // Columns 7, 6 and 6 wide with their padding and border, and the left border: 20.
        assert!(matches!(layout(&s, 1, 20), Layout::Tables(g) if g == [vec![0, 1, 2]]));
        assert!(matches!(layout(&s, 1, 19), Layout::Tables(g) if g == [vec![0, 1], vec![0, 2]]));
        assert!(matches!(layout(&s, 2, 19), Layout::Records));
    }

    #[test]
    fn a_record_names_its_row_by_its_keys_and_leaves_out_empty_cells() {
        let s = section(
            &["case", "method", "COR", "contact time"],
            &[
                &["ball", "rk4", "0.69", ""],
                &["rod", "dopri5", "0.70", "1e-4"],
            ],
        );
        assert_eq!(
            records(&s, 2, 80),
            [
                "── case: ball · method: rk4",
                "   COR           0.69",
                "── case: rod · method: dopri5",
                "   COR           0.70",
                "   contact time  1e-4",
            ]
        );
    }
}
