//! The paper's Figure 3 as SVG: the COR against the loss coefficient, by a method and exactly.

use plotters::prelude::*;

use super::OutputError;
use super::chart::svg;

/// Render a sweep: the method's COR at each η (points), the closed form `sqrt((1-η)/(1+η))`
/// (line) and the small-η approximation `1 - η` (thin line) it bends away from.
///
/// `points` are `(η, COR)` by `method`; `exact` is the closed form `e(η)`.
pub(crate) fn restitution_svg(
    case: &str,
    method: &str,
    points: &[(f64, f64)],
    exact: &dyn Fn(f64) -> f64,
) -> Result<String, OutputError> {
    if points.is_empty() {
        return Err(OutputError::Plot {
            figure: "restitution",
            reason: "no points to plot".into(),
        });
    }
    svg("restitution", (800, 600), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("COR against loss coefficient, case {case}"),
                ("sans-serif", 22),
            )
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(60)
            .build_cartesian_2d(0f64..1f64, 0f64..1.05f64)?;
        chart
            .configure_mesh()
            .x_desc("loss coefficient η")
            .y_desc("coefficient of restitution e")
            .draw()?;
        let exact_curve = (0..=400).map(|i| {
            let eta = 0.9999 * i as f64 / 400.0;
            (eta, exact(eta))
        });
        let blue = BLUE.stroke_width(2);
        chart
            .draw_series(LineSeries::new(exact_curve, blue))?
            .label("exact: sqrt((1-η)/(1+η))")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], blue));
        let grey = BLACK.mix(0.4).stroke_width(1);
        chart
            .draw_series(LineSeries::new([(0.0, 1.0), (1.0, 0.0)], grey))?
            .label("1 - η (small η)")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], grey));
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&(eta, cor)| Circle::new((eta, cor), 4, RED.filled())),
            )?
            .label(method)
            .legend(|(x, y)| Circle::new((x + 12, y), 4, RED.filled()));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .draw()?;
        Ok(())
    })
}
