//! Generic report figures as SVG (plotters): line and dot series on labelled axes with the
//! legend in its own panel beside the data, and a categorical map.

use plotters::prelude::*;

use super::OutputError;

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Style {
    /// A solid line.
    Line,
    /// A thin line.
    Thin,
    /// Dots.
    Dots,
}

/// One series: `(x, y)` points, drawn in `style` and named in the legend.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Series {
    /// Legend entry.
    pub name: String,
    /// Points; non-finite ones are left out.
    pub points: Vec<(f64, f64)>,
    /// How it is drawn.
    pub style: Style,
}

impl Series {
    /// A series.
    pub(crate) fn new(name: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Series {
        Series {
            name: name.into(),
            points,
            style,
        }
    }
}

/// A chart: a title, axis labels with units, and its series.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Chart {
    /// Title above the data.
    pub title: String,
    /// x axis label, with its unit.
    pub x_label: String,
    /// y axis label, with its unit.
    pub y_label: String,
    /// The series.
    pub series: Vec<Series>,
}

const COLOURS: [RGBColor; 8] = [
    RGBColor(0, 90, 181),
    RGBColor(220, 50, 32),
    RGBColor(0, 150, 80),
    RGBColor(230, 140, 0),
    RGBColor(120, 60, 170),
    RGBColor(0, 160, 170),
    RGBColor(90, 90, 90),
    RGBColor(200, 70, 150),
];

fn colour(i: usize) -> RGBColor {
    COLOURS[i % COLOURS.len()]
}

/// What plotters gives back when drawing fails.
pub(crate) type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// An SVG of `size` pixels: a white page on which `draw` draws; a failure to draw is the
/// `figure`'s [`OutputError::Plot`].
pub(crate) fn svg(
    figure: &'static str,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, plotters::coord::Shift>) -> DrawResult,
) -> Result<String, OutputError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        let drawn: DrawResult = root.fill(&WHITE).map_err(Into::into);
        drawn
            .and_then(|()| draw(&root))
            .and_then(|()| Ok(root.present()?))
            .map_err(|e| OutputError::Plot {
                figure,
                reason: e.to_string(),
            })?;
    }
    Ok(svg)
}

/// A tick label: plain digits for ordinary magnitudes, scientific otherwise.
fn tick(v: f64) -> String {
    let a = v.abs();
    if a < 1e-12 {
        "0".into()
    } else if (1e-3..1e5).contains(&a) {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.2e}")
    }
}

/// The smallest range holding every finite value, padded by 5 %.
fn range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return None;
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        0.5 * lo.abs().max(1e-300)
    };
    Some((lo - pad, hi + pad))
}

/// Render `chart` as an SVG string, `width × height` pixels, the legend in a panel on the
/// right.
pub(crate) fn chart_svg(chart: &Chart, width: u32, height: u32) -> Result<String, OutputError> {
    let points = || chart.series.iter().flat_map(|s| s.points.iter());
    let (Some((x0, x1)), Some((y0, y1))) =
        (range(points().map(|p| p.0)), range(points().map(|p| p.1)))
    else {
        return Err(OutputError::Plot {
            figure: "chart",
            reason: format!("`{}` has no finite point", chart.title),
        });
    };
    svg("chart", (width, height), |root| {
        let legend_width = 270.min(width / 3);
        let (plot, legend) = root.split_horizontally(width - legend_width);
        let mut c = ChartBuilder::on(&plot)
            .caption(&chart.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(78)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        c.configure_mesh()
            .x_desc(&chart.x_label)
            .y_desc(&chart.y_label)
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .x_labels(8)
            .y_labels(8)
            .y_label_formatter(&|v| tick(*v))
            .x_label_formatter(&|v| tick(*v))
            .draw()?;
        for (i, s) in chart.series.iter().enumerate() {
            let colour = colour(i);
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            match s.style {
                Style::Line | Style::Thin => {
                    let w = if s.style == Style::Line { 2 } else { 1 };
                    c.draw_series(LineSeries::new(pts, colour.stroke_width(w)))?;
                }
                Style::Dots => {
                    c.draw_series(pts.into_iter().map(|p| Circle::new(p, 4, colour.filled())))?;
                }
            }
        }
        for (i, s) in chart.series.iter().enumerate() {
            let colour = colour(i);
            let y = 50 + 24 * i32::try_from(i).unwrap_or(i32::MAX / 48);
            match s.style {
                Style::Dots => legend.draw(&Circle::new((22, y), 4, colour.filled()))?,
                Style::Line | Style::Thin => legend.draw(&PathElement::new(
                    vec![(10, y), (34, y)],
                    colour.stroke_width(if s.style == Style::Line { 2 } else { 1 }),
                ))?,
            }
            legend.draw(&Text::new(
                s.name.clone(),
                (42, y - 7),
                ("sans-serif", 14).into_font(),
            ))?;
        }
        Ok(())
    })
}

/// A categorical map: one row per `rows` entry, one cell per column, each cell coloured by
/// its class (index into `classes`, whose names and colours the legend shows).
pub(crate) fn map_svg(
    title: &str,
    x_label: &str,
    rows: &[(String, Vec<usize>)],
    classes: &[(&str, RGBColor)],
    width: u32,
    height: u32,
) -> Result<String, OutputError> {
    let columns = rows.iter().map(|r| r.1.len()).max().unwrap_or(0);
    if rows.is_empty() || columns == 0 {
        return Err(OutputError::Plot {
            figure: "map",
            reason: "no cells".into(),
        });
    }
    svg("map", (width, height), |root| {
        let legend_width = 270.min(width / 3);
        let (plot, legend) = root.split_horizontally(width - legend_width);
        let names: Vec<String> = rows.iter().map(|r| r.0.clone()).collect();
        let mut c = ChartBuilder::on(&plot)
            .caption(title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(90)
            .build_cartesian_2d(0f64..columns as f64, 0f64..rows.len() as f64)?;
        c.configure_mesh()
            .disable_mesh()
            .x_desc(x_label)
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_labels(rows.len() * 2 + 1)
            .y_label_formatter(&|v| {
                let k = *v - 0.5;
                let at = names
                    .iter()
                    .enumerate()
                    .find(|(j, _)| (k - *j as f64).abs() < 1e-9);
                if let Some((_, name)) = at {
                    name.clone()
                } else {
                    String::new()
                }
            })
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .draw()?;
        for (r, (_, cells)) in rows.iter().enumerate() {
            c.draw_series(cells.iter().enumerate().map(|(k, &class)| {
                Rectangle::new(
                    [(k as f64, r as f64 + 0.1), (k as f64 + 1.0, r as f64 + 0.9)],
                    classes[class].1.filled(),
                )
            }))?;
        }
        for (i, (name, colour)) in classes.iter().enumerate() {
            let y = 50 + 24 * i32::try_from(i).unwrap_or(i32::MAX / 48);
            legend.draw(&Rectangle::new([(10, y - 7), (30, y + 7)], colour.filled()))?;
            legend.draw(&Text::new(
                name.to_string(),
                (40, y - 7),
                ("sans-serif", 14).into_font(),
            ))?;
        }
        Ok(())
    })
}
