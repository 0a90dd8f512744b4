//! The work–precision diagram as SVG: error (x, log) against run time (y, log), one line per
//! method or code, in the manner of the SciML benchmarks.

/// Errors are drawn no lower than this.
const SMALLEST_ERROR: f64 = 1e-17;

use plotters::prelude::*;

use super::OutputError;
use super::chart::svg;

/// Render the work–precision diagram of `case`: one series per source, each point
/// `(largest relative error, run time in s)`; errors are drawn no lower than 1e-17 (an exact
/// zero has no place on a log axis).
pub(crate) fn work_precision_svg(
    case: &str,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<String, OutputError> {
    let series: Vec<(&str, Vec<(f64, f64)>)> = series
        .iter()
        .map(|(name, points)| {
            (
                name.as_str(),
                points
                    .iter()
                    .map(|&(error, time)| (error.max(SMALLEST_ERROR), time))
                    .collect(),
            )
        })
        .collect();
    let all = series.iter().flat_map(|(_, p)| p.iter());
    let (mut x_lo, mut x_hi, mut y_lo, mut y_hi) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in all {
        x_lo = x_lo.min(x);
        x_hi = x_hi.max(x);
        y_lo = y_lo.min(y);
        y_hi = y_hi.max(y);
    }
    if series.is_empty() || !(x_lo > 0.0 && y_lo > 0.0) {
        return Err(OutputError::Plot {
            figure: "work-precision",
            reason: "no points to plot".into(),
        });
    }
    // Whole decades around the data, so that the ticks fall on powers of ten.
    let decade_below = |v: f64| 10f64.powf(v.log10().floor());
    let decade_above =
        |v: f64| 10f64.powf(v.log10().ceil() + if v.log10().fract() == 0.0 { 1.0 } else { 0.0 });
    let x_range = decade_below(x_lo)..decade_above(x_hi);
    let y_range = decade_below(y_lo)..decade_above(y_hi);

    svg("work-precision", (960, 640), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(format!("Work–precision, case {case}"), ("sans-serif", 22))
            .margin(20)
            .x_label_area_size(55)
            .y_label_area_size(80)
            .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())?;
        chart
            .configure_mesh()
            .x_desc("largest relative error of COR, peak deformation, contact time")
            .y_desc("run time of one impact (s)")
            .x_label_formatter(&|x| format!("{x:.0e}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .draw()?;
        for (i, (name, points)) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?
                .label(*name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2))
                });
            chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
        }
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
