//! A user's mill under both laws as a part of the report (`report --mill DECK`): the power the
//! drum draws against time, the collision spectra of both laws overlaid, the charge's profile,
//! and the tables of `millimpact mill`, each figure with its data and the command that
//! reproduces it.

use super::{
    DataFile, Report, ReportError, ReportFigure, ReportPart, data_files, figure, table_from,
};
use crate::analysis::mill::{MillReport, MillRun, SpectrumRow};
use crate::codes::liggghts::mill::MillLaw;
use crate::output::Summary;
use crate::output::chart::{Chart, Series, Style, chart_svg};

/// The legend name of a run: its law, its build and, with several seeds, its seed.
fn run_name(mill: &MillReport, run: &MillRun) -> String {
    let seed = if mill.seeds > 1 {
        format!(", seed {}", run.seed)
    } else {
        String::new()
    };
    format!("{} ({}{seed})", run.law, run.code)
}

/// Power against rotation time, per run: from the torque on the rotating meshes (line) and from
/// the torque balance of the charge's weight (thin), each a mean over one stretch of the trace.
fn power_figure(stem: &str, mill: &MillReport) -> Result<ReportFigure, ReportError> {
    let mut series = Vec::new();
    for run in &mill.runs {
        let name = run_name(mill, run);
        let points = |pick: fn(&crate::analysis::mill::TracePoint) -> Option<f64>| {
            run.trace
                .iter()
                .filter_map(|t| pick(t).map(|p| (t.time, p)))
                .collect::<Vec<_>>()
        };
        series.push(Series::new(
            format!("{name}: torque on the meshes"),
            points(|t| t.power),
            Style::Line,
        ));
        let weight = points(|t| t.weight_power);
        if !weight.is_empty() {
            series.push(Series::new(
                format!("{name}: the weight's torque"),
                weight,
                Style::Thin,
            ));
        }
    }
    let stretch =
        mill.rotation_steps as f64 * mill.timestep / crate::analysis::mill::TRACE_POINTS as f64;
    figure(
        &format!("{stem}-power"),
        Chart {
            title: format!("Power draw against time, {}", mill.deck),
            x_label: "time from the start of the rotation (s)".into(),
            y_label: "power draw (W)".into(),
            series,
        },
        &format!(
            "The power each run's drum draws, each point a mean over {:.4} s: from the torque the charge exerts on the rotating meshes (line) and from the torque balance of the charge's weight, ω × its torque about the axis (thin), which a steady rotation makes equal in the mean. The means in the table leave out the first {:.4} s of rotation (the start-up).",
            stretch, mill.transient
        ),
        &mill.reproduce,
        ("time_s", "power_w"),
    )
}

/// The middle of a decade bin on a log₁₀ axis: open bins drawn one decade beyond their edge.
fn bin_middle(row: &SpectrumRow) -> Option<f64> {
    match (row.low, row.high) {
        (Some(low), Some(high)) => Some(0.5 * (low.log10() + high.log10())),
        (None, Some(high)) => Some(high.log10() - 0.5),
        (Some(low), None) => Some(low.log10() + 0.5),
        (None, None) => None,
    }
}

/// One spectrum (`impact_energy` or `peak_force`) of both laws overlaid: collisions per second
/// per decade bin, between particles (every pair of types summed) and against the liner.
fn spectrum_figure(
    stem: &str,
    mill: &MillReport,
    spectrum: &str,
    quantity: &str,
) -> Result<Option<ReportFigure>, ReportError> {
    let rows: Vec<&SpectrumRow> = mill
        .spectra
        .iter()
        .filter(|s| s.spectrum == spectrum)
        .collect();
    if rows.is_empty() {
        return Ok(None);
    }
    let mut middles: Vec<f64> = rows.iter().filter_map(|r| bin_middle(r)).collect();
    middles.sort_by(f64::total_cmp);
    middles.dedup();
    let mut series = Vec::new();
    for (against, liner) in [("between particles", false), ("against the liner", true)] {
        for (law, pick) in [
            (
                mill.written_law,
                (|r: &SpectrumRow| r.written.mean) as fn(&SpectrumRow) -> f64,
            ),
            (mill.switched_law, |r: &SpectrumRow| r.switched.mean),
        ] {
            let points: Vec<(f64, f64)> = middles
                .iter()
                .map(|&m| {
                    let rate: f64 = rows
                        .iter()
                        .filter(|r| r.pair.ends_with("-wall") == liner && bin_middle(r) == Some(m))
                        .map(|r| pick(r))
                        .sum();
                    (m, rate)
                })
                .collect();
            let style = if law == mill.written_law {
                Style::Line
            } else {
                Style::Dots
            };
            series.push(Series::new(
                format!("{against}, {}", law_name(mill, law)),
                points,
                style,
            ));
        }
    }
    figure(
        &format!("{stem}-{}", spectrum.replace('_', "-")),
        Chart {
            title: format!("Collisions per second by {quantity}, {}", mill.deck),
            x_label: format!("log₁₀ of the {quantity}, middle of its decade bin"),
            y_label: "collisions per second (1/s)".into(),
            series,
        },
        &format!(
            "Collisions per second in each decade bin of the {quantity}, over the last {:.4} s of rotation: the deck's own law (line) and the switched law (dots), every pair of types summed, apart from the collisions against the liner. The open bins at either end are drawn half a decade beyond their edge. Each bin per pair, with its standard error and whether the laws' difference is resolved, is in the table below.",
            mill.spectra_window
        ),
        &mill.reproduce,
        (&format!("log10_{spectrum}_bin_middle"), "collisions_per_s"),
    )
    .map(Some)
}

fn law_name(mill: &MillReport, law: MillLaw) -> String {
    let code = mill
        .runs
        .iter()
        .find(|r| r.law == law)
        .map_or(String::new(), |r| r.code.clone());
    format!("model {law} ({code})")
}

/// The charge in the drum's cross-section at the end of each law's first run, on axes of equal
/// scale, with the circle through the outermost particle centre.
fn profile_figure(stem: &str, mill: &MillReport) -> Result<Option<ReportFigure>, ReportError> {
    let firsts: Vec<&MillRun> = [mill.written_law, mill.switched_law]
        .iter()
        .filter_map(|&law| {
            mill.runs
                .iter()
                .find(|r| r.law == law && !r.profile.is_empty())
        })
        .collect();
    if firsts.is_empty() {
        return Ok(None);
    }
    let reach = firsts
        .iter()
        .flat_map(|r| r.profile.iter())
        .map(|p| p.across.hypot(p.up))
        .fold(0.0, f64::max);
    let mut series: Vec<Series> = firsts
        .iter()
        .map(|run| {
            Series::new(
                law_name(mill, run.law),
                run.profile.iter().map(|p| (p.across, p.up)).collect(),
                Style::Dots,
            )
        })
        .collect();
    series.push(Series::new(
        "the outermost centre's circle",
        (0..=180)
            .map(|k| {
                let angle = f64::from(k) * std::f64::consts::PI / 90.0;
                (reach * angle.cos(), reach * angle.sin())
            })
            .collect(),
        Style::Thin,
    ));
    let chart = Chart {
        title: format!("The charge at the end of the run, {}", mill.deck),
        x_label: "across, toward the rising side (m)".into(),
        y_label: "up, against gravity (m)".into(),
        series,
    };
    let id = format!("{stem}-charge");
    let plain = figure(
        &id,
        chart.clone(),
        "Each particle's centre in the drum's cross-section at the end of the run, under each law (the first seed): across toward the side the shell rises on, up against gravity, from the axis. The shoulder and toe angles in the table come from 200 such frames through the rotation.",
        &mill.reproduce,
        ("across_m", "up_m"),
    )?;
    // The plotting area square (the legend panel and the label areas beside it), so that the
    // drum is drawn round.
    Ok(Some(ReportFigure {
        svg: chart_svg(&chart, 790, 520)?,
        ..plain
    }))
}

/// A user's mill run under both laws as a part of the report, with its data files
/// (`mill-N.json`, `mill-N.csv`, as `millimpact mill --format json|csv` writes them).
pub fn mill_part(
    number: usize,
    mill: &MillReport,
) -> Result<(ReportPart, Vec<DataFile>), ReportError> {
    let stem = format!("mill-{number}");
    let mut figures = vec![power_figure(&stem, mill)?];
    for (spectrum, quantity) in [
        ("impact_energy", "impact energy ½ m* v_n² (J)"),
        ("peak_force", "peak normal force (N)"),
    ] {
        figures.extend(spectrum_figure(&stem, mill, spectrum, quantity)?);
    }
    figures.extend(profile_figure(&stem, mill)?);
    let names = ["figures", "spectra", "runs"];
    let tables = mill
        .sections()
        .iter()
        .zip(names)
        .map(|(section, name)| table_from(format!("{stem}-{name}"), section, &mill.reproduce))
        .collect();
    let part = ReportPart {
        id: stem.clone(),
        title: format!("Your mill: {}", mill.deck),
        intro: format!(
            "{} run whole under its own law, {}, and switched to {} at each pair's COR (walls included; {} kept), {} run(s) per law: what the law changes in the power the drum draws, the collisions that drive breakage and wear, and the charge's shape. The whole comparison: {stem}.json and {stem}.csv.",
            mill.deck,
            law_name(mill, mill.written_law),
            law_name(mill, mill.switched_law),
            mill.tangential_and_rolling,
            mill.seeds
        ),
        figures,
        tables,
    };
    Ok((part, data_files(&stem, mill)?))
}

/// Add the parts of the users' own mills to `report`, with their data and reproduce commands.
pub fn add_mills(report: &mut Report, mills: &[MillReport]) -> Result<(), ReportError> {
    for (k, mill) in mills.iter().enumerate() {
        let (part, data) = mill_part(k + 1, mill)?;
        report.parts.push(part);
        report.data.extend(data);
        report
            .appendix
            .push(format!("reproduce {}: {}", mill.deck, mill.reproduce));
    }
    Ok(())
}
