//! The report's pages: `index.html` (figures inline, no network) and `index.md`, rendered
//! from one context through the template engine.

use minijinja::{AutoEscape, Environment};
use serde::Serialize;

use super::OutputError;

/// One figure of a report: the SVG, the data behind it as CSV, and how to reproduce it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReportFigure {
    /// File stem (`<id>.svg`, `<id>.csv`).
    pub id: String,
    /// Title.
    pub title: String,
    /// What it shows.
    pub caption: String,
    /// The figure.
    pub svg: String,
    /// Its data.
    pub csv: String,
    /// The command that reproduces it.
    pub command: String,
}
const HTML: &str = include_str!("templates/report.html");
const MARKDOWN: &str = include_str!("templates/report.md");

/// Render `context` as `(index.html, index.md)`.
pub fn render_pages<C: Serialize>(context: &C) -> Result<(String, String), OutputError> {
    let mut env = Environment::new();
    env.set_auto_escape_callback(|name| {
        if name.ends_with(".html") {
            AutoEscape::Html
        } else {
            AutoEscape::None
        }
    });
    let fail = |e: minijinja::Error| OutputError::Plot {
        figure: "report page",
        reason: e.to_string(),
    };
    env.add_template("report.html", HTML).map_err(fail)?;
    env.add_template("report.md", MARKDOWN).map_err(fail)?;
    let html = env
        .get_template("report.html")
        .and_then(|t| t.render(context))
        .map_err(fail)?;
    let md = env
        .get_template("report.md")
        .and_then(|t| t.render(context))
        .map_err(fail)?;
    Ok((html, md))
}
