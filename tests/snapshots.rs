//! Snapshots of every command that needs no DEM code, in every format (table, JSON, CSV,
//! Markdown), on the shipped cases and the stored references; of the `reference` exporter on a
//! stored record; and of the solvers' work counters. Every figure is deterministic except the
//! times, which are redacted: a change in any other cell, header, key or line fails here.
//!
//! Review a change with `cargo insta review` (or set `INSTA_UPDATE=always` and read the diff of
//! `tests/snapshots/`).

mod common;

use std::fmt::Write as _;

use common::{millimpact, root, shipped, stdout};
use millimpact::analysis::store;
use millimpact::codes::CodeName;
use millimpact::output::{Format, export};
use millimpact::solve::Method;
use millimpact::solve::paper::{self, Settings};

const CANONICAL: [&str; 3] = ["ball_plate", "ball_ball", "rod_end"];

/// Field names that hold a time measured on this machine (JSON keys and CSV columns).
const TIME_FIELDS: [&str; 7] = [
    "wall_time",
    "wall_time_s",
    "time_s",
    "loop_time",
    "loop_time_s",
    "run_time",
    "date",
];

/// Assert the snapshot `name` of `text` with measured times replaced by `[time]`: JSON values
/// of the time keys, CSV cells of the time columns, and durations written as `12.34 µs`,
/// `1.234 ms` or `1.234 s` in text. With `collapse`, table padding and rules are shrunk to one
/// character, since a redacted column's width still depends on the time it held.
#[track_caller]
fn check(name: &str, text: &str, format: Format, collapse: bool) {
    let text = match format {
        Format::Csv => redact_csv(text),
        _ => text.to_string(),
    };
    let mut settings = insta::Settings::clone_current();
    let keys = TIME_FIELDS.join("|");
    settings.add_filter(
        &format!(r#""({keys})": ("[^"]*"|[-+0-9.eE]+)"#),
        r#""$1": "[time]""#,
    );
    // Which source is cheapest at a given error is decided by measured times.
    settings.add_filter(
        r#""best_at_1e_10": \{[^}]*\}"#,
        r#""best_at_1e_10": "[fastest]""#,
    );
    settings.add_filter(
        r"(cheapest impact at COR error ≤ \S+) is [^;\n]*?\(\d+\.\d+ (µs|ms|s)\)",
        "$1 is [fastest] ([time])",
    );
    settings.add_filter(r"\b\d+\.\d+ (µs|ms|s)\b", "[time]");
    if collapse && format == Format::Table {
        settings.add_filter(r"[─═]+", "─");
        settings.add_filter(r" {2,}", " ");
    }
    settings.bind(|| insta::assert_snapshot!(name.to_string(), text));
}

fn redact_csv(text: &str) -> String {
    // Flexible, so that a trailing note line (the stability head) passes through; a ragged row
    // would show in the snapshot.
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .from_reader(text.as_bytes());
    let headers = reader.headers().expect("a CSV header").clone();
    let timed: Vec<bool> = headers.iter().map(|h| TIME_FIELDS.contains(&h)).collect();
    let mut writer = csv::WriterBuilder::new()
        .flexible(true)
        .from_writer(Vec::new());
    writer.write_record(&headers).unwrap();
    for row in reader.records() {
        let row = row.expect("a CSV row");
        let cells: Vec<&str> = row
            .iter()
            .zip(&timed)
            .map(|(cell, &t)| {
                if t && !cell.is_empty() {
                    "[time]"
                } else {
                    cell
                }
            })
            .collect();
        writer.write_record(cells).unwrap();
    }
    String::from_utf8(writer.into_inner().unwrap()).unwrap()
}

fn command(args: &[&str], format: Format) -> String {
    stdout(millimpact().args(args).args(["--format", format.name()]))
}

#[test]
fn run_each_canonical_case() {
    for case in CANONICAL {
        let path = format!("cases/{case}.toml");
        for format in Format::ALL {
            let text = command(&["run", &path], format);
            check(&format!("run_{case}_{format}"), &text, format, false);
        }
    }
}

#[test]
fn run_each_method() {
    for &method in Method::ALL {
        let text = command(
            &["run", "cases/ball_plate.toml", "--method", method.name()],
            Format::Json,
        );
        check(
            &format!("run_ball_plate_{}_json", method.name()),
            &text,
            Format::Json,
            false,
        );
    }
}

#[test]
fn sweep_a_small_range() {
    for format in Format::ALL {
        let args = [
            "sweep",
            "cases/ball_plate.toml",
            "--loss-coefficient",
            "0:0.7:0.35",
        ];
        let text = command(&args, format);
        check(&format!("sweep_ball_plate_{format}"), &text, format, false);
    }
}

/// The same range asking for a COR tolerance instead of a method: the chosen method in the rows
/// and the tolerance in the reproduce line.
#[test]
fn sweep_a_small_range_at_a_tolerance() {
    for format in Format::ALL {
        let args = [
            "sweep",
            "cases/ball_plate.toml",
            "--loss-coefficient",
            "0:0.7:0.35",
            "--tolerance",
            "1e-10",
        ];
        let text = command(&args, format);
        check(&format!("sweep_tolerance_{format}"), &text, format, false);
    }
}

#[test]
fn verify_the_shipped_cases_and_references() {
    for format in Format::ALL {
        let text = command(&["verify"], format);
        check(&format!("verify_{format}"), &text, format, false);
    }
}

#[test]
fn benchmark_chung_ooi_by_the_methods() {
    for format in Format::ALL {
        let text = command(&["benchmark", "chung-ooi"], format);
        check(
            &format!("benchmark_chung_ooi_{format}"),
            &text,
            format,
            false,
        );
    }
}

#[test]
fn compare_from_the_stored_references() {
    for format in Format::ALL {
        let text = command(&["compare"], format);
        check(&format!("compare_{format}"), &text, format, true);
    }
}

#[test]
fn precision_of_the_methods() {
    for format in Format::ALL {
        let args = ["precision", "cases/ball_plate.toml", "--repeats", "1"];
        let text = command(&args, format);
        check(
            &format!("precision_ball_plate_{format}"),
            &text,
            format,
            true,
        );
    }
}

/// The grid's summary and limit sections in full; of its per-case rows (1128, about 400 kB),
/// the count and the first rows, in JSON and CSV.
#[test]
fn stability_summary_and_limits() {
    for format in Format::ALL {
        let text = command(&["stability"], format);
        let text = match format {
            Format::Json => elide_json_array(&text, "cases"),
            Format::Csv => head_of_csv(&text, 8),
            Format::Table | Format::Markdown => text,
        };
        check(&format!("stability_{format}"), &text, format, false);
    }
}

/// Replace the top-level array `key` of a pretty-printed JSON document by its length and its
/// first element, keeping the other keys in their order.
fn elide_json_array(text: &str, key: &str) -> String {
    let open = format!("  \"{key}\": [");
    let mut out = String::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        if line != open {
            out += line;
            out.push('\n');
            continue;
        }
        let mut body = Vec::new();
        for inner in lines.by_ref() {
            if inner == "  ]," || inner == "  ]" {
                let count = body.iter().filter(|l: &&&str| **l == "    {").count();
                let first: Vec<&str> = body
                    .iter()
                    .take_while(|l| **l != "    },")
                    .copied()
                    .collect();
                writeln!(out, "{open} // {count} entries; the first:").unwrap();
                for l in first {
                    out += l;
                    out.push('\n');
                }
                writeln!(out, "    }}, …\n{inner}").unwrap();
                break;
            }
            body.push(inner);
        }
    }
    out
}

fn head_of_csv(text: &str, rows: usize) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = lines[..=rows].join("\n");
    writeln!(out, "\n… {} rows in all", lines.len() - 1).unwrap();
    out
}

/// `reference` runs a DEM code; its exporter is snapshotted on the stored records of each code
/// for ball_plate at the paper's η = 0.35.
#[test]
fn reference_exporter_on_the_stored_records() {
    for &code in CodeName::ALL {
        let path = store::reference_path(&root().join("reference"), code, "ball_plate");
        let file = store::load(&path).unwrap();
        let record = file
            .runs
            .iter()
            .find(|r| (r.loss_coefficient - 0.35).abs() < 1e-12)
            .unwrap_or_else(|| panic!("{} holds a run at η = 0.35", path.display()));
        for format in Format::ALL {
            let text = export(record, format).unwrap();
            let name = format!("reference_{}_ball_plate_{format}", code.name());
            check(&name, &text, format, true);
        }
    }
}

/// The work each method does on each canonical case at its default settings (design.md item
/// 6): a change of step control, event location or series stretch shows here first.
#[test]
fn solver_work_per_method_and_case() {
    let mut table = String::from("case        method     steps  rejected  rhs evaluations\n");
    for name in CANONICAL {
        let case = shipped(name);
        for &method in Method::ALL.iter().filter(|m| m.integrates()) {
            let settings = Settings {
                method,
                contact: case.contact,
                ..Settings::default()
            };
            let outcome = paper::solve(&case.law(), case.impact_velocity, &settings).unwrap();
            let s = outcome.stats;
            writeln!(
                table,
                "{name:<11} {:<10} {:>5}  {:>8}  {:>15}",
                method.name(),
                s.steps,
                s.rejected,
                s.rhs_evaluations
            )
            .unwrap();
        }
    }
    insta::assert_snapshot!("solver_work", table);
}
