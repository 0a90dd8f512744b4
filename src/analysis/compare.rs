//! `millimpact compare`: every source side by side for each case (the paper's law exact and by
//! the paper's rk4, each DEM code, each code's own law at zero step error, the elastic contact),
//! with the differences from the paper's law split into model, integration and remainder.

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::Result;
use serde::Serialize;

use super::store::{self, Attribution, ReferenceOptions, ReferenceRecord, Split};
use crate::codes::CodeName;
use crate::model::case::Case;
use crate::model::exact;
use crate::output::{Section, Summary, sci, seconds, signed};
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
    /// The code.
    pub code: CodeName,
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
    let contact = case.scene.elastic_contact(v0);
    let elastic = (contact.peak_deformation, contact.contact_time);
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
    for &code in CodeName::ALL {
        let record: Option<ReferenceRecord> = if live {
            let options = ReferenceOptions {
                timeout,
                ..ReferenceOptions::default()
            };
            match store::run_reference(code, case, &options) {
                Ok(r) => Some(r),
                Err(e) => {
                    missing.push(format!("{code}: {e:#}"));
                    None
                }
            }
        } else {
            let found = store::find_stored(reference, code, &case.name, case.loss_coefficient)?;
            if found.is_none() {
                missing.push(format!(
                    "{code}: no stored run at η = {} (make one: millimpact reference --code {code} {} --save)",
                    case.loss_coefficient,
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
            code: r.code,
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

/// How to compare.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareOptions {
    /// Run the codes now instead of reading stored references.
    pub live: bool,
    /// Folder of stored references.
    pub reference: PathBuf,
    /// Kill a code after this long (live runs).
    pub timeout: Duration,
}

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            live: false,
            reference: PathBuf::from("reference"),
            timeout: Duration::from_secs(300),
        }
    }
}

/// Everything `compare` reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CompareReport {
    /// Whether the codes ran now.
    pub live: bool,
    /// One comparison per case.
    pub cases: Vec<CaseComparison>,
}

impl CompareReport {
    /// The codes that were asked to run and did not, with why (live runs only).
    pub fn failures(&self) -> Vec<String> {
        if self.live {
            self.cases.iter().flat_map(|c| c.missing.clone()).collect()
        } else {
            Vec::new()
        }
    }
}

/// Compare `cases`.
pub fn compare(cases: &[Case], options: &CompareOptions) -> Result<CompareReport> {
    let cases = cases
        .iter()
        .map(|case| compare_case(case, options.live, &options.reference, options.timeout))
        .collect::<Result<_>>()?;
    Ok(CompareReport {
        live: options.live,
        cases,
    })
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
    vec![
        row.source.clone(),
        format!("{:.6}", row.cor),
        sci(row.peak_deformation),
        sci(row.peak_force),
        sci(row.contact_time),
        row.run_time.map(seconds).unwrap_or_default(),
        signed(row.cor_vs_paper),
        signed(row.peak_deformation_vs_paper),
        signed(row.contact_time_vs_paper),
        format!(
            "{} / {}",
            signed(row.peak_deformation_vs_elastic),
            signed(row.contact_time_vs_elastic)
        ),
    ]
}

fn attribution_cells(a: &CodeAttribution) -> Vec<String> {
    let s = |x: &Split| {
        format!(
            "{} / {} / {}",
            signed(x.cor),
            signed(x.peak_deformation),
            signed(x.contact_time)
        )
    };
    vec![
        a.code.to_string(),
        sci(a.timestep),
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

/// One source for one case as a CSV row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CompareRecord {
    /// Case name.
    pub case: String,
    /// η.
    pub loss_coefficient: f64,
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
    /// Run time, s (empty for closed forms).
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

impl Summary for CompareReport {
    type Record = CompareRecord;

    fn records(&self) -> Vec<CompareRecord> {
        self.cases
            .iter()
            .flat_map(|c| {
                c.rows.iter().map(|r| CompareRecord {
                    case: c.case.clone(),
                    loss_coefficient: c.loss_coefficient,
                    source: r.source.clone(),
                    cor: r.cor,
                    peak_deformation: r.peak_deformation,
                    peak_force: r.peak_force,
                    contact_time: r.contact_time,
                    run_time: r.run_time,
                    cor_vs_paper: r.cor_vs_paper,
                    peak_deformation_vs_paper: r.peak_deformation_vs_paper,
                    contact_time_vs_paper: r.contact_time_vs_paper,
                    peak_deformation_vs_elastic: r.peak_deformation_vs_elastic,
                    contact_time_vs_elastic: r.contact_time_vs_elastic,
                })
            })
            .collect()
    }

    fn sections(&self) -> Vec<Section> {
        let mut sections = Vec::new();
        for c in &self.cases {
            let mut figures = Section::new(
                Some(format!(
                    "{} (η = {}, e = {:.6}){}",
                    c.case,
                    c.loss_coefficient,
                    exact::restitution(c.loss_coefficient),
                    if self.live {
                        ", codes run now"
                    } else {
                        ", stored references"
                    }
                )),
                &HEADERS,
            );
            figures.rows = c.rows.iter().map(cells).collect();
            let mut split = Section::new(
                Some(format!(
                    "{}: difference from the paper's law, split (relative to the paper's law)",
                    c.case
                )),
                &ATTRIBUTION_HEADERS,
            );
            split.rows = c.attribution.iter().map(attribution_cells).collect();
            split.notes = c.missing.iter().map(|m| format!("missing: {m}")).collect();
            sections.push(figures);
            sections.push(split);
        }
        sections
    }

    fn footer(&self) -> Vec<String> {
        let cases: Vec<String> = self.cases.iter().map(|c| c.path.clone()).collect();
        vec![format!(
            "reproduce: millimpact compare {}{}",
            cases.join(" "),
            if self.live { " --live" } else { "" },
        )]
    }
}
