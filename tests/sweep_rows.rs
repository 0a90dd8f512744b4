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
        // Both points fail on the missing binary: the sweep says so by its exit status, and
        // still writes one row per point with its parameters.
        assert_eq!(output.status.code(), Some(1), "{format}: {text}");
        let rows = rows(&text, format);
        assert_eq!(rows.len(), 2, "{format}: one row per η\n{text}");
        for row in rows {
            assert_eq!(row["code"], "liggghts", "{format}: {row:?}");
            assert_eq!(row["steps_per_contact"], "100", "{format}: {row:?}");
            assert_eq!(row["steps_per_period"], "", "{format}: {row:?}");
        }
    }
}

mod encoding {
    //! The rows' CSV bytes are the csv crate's: every kind of row (any text, any double, any
    //! axis value, empty cells) written by `CsvRecords` equals what `csv::Writer::serialize`
    //! writes for the same typed record, byte for byte, both forms.

    use millimpact::analysis::run::RunRecord as LegacyRow;
    use millimpact::analysis::sweep::{
        AxisValue, PointFigures, PointSource, RowIdentity, RowStatus, SweepRow,
    };
    use millimpact::codes::CodeName;
    use millimpact::model::figures::{Checked, Exact, Figures};
    use millimpact::output::{CsvRecords, header_of};
    use millimpact::solve::Method;
    use proptest::prelude::*;
    use serde::Serialize;

    /// Text with what CSV must quote (commas, quotes, line breaks) among the rest.
    fn text() -> impl Strategy<Value = String> {
        "[a-z0-9 ,\"\\n\\r#;:é.-]{0,14}"
    }

    /// Any double (NaN, infinities, subnormals), or one log-uniform over the doubles'
    /// magnitudes, of either sign: the exponent and plain forms of the shortest text.
    fn number() -> impl Strategy<Value = f64> {
        prop_oneof![
            any::<f64>(),
            (-323.0f64..308.0, any::<bool>()).prop_map(|(e, negative)| if negative {
                -1.0
            } else {
                1.0
            } * 10f64.powf(e)),
            (0u32..100_000).prop_map(|i| f64::from(i) * 1e-4),
        ]
    }

    fn axis_value() -> impl Strategy<Value = toml::Value> {
        prop_oneof![
            number().prop_map(toml::Value::Float),
            any::<i64>().prop_map(toml::Value::Integer),
            text().prop_map(toml::Value::String),
            any::<bool>().prop_map(toml::Value::Boolean),
        ]
    }

    fn row(axes: usize) -> impl Strategy<Value = SweepRow> {
        (
            (text(), any::<usize>()),
            proptest::collection::vec(axis_value(), axes),
            (
                proptest::option::of(proptest::sample::select(Method::ALL.to_vec())),
                proptest::option::of(proptest::sample::select(CodeName::ALL.to_vec())),
                proptest::option::of(any::<u32>()),
                proptest::option::of(any::<u32>()),
                proptest::option::of(number()),
            ),
            (
                proptest::option::of(text()),
                proptest::collection::vec(proptest::option::of(number()), 24),
                proptest::option::of(any::<u64>()),
                proptest::option::of(any::<u64>()),
                proptest::option::of(text()),
                proptest::option::of(any::<usize>()),
            ),
            prop_oneof![
                Just(RowStatus::ok()),
                text().prop_map(|t| RowStatus::failed(&t))
            ],
        )
            .prop_map(
                |(
                    (sweep, point),
                    values,
                    source,
                    (case, f, steps, rhs, version, batch),
                    status,
                )| {
                    SweepRow {
                        identity: RowIdentity { sweep, point },
                        axes: values
                            .into_iter()
                            .enumerate()
                            .map(|(i, value)| AxisValue {
                                key: format!("axis{i}"),
                                value,
                            })
                            .collect(),
                        source: PointSource {
                            method: source.0,
                            code: source.1,
                            steps_per_period: source.2,
                            steps_per_contact: source.3,
                            rtol: source.4,
                        },
                        figures: PointFigures {
                            case,
                            eta: f[0],
                            reduced_mass: f[1],
                            contact_stiffness: f[2],
                            exponent: f[3],
                            measured: Figures {
                                cor: f[4],
                                peak_deformation: f[7],
                                peak_force: f[10],
                                contact_time: f[12],
                                compression_time: f[15],
                                restitution_time: f[16],
                                ..Figures::default()
                            },
                            target: Figures {
                                cor: f[5],
                                ..Figures::default()
                            },
                            exact: Figures {
                                peak_deformation: f[8],
                                peak_force: f[11],
                                contact_time: f[13],
                                ..Figures::default()
                            },
                            error: Figures {
                                cor: f[6],
                                peak_deformation: f[9],
                                contact_time: f[14],
                                ..Figures::default()
                            },
                            absorbed_energy: f[17],
                            steps,
                            rhs_evaluations: rhs,
                            timestep: f[18],
                            wall_time: f[19],
                            loop_time: f[20],
                            whole_wall_time: f[21],
                            own_law_cor: f[22],
                            own_law_stepped_cor: f[23],
                            code_version: version,
                            batch,
                        },
                        status,
                    }
                },
            )
    }

    /// The legacy row's columns as plain fields, in the order the flattened row writes them:
    /// what the csv crate (which writes no maps) is given for the same values.
    #[derive(serde::Serialize)]
    struct FlatLegacyRow {
        case: String,
        method: &'static str,
        loss_coefficient: f64,
        cor: f64,
        peak_deformation: f64,
        peak_force: f64,
        contact_time: f64,
        compression_time: f64,
        restitution_time: f64,
        cor_exact: f64,
        peak_deformation_exact: f64,
        contact_time_exact: f64,
        cor_error: f64,
        peak_deformation_error: f64,
        contact_time_error: f64,
        absorbed_energy: f64,
        absorbed_fraction: f64,
        steps: u64,
        rhs_evaluations: u64,
        wall_time: f64,
    }

    impl From<&LegacyRow> for FlatLegacyRow {
        fn from(r: &LegacyRow) -> Self {
            FlatLegacyRow {
                case: r.case.clone(),
                method: r.method,
                loss_coefficient: r.loss_coefficient,
                cor: r.figures.cor,
                peak_deformation: r.figures.peak_deformation,
                peak_force: r.figures.peak_force,
                contact_time: r.figures.contact_time,
                compression_time: r.figures.compression_time,
                restitution_time: r.figures.restitution_time,
                cor_exact: r.exact.cor,
                peak_deformation_exact: r.exact.peak_deformation,
                contact_time_exact: r.exact.contact_time,
                cor_error: r.error.cor,
                peak_deformation_error: r.error.peak_deformation,
                contact_time_error: r.error.contact_time,
                absorbed_energy: r.absorbed_energy,
                absorbed_fraction: r.absorbed_fraction,
                steps: r.steps,
                rhs_evaluations: r.rhs_evaluations,
                wall_time: r.wall_time,
            }
        }
    }

    /// A point's figures as one flat struct, field by field in the columns' order: what the
    /// csv crate writes for them (it writes no flattened sets, which are maps to serde).
    #[derive(Default, Serialize)]
    struct FlatFigures<'a> {
        case: Option<&'a str>,
        eta: Option<f64>,
        reduced_mass: Option<f64>,
        contact_stiffness: Option<f64>,
        exponent: Option<f64>,
        cor: Option<f64>,
        peak_deformation: Option<f64>,
        peak_force: Option<f64>,
        contact_time: Option<f64>,
        compression_time: Option<f64>,
        restitution_time: Option<f64>,
        cor_target: Option<f64>,
        peak_deformation_exact: Option<f64>,
        peak_force_exact: Option<f64>,
        contact_time_exact: Option<f64>,
        cor_error: Option<f64>,
        peak_deformation_error: Option<f64>,
        contact_time_error: Option<f64>,
        absorbed_energy: Option<f64>,
        steps: Option<u64>,
        rhs_evaluations: Option<u64>,
        timestep: Option<f64>,
        wall_time: Option<f64>,
        loop_time: Option<f64>,
        whole_wall_time: Option<f64>,
        own_law_cor: Option<f64>,
        own_law_stepped_cor: Option<f64>,
        code_version: Option<&'a str>,
        batch: Option<usize>,
    }

    impl<'a> FlatFigures<'a> {
        fn of(f: &'a PointFigures) -> FlatFigures<'a> {
            FlatFigures {
                case: f.case.as_deref(),
                eta: f.eta,
                reduced_mass: f.reduced_mass,
                contact_stiffness: f.contact_stiffness,
                exponent: f.exponent,
                cor: f.measured.cor,
                peak_deformation: f.measured.peak_deformation,
                peak_force: f.measured.peak_force,
                contact_time: f.measured.contact_time,
                compression_time: f.measured.compression_time,
                restitution_time: f.measured.restitution_time,
                cor_target: f.target.cor,
                peak_deformation_exact: f.exact.peak_deformation,
                peak_force_exact: f.exact.peak_force,
                contact_time_exact: f.exact.contact_time,
                cor_error: f.error.cor,
                peak_deformation_error: f.error.peak_deformation,
                contact_time_error: f.error.contact_time,
                absorbed_energy: f.absorbed_energy,
                steps: f.steps,
                rhs_evaluations: f.rhs_evaluations,
                timestep: f.timestep,
                wall_time: f.wall_time,
                loop_time: f.loop_time,
                whole_wall_time: f.whole_wall_time,
                own_law_cor: f.own_law_cor,
                own_law_stepped_cor: f.own_law_stepped_cor,
                code_version: f.code_version.as_deref(),
                batch: f.batch,
            }
        }
    }

    /// The figures' columns are named as the csv crate names the flat struct's fields.
    #[test]
    fn the_figures_columns_are_the_flat_structs_fields() {
        let mut csv = csv::Writer::from_writer(Vec::new());
        csv.serialize(FlatFigures::default()).unwrap();
        let csv = csv.into_inner().unwrap();
        let header = csv.split(|&b| b == b'\n').next().unwrap();
        assert_eq!(
            String::from_utf8_lossy(&header_of(&PointFigures::default()).unwrap()),
            format!("{}\n", String::from_utf8_lossy(header))
        );
    }

    fn legacy_row() -> impl Strategy<Value = LegacyRow> {
        (
            text(),
            proptest::sample::select(Method::ALL.to_vec()),
            proptest::collection::vec(number(), 15),
            any::<u64>(),
            any::<u64>(),
            number(),
        )
            .prop_map(|(case, method, f, steps, rhs, wall)| LegacyRow {
                case,
                method: method.name(),
                loss_coefficient: f[0],
                figures: Exact {
                    cor: f[1],
                    peak_deformation: f[2],
                    peak_force: f[3],
                    contact_time: f[4],
                    compression_time: f[5],
                    restitution_time: f[6],
                    ..Default::default()
                },
                exact: Checked {
                    cor: f[7],
                    peak_deformation: f[8],
                    contact_time: f[9],
                    ..Default::default()
                },
                error: Checked {
                    cor: f[10],
                    peak_deformation: f[11],
                    contact_time: f[12],
                    ..Default::default()
                },
                absorbed_energy: f[13],
                absorbed_fraction: f[14],
                steps,
                rhs_evaluations: rhs,
                wall_time: wall,
            })
    }

    fn rows() -> impl Strategy<Value = Vec<SweepRow>> {
        (0usize..4).prop_flat_map(|axes| proptest::collection::vec(row(axes), 1..6))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        /// A sweep file's rows, and the lines they take (a failed row's line is found by it).
        #[test]
        fn sweep_rows_are_the_csv_crates_bytes(rows in rows()) {
            let mut csv = csv::WriterBuilder::new()
                .has_headers(false)
                .terminator(csv::Terminator::Any(b'\n'))
                .from_writer(Vec::new());
            let mut ours = CsvRecords::default();
            for r in &rows {
                let axes: Vec<&toml::Value> = r.axes.iter().map(|a| &a.value).collect();
                csv.serialize((&r.identity, axes, &r.source, FlatFigures::of(&r.figures), &r.status))
                    .unwrap();
                r.write_csv(&mut ours).unwrap();
            }
            let csv = csv.into_inner().unwrap();
            prop_assert_eq!(
                String::from_utf8_lossy(ours.as_bytes()),
                String::from_utf8_lossy(&csv)
            );
            prop_assert_eq!(ours.as_bytes(), &csv[..]);
            prop_assert_eq!(ours.lines(), csv.iter().filter(|&&b| b == b'\n').count());
            prop_assert_eq!(ours.records(), rows.len());
        }

        /// The legacy form's rows with their header (the flattened figures' columns named and
        /// written as plain fields would be).
        #[test]
        fn legacy_rows_are_the_csv_crates_bytes(
            rows in proptest::collection::vec(legacy_row(), 1..6)
        ) {
            let mut csv = csv::Writer::from_writer(Vec::new());
            let mut ours = CsvRecords::default();
            for r in &rows {
                csv.serialize(FlatLegacyRow::from(r)).unwrap();
                ours.push(r).unwrap();
            }
            let csv = csv.into_inner().unwrap();
            let ours = [header_of(&rows[0]).unwrap(), ours.into_bytes()].concat();
            prop_assert_eq!(String::from_utf8_lossy(&ours), String::from_utf8_lossy(&csv));
            prop_assert_eq!(ours, csv);
        }
    }
}
