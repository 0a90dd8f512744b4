//! `millimpact compare`: every source side by side for each case (the paper's law exact and by
//! the paper's rk4, each DEM code, each code's own law at zero step error, the elastic contact),
//! with the differences from the paper's law split into model, integration and remainder.

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::Result;
use serde::Serialize;

use crate::app::CheckFailed;
use crate::case::Case;
use crate::cli::CompareArgs;
use crate::codes;
use crate::exact;
use crate::references::{self, Attribution, ReferenceRecord};
use crate::report::{self, Format};
use crate::solve::Method;
use crate::solve::paper::{self, Settings};

/// The canonical cases compared by default.
pub const CANONICAL_CASES: [&str; 3] = [
    "cases/ball_plate.toml",
    "cases/ball_ball.toml",
    "cases/rod_end.toml",
];

/// One source's figures for one case.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SourceRow {
    /// What produced the figures.
    pub source: String,
    /// COR.
    pub cor: f64,
    /// Peak deformation, m.
    pub peak_deformation: f64,
    /// Peak force, N.
    pub peak_force: f64,
    /// Contact time, s.
    pub contact_time: f64,
    /// Run time, s (`None` for closed forms).
    pub run_time: Option<f64>,
    /// Relative difference of the COR from the paper's law.
    pub cor_vs_paper: f64,
    /// Relative difference of the peak deformation from the paper's law.
    pub peak_deformation_vs_paper: f64,
    /// Relative difference of the contact time from the paper's law.
    pub contact_time_vs_paper: f64,
    /// Relative difference of the peak deformation from the elastic contact.
    pub peak_deformation_vs_elastic: f64,
    /// Relative difference of the contact time from the elastic contact.
    pub contact_time_vs_elastic: f64,
}

/// A code's attribution for one case.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CodeAttribution {
    /// Code name.
    pub code: String,
    /// Code version.
    pub code_version: String,
    /// Time step, s.
    pub timestep: f64,
    /// The split.
    #[serde(flatten)]
    pub attribution: Attribution,
}

/// Everything compared for one case.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CaseComparison {
    /// Case name.
    pub case: String,
    /// The case file.
    pub path: String,
    /// η.
    pub loss_coefficient: f64,
    /// The rows, one per source.
    pub rows: Vec<SourceRow>,
    /// Per code, the split of its difference from the paper's law.
    pub attribution: Vec<CodeAttribution>,
    /// Codes with no result, and why.
    pub missing: Vec<String>,
}

struct Baseline {
    paper: (f64, f64, f64),
    elastic: (f64, f64),
}

impl Baseline {
    #[allow(clippy::too_many_arguments)]
    fn row(
        &self,
        source: String,
        cor: f64,
        peak: f64,
        force: f64,
        time: f64,
        run_time: Option<f64>,
    ) -> SourceRow {
        let rel = |a: f64, b: f64| (a - b) / b;
        SourceRow {
            source,
            cor,
            peak_deformation: peak,
            peak_force: force,
            contact_time: time,
            run_time,
            cor_vs_paper: rel(cor, self.paper.0),
            peak_deformation_vs_paper: rel(peak, self.paper.1),
            contact_time_vs_paper: rel(time, self.paper.2),
            peak_deformation_vs_elastic: rel(peak, self.elastic.0),
            contact_time_vs_elastic: rel(time, self.elastic.1),
        }
    }
}

/// The elastic contact of the case's spring: Hertz for the balls, the linear spring for the
/// rod; `(peak deformation, contact time)` in m and s.
pub fn elastic_figures(case: &Case) -> (f64, f64) {
    let m = case.scene.reduced_mass();
    let v0 = case.impact_velocity;
    match (
        case.scene.effective_modulus(),
        case.scene.effective_radius(),
    ) {
        (Some(e), Some(r)) => {
            let h = exact::hertz_elastic(m, e, r, v0);
            (h.peak_deformation, h.contact_time)
        }
        _ => {
            let k = case.scene.hertz_stiffness();
            (v0 * (m / k).sqrt(), std::f64::consts::PI * (m / k).sqrt())
        }
    }
}

/// Compare one case; `live` runs the codes, otherwise the stored references are read.
pub fn compare_case(
    case: &Case,
    live: bool,
    reference: &Path,
    timeout: Duration,
) -> Result<CaseComparison> {
    let law = case.law();
    let v0 = case.impact_velocity;
    let exact = exact::paper_impact(&law, v0);
    let elastic = elastic_figures(case);
    let base = Baseline {
        paper: (exact.cor, exact.peak_deformation, exact.contact_time),
        elastic,
    };
    let mut rows = vec![base.row(
        "paper law, exact".into(),
        exact.cor,
        exact.peak_deformation,
        exact.peak_force,
        exact.contact_time,
        None,
    )];
    let settings = Settings {
        method: Method::Rk4,
        contact: case.contact,
        ..Settings::default()
    };
    let rk4 = paper::solve(&law, v0, &settings)?;
    let f = &rk4.figures;
    rows.push(base.row(
        "paper law, rk4 (paper's method)".into(),
        f.cor,
        f.peak_deformation,
        f.peak_force,
        f.contact_time,
        Some(rk4.wall_time),
    ));
    let mut attribution = Vec::new();
    let mut missing = Vec::new();
    for driver in codes::all_drivers() {
        let record: Option<ReferenceRecord> = if live {
            match references::run_reference(driver.as_ref(), case, None, None, false, timeout) {
                Ok(r) => Some(r),
                Err(e) => {
                    missing.push(format!("{}: {e:#}", driver.name()));
                    None
                }
            }
        } else {
            let found = references::find_stored(
                reference,
                driver.name(),
                &case.name,
                case.loss_coefficient,
            )?;
            if found.is_none() {
                missing.push(format!(
                    "{}: no stored run at η = {} (make one: millimpact reference --code {} {} --save)",
                    driver.name(),
                    case.loss_coefficient,
                    driver.name(),
                    case.path.display()
                ));
            }
            found
        };
        let Some(r) = record else { continue };
        rows.push(base.row(
            format!("{} {}", r.code, short_version(&r.code_version)),
            r.cor,
            r.peak_deformation,
            r.peak_force,
            r.contact_time,
            Some(r.wall_time),
        ));
        rows.push(base.row(
            format!("{} law, exact", r.code),
            r.law_exact.cor,
            r.law_exact.peak_deformation,
            r.law_exact.peak_force,
            r.law_exact.contact_time,
            None,
        ));
        attribution.push(CodeAttribution {
            code: r.code.clone(),
            code_version: r.code_version.clone(),
            timestep: r.timestep,
            attribution: r.attribution(),
        });
    }
    rows.push(base.row(
        if case.scene.effective_modulus().is_some() {
            "Hertz, elastic".into()
        } else {
            "linear spring, elastic".into()
        },
        1.0,
        elastic.0,
        f64::NAN,
        elastic.1,
        None,
    ));
    Ok(CaseComparison {
        case: case.name.clone(),
        path: case.path.display().to_string(),
        loss_coefficient: case.loss_coefficient,
        rows,
        attribution,
        missing,
    })
}

fn short_version(version: &str) -> String {
    version
        .split(',')
        .next()
        .unwrap_or(version)
        .trim()
        .to_string()
}

/// Run `millimpact compare`.
pub fn compare_command(args: &CompareArgs) -> Result<String> {
    let paths: Vec<PathBuf> = if args.cases.is_empty() {
        CANONICAL_CASES.iter().map(PathBuf::from).collect()
    } else {
        args.cases.clone()
    };
    let cases = paths
        .iter()
        .map(|p| Case::load(p))
        .collect::<Result<Vec<_>, _>>()?;
    let timeout = Duration::from_secs_f64(args.timeout.max(1.0));
    let mut comparisons = Vec::new();
    for case in &cases {
        comparisons.push(compare_case(case, args.live, &args.reference, timeout)?);
    }
    let text = render(&comparisons, args.format, args.live)?;
    let failures: Vec<&String> = if args.live {
        comparisons.iter().flat_map(|c| &c.missing).collect()
    } else {
        Vec::new()
    };
    if !failures.is_empty() {
        print!("{text}");
        let list: Vec<String> = failures.iter().map(|s| s.to_string()).collect();
        return Err(CheckFailed(format!("compare --live: {}", list.join("; "))).into());
    }
    Ok(text)
}

const HEADERS: [&str; 10] = [
    "source",
    "COR",
    "peak (m)",
    "peak force (N)",
    "contact time (s)",
    "run time",
    "ΔCOR vs paper",
    "Δpeak vs paper",
    "Δtime vs paper",
    "Δpeak / Δtime vs elastic",
];

fn cells(row: &SourceRow) -> Vec<String> {
    let sci = report::sci;
    vec![
        row.source.clone(),
        format!("{:.6}", row.cor),
        sci(row.peak_deformation),
        sci(row.peak_force),
        sci(row.contact_time),
        row.run_time.map(report::seconds).unwrap_or_default(),
        format!("{:+.2e}", row.cor_vs_paper),
        format!("{:+.2e}", row.peak_deformation_vs_paper),
        format!("{:+.2e}", row.contact_time_vs_paper),
        format!(
            "{:+.2e} / {:+.2e}",
            row.peak_deformation_vs_elastic, row.contact_time_vs_elastic
        ),
    ]
}

fn attribution_cells(a: &CodeAttribution) -> Vec<String> {
    let s = |x: &references::Split| {
        format!(
            "{:+.2e} / {:+.2e} / {:+.2e}",
            x.cor, x.peak_deformation, x.contact_time
        )
    };
    vec![
        a.code.clone(),
        report::sci(a.timestep),
        s(&a.attribution.total),
        s(&a.attribution.model),
        s(&a.attribution.integration),
        s(&a.attribution.remainder),
    ]
}

const ATTRIBUTION_HEADERS: [&str; 6] = [
    "code",
    "Δt (s)",
    "total (COR / peak / time)",
    "model",
    "integration",
    "remainder",
];

fn render(comparisons: &[CaseComparison], format: Format, live: bool) -> Result<String> {
    match format {
        Format::Json => Ok(serde_json::to_string_pretty(&serde_json::json!({
            "live": live,
            "cases": comparisons,
        }))? + "\n"),
        Format::Csv => {
            #[derive(Serialize)]
            struct Flat<'a> {
                case: &'a str,
                loss_coefficient: f64,
                #[serde(flatten)]
                row: &'a SourceRow,
            }
            let mut writer = csv::Writer::from_writer(Vec::new());
            for c in comparisons {
                for row in &c.rows {
                    writer.serialize(Flat {
                        case: &c.case,
                        loss_coefficient: c.loss_coefficient,
                        row,
                    })?;
                }
            }
            Ok(String::from_utf8(writer.into_inner()?)?)
        }
        Format::Table | Format::Markdown => {
            let mut text = String::new();
            for c in comparisons {
                let title = format!(
                    "{} (η = {}, e = {:.6}){}",
                    c.case,
                    c.loss_coefficient,
                    exact::restitution(c.loss_coefficient),
                    if live {
                        ", codes run now"
                    } else {
                        ", stored references"
                    }
                );
                let rows: Vec<Vec<String>> = c.rows.iter().map(cells).collect();
                let attr: Vec<Vec<String>> = c.attribution.iter().map(attribution_cells).collect();
                if format == Format::Markdown {
                    text += &format!("### {title}\n\n");
                    text += &report::markdown_table(&HEADERS, &rows);
                    text += "\nDifference from the paper's law, split (relative to the paper's law):\n\n";
                    text += &report::markdown_table(&ATTRIBUTION_HEADERS, &attr);
                    text.push('\n');
                } else {
                    let mut t = report::new_table(&HEADERS);
                    for r in rows {
                        t.add_row(r);
                    }
                    let mut a = report::new_table(&ATTRIBUTION_HEADERS);
                    for r in attr {
                        a.add_row(r);
                    }
                    text +=
                        &format!("{title}\n{t}\ndifference from the paper's law, split:\n{a}\n");
                }
                for m in &c.missing {
                    text += &format!("missing: {m}\n");
                }
                text.push('\n');
            }
            let cases: Vec<String> = comparisons.iter().map(|c| c.path.clone()).collect();
            text += &format!(
                "reproduce: millimpact compare {}{} --format {}\n",
                cases.join(" "),
                if live { " --live" } else { "" },
                match format {
                    Format::Markdown => "markdown",
                    _ => "table",
                }
            );
            Ok(text)
        }
    }
}
