//! Tests 4–8 as charts, one per test, the figure the paper plots for it: Thornton's
//! normalised rebound angle ψ' against the normalised incident angle ψ (tests 4, 5, 6 and 8),
//! and the rebound spin of both balls against the spin they met with (test 7). Each solver is
//! a series per material, and the closed form, where it holds, a series of dots.

use serde::Serialize;

use super::oblique::{OBLIQUE_TESTS, ObliqueImpact};
use super::{BenchmarkReport, BenchmarkRow, Quantity};
use crate::analysis::groups;
use crate::model::exact;
use crate::model::tangential::{TangentialBodies, normalised_angle};
use crate::output::chart::{Chart, Series, Style, chart_svg};
use crate::output::report_page::ReportFigure;
use crate::output::{OutputError, csv_string};

/// One point of a test's chart, and one CSV row.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct ObliquePoint {
    /// The test.
    pub test: u8,
    /// The material.
    pub material: &'static str,
    /// The solver, or `closed-form`.
    pub series: String,
    /// The figure.
    pub quantity: Quantity,
    /// The abscissa: ψ (tests 4, 5, 6, 8) or the incoming spin, rad/s (test 7).
    pub x: f64,
    /// The figure's value.
    pub y: f64,
}

/// The abscissa of `impact` at the swept value `swept`: ψ = 2 s/(μ(1+e)v_n) of the slip at
/// first contact, or (test 7) the incoming spin itself.
fn abscissa(impact: &ObliqueImpact, swept: f64) -> Option<f64> {
    if impact.test == 7 {
        return Some(swept);
    }
    let base = impact.case().ok()?;
    super::oblique::INCIDENT_ANGLES.iter().find_map(|&angle| {
        let (case, value) = impact.at(&base, angle);
        if value.to_bits() != swept.to_bits() {
            return None;
        }
        let oblique = case.oblique.as_ref()?;
        let slip = TangentialBodies::of(&case.scene, oblique)?.slip();
        normalised_angle(
            slip,
            case.impact_velocity,
            oblique.friction_coefficient,
            exact::restitution(case.loss_coefficient),
        )
    })
}

/// The largest ψ drawn: the paper's figures (and the codes' scripts that redraw them) show
/// ψ up to about 14, where partial slip and the onset of sliding are; beyond it every point is
/// gross sliding, ψ' = ψ − 7. The CSV keeps every point.
const PSI_DRAWN_MAX: f64 = 20.0;

/// The figures drawn for a test.
fn drawn(test: u8) -> &'static [Quantity] {
    if test == 7 {
        &[Quantity::ReboundSpin, Quantity::OtherReboundSpin]
    } else {
        &[Quantity::NormalisedReboundAngle]
    }
}

/// Every point of `report`'s rows of `test`: the solvers' values and the closed form's.
fn points(report: &BenchmarkReport, test: u8) -> Vec<ObliquePoint> {
    let mut points = Vec::new();
    let of_test: Vec<&BenchmarkRow> = report.rows.iter().filter(|r| r.test == test).collect();
    for impact in OBLIQUE_TESTS.iter().filter(|i| i.test == test) {
        for r in of_test.iter().filter(|r| r.case == impact.case) {
            let Some(x) = r.swept_value.and_then(|v| abscissa(impact, v)) else {
                continue;
            };
            let point = |series: String, y: f64| ObliquePoint {
                test,
                material: r.material,
                series,
                quantity: r.quantity,
                x,
                y,
            };
            points.push(point(r.source.to_string(), r.value));
            // One closed-form point per sweep point: with the first solver's row.
            if let Some(c) = r.closed_form
                && r.source == super::Source::Method(super::oblique::OBLIQUE_METHODS[0])
            {
                points.push(point("closed-form".into(), c));
            }
        }
    }
    points
}

/// One figure per test 4–8 from `report`'s rows; each `id` is the file stem of its `.svg` and
/// `.csv`, whose CSV holds every figure of the test, drawn or not.
pub(crate) fn oblique_figures(report: &BenchmarkReport) -> Result<Vec<ReportFigure>, OutputError> {
    let mut tests: Vec<u8> = OBLIQUE_TESTS.iter().map(|t| t.test).collect();
    tests.dedup();
    let mut figures = Vec::new();
    for test in tests {
        let points = points(report, test);
        if points.is_empty() {
            continue;
        }
        let mut series: Vec<Series> = Vec::new();
        for &quantity in drawn(test) {
            let of_quantity = points.iter().filter(|p| p.quantity == quantity);
            for ((material, name), group) in groups(of_quantity, |p| (p.material, &p.series)) {
                let xy: Vec<(f64, f64)> = group
                    .iter()
                    .filter(|p| test == 7 || p.x <= PSI_DRAWN_MAX)
                    .map(|p| (p.x, p.y))
                    .collect();
                let style = if name == "closed-form" {
                    Style::Dots
                } else {
                    Style::Line
                };
                let label = if test == 7 {
                    format!("{material}, {name}, {}", quantity_short(quantity))
                } else {
                    format!("{material}, {name}")
                };
                series.push(Series::new(label, xy, style));
            }
        }
        let (x_label, y_label, what) = if test == 7 {
            (
                "incoming spin ω (rad/s)",
                "rebound spin (rad/s)",
                "the rebound spin of both balls against the spin each met with (opposite senses: nothing slips, and each keeps its spin)",
            )
        } else {
            (
                "normalised incident angle ψ",
                "normalised rebound angle ψ'",
                "Thornton's normalised rebound angle ψ' of the contact point against the normalised incident angle ψ, drawn up to ψ = 20 (beyond it every point slides throughout, ψ' = ψ − 7)",
            )
        };
        let chart = Chart {
            title: format!("Chung & Ooi test {test}: {y_label} against {x_label}"),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series,
        };
        figures.push(ReportFigure {
            id: format!("oblique-chart-test-{test}"),
            title: chart.title.clone(),
            caption: format!(
                "Chung & Ooi's test {test}: {what}, by rk4-event and dopri5 (the tangential solver) per material, and the closed form where it is exact (dots). The CSV holds every figure of the test's rows."
            ),
            svg: chart_svg(&chart, 960, 520)?,
            csv: csv_string(&points)?,
            command: "millimpact benchmark chung-ooi --chart DIR".into(),
        });
    }
    Ok(figures)
}

/// A short name of a drawn figure, for test 7's legend.
fn quantity_short(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::OtherReboundSpin => "ball 2",
        _ => "ball 1",
    }
}
