//! `millimpact report`: the figures and tables of a self-contained report on model agreement,
//! each with the data behind it and the command that reproduces it. From stored references it
//! runs no DEM code.

mod mill;

use std::path::Path;
use std::time::Duration;

use serde::Serialize;
use thiserror::Error;

pub use mill::{add_mills, mill_part};

use super::benchmark::cor_chart::cor_chart;
use super::benchmark::{self, BenchmarkError, BenchmarkOptions, CodeRuns};
use super::compare::{
    CompareError, CompareOptions, CompareReport, CompareSource, ModelPointRecord, compare,
};
use super::deck::DeckReport;
use super::precision::{PrecisionError, method_sweep};
use super::stability::{METHODS, stability_report};
use super::store::{self, CodeLawError, StoreError, own_law_exact};
use crate::codes::{self, CodeName};
use crate::error::Blame;
use crate::model::case::{Case, CaseError, ContactKind};
use crate::model::exact;
use crate::model::law::{CodeLaw, DashpotLaw};
use crate::model::shipped::shipped_case;
use crate::output::chart::{Chart, Series, Style, chart_svg, map_svg};
use crate::output::invocation::Invocation;
pub use crate::output::report_page::ReportFigure;
use crate::output::{Format, OutputError, Section, Summary, csv_string, export, signed};
use crate::solve::paper::{self, Settings};
use crate::solve::{Method, SolveError};

/// One table: formatted cells, the data behind it, and how to reproduce it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReportTable {
    /// File stem (`<id>.csv`, `<id>.json`).
    pub id: String,
    /// Title.
    pub title: String,
    /// Column headers.
    pub headers: Vec<String>,
    /// Rows.
    pub rows: Vec<Vec<String>>,
    /// Notes under it.
    pub notes: Vec<String>,
    /// The command that reproduces it.
    pub command: String,
}

/// A part of the report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReportPart {
    /// Anchor.
    pub id: String,
    /// Heading.
    pub title: String,
    /// Text under the heading.
    pub intro: String,
    /// Figures.
    pub figures: Vec<ReportFigure>,
    /// Tables.
    pub tables: Vec<ReportTable>,
}

/// Files written beside the pages: the data behind the tables, as the commands export them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DataFile {
    /// File name.
    pub name: String,
    /// Contents.
    pub text: String,
}

/// The whole report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// Title.
    pub title: String,
    /// The parts.
    pub parts: Vec<ReportPart>,
    /// Appendix lines: versions, revision, date, reproduce commands.
    pub appendix: Vec<String>,
    /// Extra data files (JSON and CSV of whole summaries).
    #[serde(skip)]
    pub data: Vec<DataFile>,
    /// Codes asked to run (`--live`) that did not, and why.
    #[serde(skip)]
    pub failures: Vec<String>,
}

/// How to build the report.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ReportOptions {
    /// Run the codes now.
    pub live: bool,
    /// Folder of stored references.
    pub reference: std::path::PathBuf,
    /// Time limit per code run (live).
    pub timeout: Duration,
    /// millimpact's git revision, if known.
    pub revision: Option<String>,
}

/// Why the report could not be built; each variant names the case, the code or the part
/// that failed, or wraps the failure of the analysis it draws on.
#[derive(Debug, Error)]
pub enum ReportError {
    /// A figure or table could not be drawn or written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A built-in case is invalid.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// The paper's law could not be integrated for a figure.
    #[error("{case}: the paper's law")]
    PaperLaw {
        /// The case's name.
        case: String,
        /// Why.
        source: SolveError,
    },
    /// A code's run could not be sized, or its own law not integrated.
    #[error(transparent)]
    Law(#[from] CodeLawError),
    /// A code's card offers a setting to take at its word, but not for this setup.
    #[error("{code}: no setting to take at its word")]
    NoSettingAtItsWord {
        /// The code.
        code: CodeName,
    },
    /// The comparison failed.
    #[error(transparent)]
    Compare(#[from] CompareError),
    /// The work–precision sweep failed.
    #[error(transparent)]
    Precision(#[from] PrecisionError),
    /// The stored references could not be read.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// The benchmark's COR chart could not be built.
    #[error(transparent)]
    Benchmark(#[from] BenchmarkError),
}

impl Blame for ReportError {
    fn is_user_error(&self) -> bool {
        match self {
            ReportError::Case(_) => true,
            ReportError::Compare(e) => e.is_user_error(),
            ReportError::Store(e) => e.is_user_error(),
            ReportError::Benchmark(e) => e.is_user_error(),
            _ => false,
        }
    }
}

/// A figure's points as CSV, one row per point: its series, then `x` and `y` under the
/// axes' names.
fn series_csv(x: &str, y: &str, series: &[Series]) -> Result<String, OutputError> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(["series", x, y])?;
    for s in series {
        for (a, b) in &s.points {
            writer.serialize((&s.name, a, b))?;
        }
    }
    let bytes = writer
        .into_inner()
        .map_err(|e| csv::Error::from(e.into_error()))?;
    // Names and numbers written from strings and floats: UTF-8 throughout.
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

fn figure(
    id: &str,
    chart: Chart,
    caption: &str,
    command: &str,
    csv_names: (&str, &str),
) -> Result<ReportFigure, ReportError> {
    Ok(ReportFigure {
        id: id.to_string(),
        title: chart.title.clone(),
        caption: caption.to_string(),
        svg: chart_svg(&chart, 960, 520)?,
        csv: series_csv(csv_names.0, csv_names.1, &chart.series)?,
        command: command.to_string(),
    })
}

fn table_from(id: String, s: &Section, command: &str) -> ReportTable {
    ReportTable {
        id,
        title: s.title.clone().unwrap_or_default(),
        headers: s.headers.clone(),
        rows: s.rows.clone(),
        notes: s.notes.clone(),
        command: command.to_string(),
    }
}

/// The paper's law on `case` by `settings`.
fn solve_case(case: &Case, settings: &Settings) -> Result<paper::Outcome, ReportError> {
    paper::solve(&case.law(), case.impact_velocity, settings).map_err(|source| {
        ReportError::PaperLaw {
            case: case.name.clone(),
            source,
        }
    })
}

/// The paper's Figure 2: the rod end at η = 0.35 with two-sided contact, displacement and
/// velocity against time, beside the damped harmonic oscillator with the same loss per
/// half-cycle.
fn figure_2() -> Result<Vec<ReportFigure>, ReportError> {
    let case = shipped_case("rod_end_bilateral")?;
    let law = case.law();
    let v0 = case.impact_velocity;
    let settings = Settings {
        method: Method::Rk4,
        contact: ContactKind::Bilateral,
        record: true,
        periods: 3.0,
        ..Settings::default()
    };
    let out = solve_case(&case, &settings)?;
    let e = exact::restitution(law.loss_coefficient);
    let zeta = DashpotLaw::damping_ratio(e);
    let w0 = (law.stiffness / law.mass).sqrt();
    let wd = w0 * (1.0 - zeta * zeta).sqrt();
    let t_end = out.trajectory.last().map_or(0.0, |s| s.t);
    let oscillator = |t: f64| {
        let decay = (-zeta * w0 * t).exp();
        (
            v0 / wd * decay * (wd * t).sin(),
            v0 * decay * ((wd * t).cos() - zeta * w0 / wd * (wd * t).sin()),
        )
    };
    let grid: Vec<f64> = (0..=1500).map(|i| t_end * i as f64 / 1500.0).collect();
    let ms = 1e3;
    let um = 1e6;
    let paper_y: Vec<(f64, f64)> = out
        .trajectory
        .iter()
        .map(|s| (s.t * ms, s.y * um))
        .collect();
    let paper_v = out.trajectory.iter().map(|s| (s.t * ms, s.v)).collect();
    let osc_y = grid
        .iter()
        .map(|&t| (t * ms, oscillator(t).0 * um))
        .collect();
    let osc_v = grid.iter().map(|&t| (t * ms, oscillator(t).1)).collect();
    let command = "millimpact run cases/rod_end_bilateral.toml --method rk4 --trajectory fig2.csv";
    let caption = format!(
        "Rod end on a rigid plate, η = {}, two-sided contact (paper Eq. 14), the paper's RK4 at T/1000; beside it the damped harmonic oscillator with the same undamped frequency and the same loss per half-cycle (ζ = {:.4}, speed ratio e = {:.4} per half-cycle). The paper's law decays linearly in amplitude ratio per half-cycle with a kinked velocity at each turning point; the oscillator's is smooth.",
        law.loss_coefficient, zeta, e
    );
    [
        (
            "displacement",
            "2a",
            "approach y (µm)",
            paper_y,
            osc_y,
            "y_um",
        ),
        (
            "velocity",
            "2b",
            "approach rate ẏ (m/s)",
            paper_v,
            osc_v,
            "v_m_per_s",
        ),
    ]
    .into_iter()
    .map(|(what, number, y_label, paper, oscillator, column)| {
        let chart = Chart {
            title: format!("Figure {number}: rod end {what}, η = 0.35"),
            x_label: "time t (ms)".into(),
            y_label: y_label.into(),
            series: vec![
                Series::new("paper's law, bilateral", paper, Style::Line),
                Series::new("damped oscillator, same loss", oscillator, Style::Thin),
            ],
        };
        figure(
            &format!("fig2-{what}"),
            chart,
            &caption,
            command,
            ("t_ms", column),
        )
    })
    .collect()
}

/// The paper's Figure 3: COR against η, rod (line) and ball (dots) by the paper's RK4, the
/// closed form, and the small-η line 1 − η.
fn figure_3() -> Result<ReportFigure, ReportError> {
    let etas: Vec<f64> = (0..=19).map(|i| 0.05 * i as f64).collect();
    let mut series = Vec::new();
    for (name, file, style) in [
        ("rod end, rk4 (line)", "rod_end", Style::Line),
        ("ball on plate, rk4 (dots)", "ball_plate", Style::Dots),
    ] {
        let case = shipped_case(file)?;
        let settings = Settings {
            method: Method::Rk4,
            ..Settings::default()
        };
        let pts = etas
            .iter()
            .map(|&eta| {
                let out = solve_case(&case.with_loss_coefficient(eta), &settings)?;
                Ok((eta, out.figures.cor))
            })
            .collect::<Result<_, ReportError>>()?;
        series.push(Series::new(name, pts, style));
    }
    let fine: Vec<f64> = (0..=200).map(|i| 0.95 * i as f64 / 200.0).collect();
    series.push(Series::new(
        "closed form √((1−η)/(1+η))",
        fine.iter().map(|&h| (h, exact::restitution(h))).collect(),
        Style::Thin,
    ));
    series.push(Series::new(
        "small-η line 1 − η",
        fine.iter().map(|&h| (h, 1.0 - h)).collect(),
        Style::Thin,
    ));
    figure(
        "fig3-cor-vs-eta",
        Chart {
            title: "Figure 3: COR against the loss coefficient".into(),
            x_label: "loss coefficient η (–)".into(),
            y_label: "coefficient of restitution e (–)".into(),
            series,
        },
        "The rod (linear, n = 1) and the ball (Hertz, n = 1.5) give one curve: the COR depends on η alone. Numerical points by the paper's RK4 at T/1000; the closed form through them; the line 1 − η it bends away from as η grows.",
        "millimpact sweep cases/rod_end.toml --loss-coefficient 0:0.95:0.05 --method rk4 (and cases/ball_plate.toml)",
        ("eta", "cor"),
    )
}

/// Force–overlap loops and force–time curves of the paper's law and each code's law.
fn force_figures(case: &Case) -> Result<Vec<ReportFigure>, ReportError> {
    let law = case.law();
    let settings = Settings {
        method: Method::Rk4Event,
        steps_per_period: 2000,
        record: true,
        ..Settings::default()
    };
    let out = solve_case(case, &settings)?;
    let (um, kn, us) = (1e6, 1e-3, 1e6);
    let mut loops = vec![Series::new(
        "paper's law",
        out.trajectory
            .iter()
            .map(|s| (s.y * um, law.force(s.y, s.v) * kn))
            .collect(),
        Style::Line,
    )];
    let mut times = vec![Series::new(
        "paper's law",
        out.trajectory
            .iter()
            .map(|s| (s.t * us, law.force(s.y, s.v) * kn))
            .collect(),
        Style::Line,
    )];
    for &code in CodeName::ALL {
        let driver = code.driver();
        let setup = store::prepare(code, case, None, None, false)?;
        let own = driver.law(&setup);
        let t = driver.stepping(&setup).trajectory(
            &own,
            setup.impact_velocity,
            setup.timestep,
            setup.steps,
            0.0,
        );
        let end = t
            .overlap
            .iter()
            .skip(1)
            .position(|&y| y <= 0.0)
            .map_or(t.time.len(), |k| k + 2);
        let name = CompareSource::CodeLawStepped(code).to_string();
        let style = if driver.shares_law_with().is_some() {
            Style::Thin
        } else {
            Style::Line
        };
        let force = |x: &[f64], scale: f64| -> Vec<(f64, f64)> {
            (0..end)
                .map(|i| (x[i] * scale, t.normal_force[i] * kn))
                .collect()
        };
        loops.push(Series::new(name.clone(), force(&t.overlap, um), style));
        times.push(Series::new(name, force(&t.time, us), style));
    }
    let n = &case.name;
    let caption_loop = format!(
        "{n}, η = {}: normal force against overlap. The paper's law loads along C(1+η)yⁿ and unloads along C(1−η)yⁿ with a jump at the turning point; the codes' viscoelastic laws at the same COR draw a rounded loop with a lower peak, and end with the force at or below zero while overlap is left. LIGGGHTS and LAMMPS run the same law (the lines coincide).",
        case.loss_coefficient
    );
    let caption_time = format!(
        "{n}, η = {}: normal force against time. The codes' force returns to zero well before the overlap closes (force-based contact end).",
        case.loss_coefficient
    );
    let command = Invocation::new("compare")
        .arg(format!("cases/{n}.toml"))
        .to_string();
    Ok(vec![
        figure(
            &format!("force-overlap-{n}"),
            Chart {
                title: format!("Force–overlap loop, {n}"),
                x_label: "overlap y (µm)".into(),
                y_label: "normal force F (kN)".into(),
                series: loops,
            },
            &caption_loop,
            &command,
            ("overlap_um", "force_kN"),
        )?,
        figure(
            &format!("force-time-{n}"),
            Chart {
                title: format!("Force against time, {n}"),
                x_label: "time t (µs)".into(),
                y_label: "normal force F (kN)".into(),
                series: times,
            },
            &caption_time,
            &command,
            ("t_us", "force_kN"),
        )?,
    ])
}

/// The codes' model differences as functions of e (from the compare report's points).
fn model_by_e_figure(c: &super::compare::CaseComparison) -> Result<ReportFigure, ReportError> {
    let mut series = Vec::new();
    for &code in CodeName::ALL {
        let pts: Vec<_> = c
            .model_by_restitution
            .iter()
            .filter(|p| p.code == code)
            .collect();
        for (what, f) in [
            (
                "peak force",
                (|p: &super::compare::ModelPoint| p.offsets.peak_force) as fn(&_) -> f64,
            ),
            ("contact time by force", |p| p.offsets.force_contact_time),
            ("contact time by overlap", |p| p.offsets.contact_time),
            ("peak deformation", |p| p.offsets.peak_deformation),
        ] {
            series.push(Series::new(
                format!("{code}: {what}"),
                pts.iter().map(|p| (p.restitution, 100.0 * f(p))).collect(),
                if code.driver().shares_law_with().is_some() {
                    Style::Dots
                } else {
                    Style::Line
                },
            ));
        }
    }
    figure(
        &format!("model-by-e-{}", c.case),
        Chart {
            title: format!("Model difference from the paper's law, {}", c.case),
            x_label: "coefficient of restitution e (–)".into(),
            y_label: "code's law − paper's law (% of the paper's)".into(),
            series,
        },
        "Each code's law, as its driver sets it for the COR, against the paper's law at the same COR, both integrated exactly. Peak force and force-based contact time differ most; all differences vanish as e → 1. LAMMPS (dots) runs the same law as LIGGGHTS.",
        &Invocation::new("compare")
            .arg(&c.path)
            .option("--format", "csv")
            .to_string(),
        ("e", "difference_percent"),
    )
}

/// The COR each code realises against the COR asked of it, as the drivers set the code up and
/// as a user who takes each code's setting at its word would (LAMMPS `tsuji` with e_in = e,
/// YADE `en = e`, the clamps on).
fn realised_vs_requested() -> Result<(ReportFigure, ReportTable), ReportError> {
    let case = shipped_case("ball_plate")?;
    let es: Vec<f64> = (0..=13).map(|i| 0.3 + 0.05 * i as f64).collect();
    let mut series: Vec<Series> = Vec::new();
    let mut add = |name: &str,
                   style: Style,
                   f: &dyn Fn(&Case) -> Result<f64, ReportError>|
     -> Result<(), ReportError> {
        let mut pts = Vec::new();
        for &e in &es {
            let at = case.with_loss_coefficient(exact::loss_coefficient(e));
            pts.push((e, f(&at)? - e));
        }
        series.push(Series::new(name, pts, style));
        Ok(())
    };
    let cor_of = |code: CodeName, law: &CodeLaw, v0: f64| -> Result<f64, ReportError> {
        Ok(own_law_exact(code, law, v0, 1e-11)?.cor)
    };
    for &code in CodeName::ALL {
        add(
            &format!("{code}, as the driver sets it"),
            Style::Dots,
            &|at| {
                let setup = codes::setup_for_case(at, 1.0);
                cor_of(code, &code.driver().law(&setup), at.impact_velocity)
            },
        )?;
    }
    // A user who takes each code's COR setting at its word, once per distinct setting.
    let mut labels = Vec::new();
    for &code in CodeName::ALL {
        let Some(card) = code.driver().card() else {
            continue;
        };
        let probe_setup = codes::setup_for_case(&case, 1.0);
        let Some((label, _)) = card.law_at_its_word(&probe_setup) else {
            continue;
        };
        if labels.contains(&label) {
            continue;
        }
        labels.push(label);
        add(&format!("{code}, {label}"), Style::Line, &|at| {
            let setup = codes::setup_for_case(at, 1.0);
            let (_, law) = card
                .law_at_its_word(&setup)
                .ok_or(ReportError::NoSettingAtItsWord { code })?;
            cor_of(code, &law.into(), at.impact_velocity)
        })?;
    }
    let mut clamps: Vec<&str> = Vec::new();
    let mut clamped_code = None;
    for &code in CodeName::ALL {
        if let Some(setting) = code.driver().card().and_then(|c| c.clamp_setting()) {
            clamped_code.get_or_insert(code);
            if !clamps.contains(&setting) {
                clamps.push(setting);
            }
        }
    }
    if let Some(code) = clamped_code {
        add(
            &format!("clamp on ({})", clamps.join(", ")),
            Style::Line,
            &|at| {
                let setup = codes::setup_for_case(at, 1.0);
                cor_of(
                    code,
                    &code.driver().law(&setup).clamped(),
                    at.impact_velocity,
                )
            },
        )?;
    }
    let command =
        "millimpact report (figure realised-vs-requested; from the codes' laws, no code run)";
    let mut headers = vec!["requested e".to_string()];
    headers.extend(series.iter().map(|s| s.name.clone()));
    let rows = es
        .iter()
        .enumerate()
        .map(|(i, e)| {
            let mut r = vec![format!("{e:.2}")];
            r.extend(series.iter().map(|s| format!("{:.6}", s.points[i].1 + e)));
            r
        })
        .collect();
    let fig = figure(
        "realised-vs-requested",
        Chart {
            title: "Realised minus requested COR, ball on plate".into(),
            x_label: "requested COR e (–)".into(),
            y_label: "realised − requested COR (–)".into(),
            series,
        },
        "From each code's own law integrated exactly (no code run). Dots: the codes as the drivers set them up (LAMMPS tsuji compensated, YADE en from the Thornton inversion, no clamp): on zero. Lines: as a user who takes each setting at its word would: LAMMPS tsuji with e_in = e realises a higher COR; YADE with en = e misses by the fit's error; a clamp (LIGGGHTS limitForce on, LAMMPS limit_damping) cuts the attractive tail and raises the COR.",
        command,
        ("requested_e", "realised_minus_requested"),
    )?;
    let table = ReportTable {
        id: "realised-vs-requested-table".into(),
        title: "Realised COR against requested, ball on plate (own laws, exact)".into(),
        headers,
        rows,
        notes: vec![],
        command: command.into(),
    };
    Ok((fig, table))
}

fn log10(x: f64) -> f64 {
    x.max(1e-17).log10()
}

/// The work–precision diagram on ball_plate: the paper's-law methods swept now, and each DEM
/// code's stored run at the case's η as one point.
fn work_precision(reference: &Path) -> Result<ReportFigure, ReportError> {
    let case = shipped_case("ball_plate")?;
    let mut series = Vec::new();
    for &m in Method::ALL.iter().filter(|m| m.integrates()) {
        let points = method_sweep(&case, m, 3)?;
        series.push(Series::new(
            m.to_string(),
            points
                .iter()
                .map(|p| (log10(p.max_error), log10(p.time_s)))
                .collect(),
            Style::Line,
        ));
    }
    for &code in CodeName::ALL {
        let Some(r) = store::find_stored(reference, code, &case.name, case.loss_coefficient)?
        else {
            continue;
        };
        // As `precision` measures a code: against its own law at zero step error, so that the
        // point is the code's integration error, not the model difference.
        let exact = &r.law_exact;
        let error = [
            (r.figures.cor - exact.cor) / exact.cor,
            (r.figures.peak_deformation - exact.peak_deformation) / exact.peak_deformation,
            (r.figures.contact_time - exact.contact_time) / exact.contact_time,
        ]
        .iter()
        .fold(0.0f64, |worst, e| worst.max(e.abs()));
        series.push(Series::new(
            format!("{code} (stored run)"),
            vec![(log10(error), log10(r.wall_time))],
            Style::Dots,
        ));
    }
    figure(
        "work-precision",
        Chart {
            title: "Work–precision, ball on plate (this machine, now)".into(),
            x_label: "log₁₀ largest relative error (COR, peak, contact time)".into(),
            y_label: "log₁₀ run time of one impact (s)".into(),
            series,
        },
        "Each method of the paper's law swept over its knob (steps per period, or rtol), error against the closed forms, median of 3 timed runs. Each DEM code is a dot: its stored run at the case's η (1000 steps per elastic contact), error against the code's own law at zero step error, time the process wall time, almost all of it start-up. The codes' sweeps over the step are in reference/work-precision*.md (millimpact precision CASE --codes ...).",
        "millimpact precision cases/ball_plate.toml --repeats 3",
        ("log10_error", "log10_time_s"),
    )
}

/// The stability grid as a map: one row per method, one cell per grid case.
fn stability_map() -> Result<ReportFigure, ReportError> {
    let report = stability_report();
    let classes = [
        (
            "accurate (within its tolerance)",
            plotters::style::RGBColor(0, 150, 80),
        ),
        (
            "bounded, finite, outside tolerance",
            plotters::style::RGBColor(230, 160, 0),
        ),
        (
            "fails its criterion",
            plotters::style::RGBColor(210, 40, 30),
        ),
    ];
    let rows: Vec<(String, Vec<usize>)> = METHODS
        .iter()
        .map(|&m| {
            let cells = report
                .cases
                .iter()
                .filter(|c| c.method == m)
                .map(|c| match (c.pass, c.accurate) {
                    (true, true) => 0,
                    (true, false) => 1,
                    _ => 2,
                })
                .collect();
            (m.to_string(), cells)
        })
        .collect();
    let n = rows.first().map_or(0, |r| r.1.len());
    let svg = map_svg(
        &format!("Stability grid: {n} cases by each method"),
        "grid case, in the order of stability-map.csv",
        &rows,
        &classes,
        960,
        360,
    )?;
    let csv = csv_string(&report.records())?;
    Ok(ReportFigure {
        id: "stability-map".into(),
        title: "Stability grid".into(),
        caption: "Every built-in stiff or extreme case (E 1e5–1e15 Pa, R 1e-6–1 m, v0 1e-8–1e3 m/s, η 0–0.999999, mass and aspect ratios) by each method: green within the method's stated tolerance, amber finite and bounded but outside it, red failing the method's criterion.".into(),
        svg,
        csv,
        command: "millimpact stability --format json".into(),
    })
}

/// Chung & Ooi's test 3 as `benchmark chung-ooi --chart` draws it, from the benchmark's stored
/// runs under `reference` (a build without them is left out of the figure).
fn benchmark_cor_chart(reference: &Path) -> Result<Vec<ReportFigure>, ReportError> {
    let options = BenchmarkOptions {
        codes: CodeRuns::Stored(reference.join(benchmark::STORED_FOLDER)),
        ..BenchmarkOptions::default()
    };
    let report = benchmark::chung_ooi(&options)?;
    Ok(cor_chart(&report)?.figures()?)
}

/// The stored oblique runs (`<reference>/oblique/`) against Coulomb's closed form, one row per
/// build and case; `None` where the store holds none.
fn tangential_part(reference: &Path) -> Result<Option<ReportPart>, ReportError> {
    let folder = reference.join(crate::analysis::store::OBLIQUE_FOLDER);
    let mut section = Section::new(
        Some("Oblique impacts on a plate: each build's motion after the impact against Coulomb's closed form at the run's own COR".into()),
        &[
            "build",
            "case",
            "COR realised",
            "v_t' (m/s)",
            "closed form",
            "ω' (rad/s)",
            "closed form",
            "change of v_t off",
            "change of ω off",
            "allowed",
        ],
    );
    let optional = |x: Option<f64>| x.map_or_else(|| "—".to_string(), crate::output::sci);
    for path in crate::analysis::store::stored_files(&folder)? {
        for run in crate::analysis::store::load(&path)?.runs {
            let Some(t) = &run.tangential else { continue };
            section.rows.push(vec![
                format!("{} {}", run.code, run.code_version),
                run.case.clone(),
                format!("{:.6}", run.figures.cor),
                crate::output::sci(t.tangential_velocity_out),
                optional(t.tangential_velocity_closed_form),
                crate::output::sci(t.angular_velocity_out),
                optional(t.angular_velocity_closed_form),
                t.tangential_change_error.map_or_else(|| "—".into(), signed),
                t.spin_change_error.map_or_else(|| "—".into(), signed),
                optional(t.allowed_change_error),
            ]);
        }
    }
    if section.rows.is_empty() {
        return Ok(None);
    }
    section.notes = vec![
        "The change the impact makes, (Δ_code − Δ_closed)/|Δ_closed|, allowed 1 % plus the friction a damped law's attractive tail carries under a bound on μ|F_n|; the stock builds' 0.7–0.9 % is that tail's (0.05 % with --clamp), the spin's 0.1–0.3 % short in LIGGGHTS, YADE and Kratos their torque's lever at a wall (R − δ/2, R − δ).".into(),
    ];
    Ok(Some(ReportPart {
        id: "tangential".into(),
        title: "The tangential half".into(),
        intro: "An oblique or spinning ball on a plate in every build that runs one, from the stored runs that verify checks.".into(),
        figures: Vec::new(),
        tables: vec![table_from(
            "tangential".into(),
            &section,
            "millimpact reference --code CODE cases/oblique/CASE.toml",
        )],
    }))
}

/// Build the report for `cases`; `progress` is told each stage as it starts (one per case
/// compared, then one per part).
pub(crate) fn build_report(
    cases: &[Case],
    options: &ReportOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<Report, ReportError> {
    let compare_options = CompareOptions {
        live: options.live,
        reference: options.reference.clone(),
        timeout: options.timeout,
    };
    let mut compared = compare(&[], &compare_options)?;
    for case in cases {
        progress(&format!(
            "{}: {}",
            case.name,
            if options.live {
                "running the codes"
            } else {
                "comparing"
            }
        ));
        compared
            .cases
            .extend(compare(std::slice::from_ref(case), &compare_options)?.cases);
    }
    progress("the paper's figures");
    let paths: Vec<String> = cases.iter().map(|c| c.path.display().to_string()).collect();
    let compare_command = Invocation::new("compare")
        .args(&paths)
        .flag("--live", options.live)
        .to_string();
    let mut parts = Vec::new();
    parts.push(ReportPart {
        id: "paper".into(),
        title: "The paper's figures".into(),
        intro: "The law F = C yⁿ (1 + η sign ẏ): its decaying two-sided oscillation (Figure 2) and its COR, which depends on η alone (Figure 3).".into(),
        figures: {
            let mut f = figure_2()?;
            f.push(figure_3()?);
            f
        },
        tables: vec![],
    });
    progress("force–overlap loops");
    let force = cases
        .iter()
        .map(force_figures)
        .collect::<Result<Vec<_>, _>>()?;
    parts.push(ReportPart {
        id: "models".into(),
        title: "The model difference at a glance".into(),
        intro: "At equal COR the codes' viscoelastic laws and the paper's hysteretic law draw different loops: lower peak force, and a force that ends before the overlap closes.".into(),
        figures: force.concat(),
        tables: vec![],
    });
    let tables = compared
        .sections()
        .iter()
        .enumerate()
        .map(|(i, s)| table_from(format!("agreement-{i}"), s, &compare_command))
        .collect();
    let by_e = compared
        .cases
        .iter()
        .map(model_by_e_figure)
        .collect::<Result<_, _>>()?;
    parts.push(ReportPart {
        id: "agreement".into(),
        title: "Agreement: every figure, every source".into(),
        intro: format!(
            "From {}. Contact time by overlap (first touch until the overlap returns to zero; the figure quoted before) and by force (until the normal force first returns to zero). Each code's difference from the paper's law is split into model (own law exact − paper's law exact), integration (own law stepped − own law exact, given as a band over where the first contact falls within a step, with the stored run's start as a point in it) and a remainder (code − own law stepped).",
            if options.live { "the installed codes, run now" } else { "the stored references" }
        ),
        figures: by_e,
        tables,
    });
    progress("realised against requested COR");
    let (fig, table) = realised_vs_requested()?;
    let mut figures = vec![fig];
    figures.extend(benchmark_cor_chart(&options.reference)?);
    parts.push(ReportPart {
        id: "conventions".into(),
        title: "Where each code's convention bites".into(),
        intro: "The COR each code realises against the COR asked of it, set up as the drivers set it and as a user who takes each setting at its word would; then Chung & Ooi's test 3 in every build, from the benchmark's stored runs.".into(),
        figures,
        tables: vec![table],
    });
    parts.push(ReportPart {
        id: "cost".into(),
        title: "Accuracy, cost and stability".into(),
        intro: "The integrators of the paper's law: error against run time, and a grid of stiff and extreme cases.".into(),
        figures: {
            progress("work–precision and stability");
            vec![
                work_precision(&options.reference)?,
                stability_map()?,
            ]
        },
        tables: vec![],
    });
    progress("the tangential half");
    if let Some(part) = tangential_part(&options.reference)? {
        parts.push(part);
    }
    let appendix = appendix(options, &paths)?;
    let data = compare_data(&compared)?;
    Ok(Report {
        title: "millimpact: the paper's contact law against the DEM codes".into(),
        parts,
        appendix,
        data,
        failures: compared.failures(),
    })
}

/// The report's appendix: the build, its revision, the date, where the code figures come from,
/// each stored code's version, and the command that reproduces the whole report.
fn appendix(options: &ReportOptions, paths: &[String]) -> Result<Vec<String>, ReportError> {
    let mut versions = std::collections::BTreeSet::new();
    for path in store::stored_files(&options.reference)? {
        for r in store::load(&path)?.runs {
            versions.insert(format!("{}: {}", r.code, r.code_version));
        }
    }
    let mut appendix = vec![
        format!("millimpact {}", env!("CARGO_PKG_VERSION")),
        format!(
            "git revision: {}",
            options.revision.clone().unwrap_or_else(|| "unknown".into())
        ),
        format!(
            "date: {}",
            chrono::Utc::now().to_rfc3339_opts(chrono::SecondsFormat::Secs, true)
        ),
        format!(
            "source of the code figures: {}",
            if options.live {
                "codes run now"
            } else {
                "stored references (reference/)"
            }
        ),
    ];
    appendix.extend(versions.into_iter().map(|v| format!("code version, {v}")));
    appendix.push(format!(
        "reproduce the whole report: {}",
        Invocation::new("report")
            .args(paths)
            .flag("--live", options.live)
    ));
    Ok(appendix)
}

/// The comparison behind the agreement tables, as `compare` exports it, and the model
/// difference against e.
fn compare_data(compared: &CompareReport) -> Result<Vec<DataFile>, ReportError> {
    Ok(vec![
        DataFile {
            name: "compare.json".into(),
            text: serde_json::to_string_pretty(compared).map_err(OutputError::from)? + "\n",
        },
        DataFile {
            name: "compare.csv".into(),
            text: csv_string(&compared.records())?,
        },
        DataFile {
            name: "model-by-e.csv".into(),
            text: csv_string(
                &compared
                    .cases
                    .iter()
                    .flat_map(|c| c.model_by_restitution.iter())
                    .map(ModelPointRecord::from)
                    .collect::<Vec<_>>(),
            )?,
        },
    ])
}

/// The report's part on a user's own deck, checked by `deck`: its table of pairs, the traps
/// its lines meet, the warnings and what the impacts leave out, with the whole check beside it
/// as `deck-<number>.json` and `.csv` (`number` from 1, in the order the decks were given).
pub fn deck_part(
    number: usize,
    check: &DeckReport,
) -> Result<(ReportPart, Vec<DataFile>), ReportError> {
    let command = check.reproduce().to_string();
    let stem = format!("deck-{number}");
    let sections = check.sections();
    let mut tables = Vec::new();
    if let Some(pairs) = sections.first() {
        let mut table = table_from(format!("{stem}-pairs"), pairs, &command);
        table.title = "Each pair at each impact speed".into();
        tables.push(table);
    }
    let mut traps = Section::new(
        Some("Traps of these lines".into()),
        &["pair", "model", "trap"],
    );
    let mut seen = std::collections::BTreeSet::new();
    for i in &check.impacts {
        if seen.insert(&i.pair) {
            for t in &i.traps {
                traps
                    .rows
                    .push(vec![i.pair.clone(), i.model.clone(), t.clone()]);
            }
        }
    }
    let mut warnings = Section::new(
        Some("Warnings and failures".into()),
        &["pair", "v0 (m/s)", "warning"],
    );
    for i in &check.impacts {
        for w in i
            .failure
            .iter()
            .map(|f| format!("failed: {f}"))
            .chain(i.warnings.iter().cloned())
        {
            warnings
                .rows
                .push(vec![i.pair.clone(), i.impact_velocity.to_string(), w]);
        }
    }
    let mut left_out = Section::new(
        Some("Left out of the impacts (the deck's own run needs them; one impact does not)".into()),
        &["what", "where"],
    );
    for l in &check.left_out {
        let (what, at) = l.rsplit_once(": ").unwrap_or((l.as_str(), ""));
        left_out.rows.push(vec![what.to_string(), at.to_string()]);
    }
    for (name, section) in [
        ("traps", traps),
        ("warnings", warnings),
        ("left-out", left_out),
    ] {
        if !section.rows.is_empty() {
            tables.push(table_from(format!("{stem}-{name}"), &section, &command));
        }
    }
    let particles: Vec<String> = check
        .bodies
        .iter()
        .map(|b| {
            format!(
                "type {} (R = {} m, ρ = {} kg/m³)",
                b.type_id, b.radius, b.density
            )
        })
        .chain(check.walls.iter().map(|w| format!("wall {}", w.name)))
        .collect();
    let part = ReportPart {
        id: stem.clone(),
        title: format!("Your setup: {}", check.deck),
        intro: format!(
            "{} run by {} ({}) with the deck's own contact lines at its time step {} s ({}), one normal impact per pair of {} at {} m/s ({}). Each pair's COR is set against the COR entered and against the code's own law, exact and stepped as the code steps, so that a difference splits into model, integration and remainder. The whole check: {stem}.json and {stem}.csv.",
            check.deck,
            check.code,
            check.code_version.as_deref().unwrap_or("not run"),
            crate::output::sci(check.timestep),
            check.timestep_from,
            particles.join(", "),
            check
                .velocities
                .iter()
                .map(|v| v.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            check.velocities_from,
        ),
        figures: cor_against_speed_figure(&stem, check, &command)?
            .into_iter()
            .collect(),
        tables,
    };
    Ok((part, data_files(&stem, check)?))
}

/// `summary` as its command exports it, `<stem>.json` and `<stem>.csv`.
fn data_files<S: Summary>(stem: &str, summary: &S) -> Result<Vec<DataFile>, OutputError> {
    [Format::Json, Format::Csv]
        .into_iter()
        .map(|format| {
            Ok(DataFile {
                name: format!("{stem}.{}", format.name()),
                text: export(summary, format)?,
            })
        })
        .collect()
}

/// The COR each pair of a deck realises against the impact speed, beside its law's exact COR
/// (and Müller & Pöschel's closed form where the law is viscoelastic): a figure where the check
/// ran more than one speed.
fn cor_against_speed_figure(
    stem: &str,
    check: &DeckReport,
    command: &str,
) -> Result<Option<ReportFigure>, ReportError> {
    let curves = &check.cor_against_speed;
    if curves.is_empty() || check.velocities.len() < 2 {
        return Ok(None);
    }
    let mut series = Vec::new();
    for curve in curves {
        let points = |cor: &[f64]| -> Vec<(f64, f64)> {
            curve
                .speeds
                .iter()
                .zip(cor)
                .filter(|(_, e)| e.is_finite())
                .map(|(&v, &e)| (v, e))
                .collect()
        };
        series.push(Series::new(
            format!("{}: realised in {}", curve.pair, check.code),
            points(&curve.cor_realised),
            Style::Dots,
        ));
        series.push(Series::new(
            format!("{}: its law, exact", curve.pair),
            points(&curve.cor_law),
            Style::Line,
        ));
        if let Some(closed) = &curve.cor_closed_form {
            series.push(Series::new(
                format!("{}: Müller & Pöschel's closed form", curve.pair),
                points(closed),
                Style::Thin,
            ));
        }
    }
    let dependent: Vec<String> = curves.iter().filter_map(|c| c.trap()).collect();
    let caption = if dependent.is_empty() {
        "The COR each pair realises in the code (dots) against the impact speed, beside its law's exact COR (line): the law's COR does not depend on the speed here.".to_string()
    } else {
        format!(
            "The COR each pair realises in the code (dots) against the impact speed, beside its law's exact COR (line) and, for viscoelastic damping, Müller & Pöschel's closed form (thin). {}",
            dependent.join(" ")
        )
    };
    figure(
        &format!("{stem}-cor-against-speed"),
        Chart {
            title: format!("COR against impact speed, {}", check.deck),
            x_label: "impact speed v0 (m/s)".into(),
            y_label: "coefficient of restitution e (–)".into(),
            series,
        },
        &caption,
        command,
        ("v0_m_per_s", "cor"),
    )
    .map(Some)
}

/// Add the parts of the users' own decks to `report`, with their data, reproduce commands and
/// failed runs.
pub(crate) fn add_decks(report: &mut Report, checks: &[DeckReport]) -> Result<(), ReportError> {
    for (k, check) in checks.iter().enumerate() {
        let (part, data) = deck_part(k + 1, check)?;
        report.parts.push(part);
        report.data.extend(data);
        report
            .appendix
            .push(format!("reproduce {}: {}", check.deck, check.reproduce()));
        report.failures.extend(
            super::deck::failures(check)
                .into_iter()
                .map(|f| format!("{}: {f}", check.deck)),
        );
    }
    Ok(())
}
