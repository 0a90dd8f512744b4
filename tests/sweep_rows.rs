//! Every label of a sweep row sits over its own value: for every combination of the source
//! axes (code × steps_per_contact, method × steps_per_period × rtol) and both row formats, each
//! row's source columns hold exactly what its point was computed by. Code points run with the
//! code's binary pointed at a file that does not exist, so they fail at once (no DEM process
//! starts) and their rows still carry their parameters.

use std::collections::BTreeMap;

mod common;

/// The source axes of one combination, as TOML lines.
#[derive(Clone, Debug)]
struct Combination {
    methods: Option<&'static [&'static str]>,
    steps_per_period: bool,
    rtol: bool,
    code: bool,
    steps_per_contact: bool,
}

impl Combination {
    fn toml(&self) -> String {
        let mut text = format!(
            "base = {:?}\n[axes]\nloss_coefficient = [0.2, 0.5]\n",
            common::case_path("ball_plate").display().to_string()
        );
        if let Some(methods) = self.methods {
            text += &format!("method = {methods:?}\n");
        }
        if self.steps_per_period {
            text += "steps_per_period = [400]\n";
        }
        if self.rtol {
            text += "rtol = [1e-9]\n";
        }
        if self.code {
            text += "code = [\"liggghts\"]\n";
        }
        if self.steps_per_contact {
            text += "steps_per_contact = [100]\n";
        }
        text
    }

    /// What the sweep file reader accepts: a knob needs a source that has it.
    fn valid(&self) -> bool {
        let methods = self
            .methods
            .unwrap_or(if self.code { &[] } else { &["rk4-event"] });
        (!self.steps_per_period || methods.iter().any(|m| *m != "dopri5" && *m != "exact"))
            && (!self.rtol || methods.contains(&"dopri5"))
            && (!self.steps_per_contact || self.code)
    }

    fn all() -> Vec<Combination> {
        let mut out = Vec::new();
        let method_sets: [Option<&'static [&'static str]>; 3] = [
            None,
            Some(&["rk4", "dopri5", "exact"]),
            Some(&["rk4-event"]),
        ];
        for methods in method_sets {
            for bits in 0..16u8 {
                let c = Combination {
                    methods,
                    steps_per_period: bits & 1 != 0,
                    rtol: bits & 2 != 0,
                    code: bits & 4 != 0,
                    steps_per_contact: bits & 8 != 0,
                };
                if c.valid() {
                    out.push(c);
                }
            }
        }
        out
    }
}

/// The rows of a sweep output as column → cell maps (JSON nulls as empty cells).
fn rows(text: &str, format: &str) -> Vec<BTreeMap<String, String>> {
    if format == "csv" {
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let header = reader.headers().unwrap().clone();
        reader
            .records()
            .map(|r| {
                let r = r.unwrap();
                header
                    .iter()
                    .zip(r.iter())
                    .map(|(h, c)| (h.to_string(), c.to_string()))
                    .collect()
            })
            .collect()
    } else {
        text.lines()
            .map(|line| {
                let object: serde_json::Map<String, serde_json::Value> =
                    serde_json::from_str(line).unwrap();
                object
                    .into_iter()
                    .map(|(k, v)| {
                        let cell = match v {
                            serde_json::Value::Null => String::new(),
                            serde_json::Value::String(s) => s,
                            other => other.to_string(),
                        };
                        (k, cell)
                    })
                    .collect()
            })
            .collect()
    }
}

#[test]
fn every_axis_combination_puts_each_value_under_its_own_label() {
    let dir = tempfile::tempdir().unwrap();
    let combinations = Combination::all();
    assert!(
        combinations.len() >= 20,
        "{} combinations",
        combinations.len()
    );
    for (i, c) in combinations.iter().enumerate() {
        let file = dir.path().join(format!("sweep{i}.toml"));
        std::fs::write(&file, c.toml()).unwrap();
        for format in ["csv", "jsonl"] {
            let output = common::millimpact()
                .args(["sweep", file.to_str().unwrap(), "--format", format])
                .env("MILLIMPACT_LIGGGHTS_BINARY", dir.path().join("no-liggghts"))
                .output()
                .unwrap();
            let text = String::from_utf8(output.stdout).unwrap();
            let what = format!("{format} of\n{}", c.toml());
            let rows = rows(&text, format);
            let sources_per_eta = c
                .methods
                .map(<[_]>::len)
                .unwrap_or(if c.code { 0 } else { 1 })
                + usize::from(c.code);
            assert_eq!(rows.len(), 2 * sources_per_eta, "{what}\n{text}");
            for row in &rows {
                let method = row["method"].as_str();
                let code = row["code"].as_str();
                assert!(
                    ["0.2", "0.5"].contains(&row["loss_coefficient"].as_str()),
                    "{what}: {row:?}"
                );
                if code.is_empty() {
                    let allowed = c.methods.unwrap_or(&["rk4-event"]);
                    assert!(allowed.contains(&method), "{what}: {row:?}");
                    let fixed_step = method == "rk4" || method == "rk4-event";
                    let spp = if c.steps_per_period && fixed_step {
                        "400"
                    } else {
                        ""
                    };
                    assert_eq!(row["steps_per_period"], spp, "{what}: {row:?}");
                    let rtol = if c.rtol && method == "dopri5" {
                        "1e-9"
                    } else {
                        ""
                    };
                    assert_eq!(row["rtol"], rtol, "{what}: {row:?}");
                    assert_eq!(row["steps_per_contact"], "", "{what}: {row:?}");
                    assert_eq!(row["status"], "ok", "{what}: {row:?}");
                    assert_eq!(row["eta"], row["loss_coefficient"], "{what}: {row:?}");
                } else {
                    assert!(c.code, "{what}: {row:?}");
                    assert_eq!(code, "liggghts", "{what}: {row:?}");
                    assert_eq!(method, "", "{what}: {row:?}");
                    assert_eq!(row["steps_per_period"], "", "{what}: {row:?}");
                    assert_eq!(row["rtol"], "", "{what}: {row:?}");
                    let spc = if c.steps_per_contact { "100" } else { "" };
                    assert_eq!(row["steps_per_contact"], spc, "{what}: {row:?}");
                    assert!(
                        row["status"].contains("no-liggghts"),
                        "{what}: the code point should fail on the missing binary: {row:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_issue_sweep_puts_the_code_under_code() {
    // The sweep that once wrote `liggghts` under `steps_per_period` and left `code` empty.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("sweep.toml");
    let c = Combination {
        methods: None,
        steps_per_period: false,
        rtol: false,
        code: true,
        steps_per_contact: true,
    };
    std::fs::write(&file, c.toml()).unwrap();
    for format in ["csv", "jsonl"] {
        let output = common::millimpact()
            .args(["sweep", file.to_str().unwrap(), "--format", format])
            .env("MILLIMPACT_LIGGGHTS_BINARY", dir.path().join("no-liggghts"))
            .output()
            .unwrap();
        let text = String::from_utf8(output.stdout).unwrap();
        for row in rows(&text, format) {
            assert_eq!(row["code"], "liggghts", "{format}: {row:?}");
            assert_eq!(row["steps_per_contact"], "100", "{format}: {row:?}");
            assert_eq!(row["steps_per_period"], "", "{format}: {row:?}");
        }
    }
}
