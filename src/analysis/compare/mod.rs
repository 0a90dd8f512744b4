//! `millimpact compare`: every source side by side for each case (the paper's law exact and by
//! the paper's rk4, each DEM code, each code's own law at zero step error, the elastic contact),
//! with the differences from the paper's law split into model, integration and remainder.

pub mod phase;

use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::Serialize;
use thiserror::Error;

use super::store::{
    self, Attribution, CodeLawError, ReferenceOptions, ReferenceRecord, StoreError, own_law_exact,
};
use crate::codes::{CodeName, setup_for_case};
use crate::error::{Blame, Chain};
use crate::model::case::Case;
use crate::model::exact;
use crate::model::figures::{Elastic, Figures, Measured, Quantity, quantity};
use crate::model::trajectory::TrajectoryMetrics;
use crate::output::invocation::Invocation;
use crate::output::{Section, Summary, sci, seconds, signed};
use crate::solve::paper::{self, Settings};
use crate::solve::{Method, SolveError};
use phase::{DEFAULT_PHASES, OFFSET_QUANTITIES, Offsets, PhaseBand};

/// What produced a row of figures in a comparison; written (in every format) as its
/// [`Display`](std::fmt::Display) text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CompareSource {
    /// The paper's law by its closed form.
    PaperExact,
    /// The paper's law stepped by the paper's fixed-step RK4.
    PaperRk4,
    /// A DEM code's run, with the version it reported.
    Code {
        /// The code.
        code: CodeName,
        /// Its version, shortened.
        version: String,
    },
    /// The code's own law stepped as the code steps it.
    CodeLawStepped(CodeName),
    /// The code's own law integrated to near zero step error.
    CodeLawExact(CodeName),
    /// The elastic contact (no loss): Hertz's for a ball scene, else a linear spring.
    Elastic {
        /// Whether the contact is Hertz's.
        hertz: bool,
    },
}

impl std::fmt::Display for CompareSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CompareSource::PaperExact => f.write_str("paper law, exact"),
            CompareSource::PaperRk4 => f.write_str("paper law, rk4 (paper's method)"),
            CompareSource::Code { code, version } => write!(f, "{code} {version}"),
            CompareSource::CodeLawStepped(code) => write!(f, "{code} law, stepped as {code}"),
            CompareSource::CodeLawExact(code) => write!(f, "{code} law, exact"),
            CompareSource::Elastic { hertz: true } => f.write_str("Hertz, elastic"),
            CompareSource::Elastic { hertz: false } => f.write_str("linear spring, elastic"),
        }
    }
}

impl Serialize for CompareSource {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// One source's figures for one case.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SourceRow {
    /// What produced the figures.
    pub source: CompareSource,
    /// Its figures; the force contact time and the compression time are NaN where the source
    /// does not give them (a code run stored without them).
    #[serde(flatten)]
    pub figures: Measured,
    /// Kinetic energy absorbed by the impact, J: `½ M v0² (1 − e²)`.
    pub absorbed_energy: f64,
    /// Absorbed energy as a fraction of the impact energy: `1 − e²`.
    pub absorbed_fraction: f64,
    /// Run time, s (`None` for closed forms).
    pub run_time: Option<f64>,
    /// Relative difference of each figure from the paper's law's (whose force contact time
    /// equals its overlap contact time: its force is repulsive throughout the contact).
    #[serde(flatten, serialize_with = "crate::model::figures::suffix::vs_paper")]
    pub vs_paper: Measured,
    /// Relative difference of the peak deformation and the contact time from the elastic
    /// contact's.
    #[serde(flatten, serialize_with = "crate::model::figures::suffix::vs_elastic")]
    pub vs_elastic: Elastic,
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
    /// The split of the code's COR, peak deformation and overlap contact time.
    #[serde(flatten)]
    pub attribution: Attribution,
    /// The model difference in every figure: own law exact − paper's law exact.
    pub model_offsets: Offsets,
    /// The integration offset of the stored run's start (own law stepped from touch − own
    /// law exact): one point in `band`.
    pub integration_offsets: Offsets,
    /// The integration offset over the start phase.
    pub band: PhaseBand,
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
    /// Each code's model difference from the paper's law as a function of e.
    pub model_by_restitution: Vec<ModelPoint>,
}

/// The restitutions at which the model differences are tabulated.
pub(crate) const RESTITUTIONS: [f64; 8] = [0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95];

/// One code's law against the paper's law at one COR, both exact.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModelPoint {
    /// Case name.
    pub case: String,
    /// The code whose law (as its driver sets it up) this is.
    pub code: CodeName,
    /// The COR asked for.
    pub restitution: f64,
    /// The paper's η for it.
    pub loss_coefficient: f64,
    /// The COR the code's law realises (exact integration).
    pub law_cor: f64,
    /// Own law exact − paper's law exact, relative to the paper's law.
    pub offsets: Offsets,
    /// Relative difference of the compression time.
    pub compression_time: f64,
}

/// The quantities a [`ModelPoint`]'s CSV row gives: its offsets and its compression time.
const MODEL_POINT_QUANTITIES: u8 = OFFSET_QUANTITIES | quantity::COMPRESSION_TIME;

/// A [`ModelPoint`] as one CSV row: its offsets side by side.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct ModelPointRecord {
    /// Case name.
    pub case: String,
    /// The code whose law this is.
    pub code: CodeName,
    /// The COR asked for.
    pub restitution: f64,
    /// The paper's η for it.
    pub loss_coefficient: f64,
    /// The COR the code's law realises (exact integration).
    pub law_cor: f64,
    /// Own law exact − paper's law exact, relative, per figure.
    #[serde(flatten)]
    pub offsets: Figures<f64, MODEL_POINT_QUANTITIES>,
}

impl From<&ModelPoint> for ModelPointRecord {
    fn from(p: &ModelPoint) -> Self {
        let mut offsets: Figures<f64, MODEL_POINT_QUANTITIES> = p.offsets.select();
        offsets.compression_time = p.compression_time;
        ModelPointRecord {
            case: p.case.clone(),
            code: p.code,
            restitution: p.restitution,
            loss_coefficient: p.loss_coefficient,
            law_cor: p.law_cor,
            offsets,
        }
    }
}

/// Why a comparison could not be made; each variant names the code or the case.
#[derive(Debug, Error)]
pub enum CompareError {
    /// A code's own law could not be integrated, exactly or stepped as the code steps.
    #[error(transparent)]
    Law(#[from] CodeLawError),
    /// The paper's law could not be integrated by the paper's method.
    #[error("{}: rk4 (the paper's method)", case.display())]
    PaperMethod {
        /// The case file.
        case: PathBuf,
        /// Why.
        source: SolveError,
    },
    /// A stored reference could not be read.
    #[error(transparent)]
    Store(#[from] StoreError),
}

impl Blame for CompareError {
    fn is_user_error(&self) -> bool {
        match self {
            CompareError::Store(e) => e.is_user_error(),
            _ => false,
        }
    }
}

/// Each code's law, as its driver sets it up for `case` at each COR in `restitutions`,
/// against the paper's law at the same COR, both integrated exactly.
pub(crate) fn model_by_restitution(
    case: &Case,
    restitutions: &[f64],
) -> Result<Vec<ModelPoint>, CompareError> {
    let mut points = Vec::new();
    for &e in restitutions {
        let at = case.with_loss_coefficient(exact::loss_coefficient(e));
        let paper = exact::paper_impact(&at.law(), at.impact_velocity);
        let p = paper.metrics();
        let setup = setup_for_case(&at, 1.0);
        for &code in CodeName::ALL {
            let law = code.driver().law(&setup);
            let m = own_law_exact(code, &law, at.impact_velocity, 1e-12)?;
            points.push(ModelPoint {
                case: case.name.clone(),
                code,
                restitution: e,
                loss_coefficient: at.loss_coefficient,
                law_cor: m.cor,
                offsets: Offsets::between(&m, &p, &paper),
                compression_time: (m.compression_time - p.compression_time) / p.compression_time,
            });
        }
    }
    Ok(points)
}

struct Baseline {
    paper: Measured,
    elastic: Elastic,
    impact_energy: f64,
}

impl Baseline {
    fn row(&self, source: CompareSource, figures: Measured, run_time: Option<f64>) -> SourceRow {
        let fraction = 1.0 - figures.cor * figures.cor;
        SourceRow {
            source,
            figures,
            absorbed_energy: fraction * self.impact_energy,
            absorbed_fraction: fraction,
            run_time,
            vs_paper: figures.map(|q, x| (x - self.paper.get(q)) / self.paper.get(q)),
            vs_elastic: self.elastic.map(|q, e| (figures.get(q) - e) / e),
        }
    }
}

/// The attribution of a stored or live run, with the model difference in every figure and
/// the integration offset as a band over the start phase. The code's own law is integrated
/// again (exact and stepped) so that records stored before the force-based figures existed
/// give them too.
pub(crate) fn code_attribution(
    r: &ReferenceRecord,
) -> Result<(CodeAttribution, TrajectoryMetrics, TrajectoryMetrics), CompareError> {
    let code = r.code;
    let own_exact = own_law_exact(code, &r.law, r.setup.impact_velocity, 1e-13)?;
    let stepped = |source| CodeLawError::SteppedLaw { code, source };
    let own_stepped = phase::stepped_at_phase(r, 0.0).map_err(stepped)?;
    let paper = r.paper_exact.metrics();
    let band = phase::start_phase_band(r, &own_exact, DEFAULT_PHASES).map_err(stepped)?;
    Ok((
        CodeAttribution {
            code: r.code,
            code_version: r.code_version.clone(),
            timestep: r.timestep,
            attribution: r.attribution(),
            model_offsets: Offsets::between(&own_exact, &paper, &r.paper_exact),
            integration_offsets: Offsets::between(&own_stepped, &own_exact, &r.paper_exact),
            band,
        },
        own_stepped,
        own_exact,
    ))
}

/// Compare one case; `live` runs the codes, otherwise the stored references are read.
pub(crate) fn compare_case(
    case: &Case,
    live: bool,
    reference: &Path,
    timeout: Duration,
) -> Result<CaseComparison, CompareError> {
    let law = case.law();
    let v0 = case.impact_velocity;
    let exact = exact::paper_impact(&law, v0);
    let contact = case.scene.elastic_contact(v0);
    let base = Baseline {
        paper: exact.metrics(),
        elastic: Figures {
            peak_deformation: contact.peak_deformation,
            contact_time: contact.contact_time,
            ..Figures::default()
        },
        impact_energy: 0.5 * law.mass * v0 * v0,
    };
    let mut rows = vec![base.row(CompareSource::PaperExact, base.paper, None)];
    let settings = Settings {
        method: Method::Rk4,
        contact: case.contact,
        ..Settings::default()
    };
    let rk4 = paper::solve(&law, v0, &settings).map_err(|source| CompareError::PaperMethod {
        case: case.path.clone(),
        source,
    })?;
    rows.push(base.row(
        CompareSource::PaperRk4,
        rk4.figures.metrics(),
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
                    missing.push(format!("{code}: {}", Chain(&e)));
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
        let (split, own_stepped, own_exact) = code_attribution(&r)?;
        let code_figures = r.figures;
        rows.push(base.row(
            CompareSource::Code {
                code: r.code,
                version: short_version(&r.code_version),
            },
            code_figures,
            Some(r.wall_time),
        ));
        for (source, figures) in [
            (CompareSource::CodeLawStepped(r.code), &own_stepped),
            (CompareSource::CodeLawExact(r.code), &own_exact),
        ] {
            rows.push(base.row(source, *figures, None));
        }
        attribution.push(split);
    }
    let elastic_figures = Measured {
        cor: 1.0,
        peak_deformation: contact.peak_deformation,
        peak_force: f64::NAN,
        contact_time: contact.contact_time,
        force_contact_time: contact.contact_time,
        compression_time: 0.5 * contact.contact_time,
        ..Measured::default()
    };
    rows.push(base.row(
        CompareSource::Elastic {
            hertz: case.scene.effective_modulus().is_some(),
        },
        elastic_figures,
        None,
    ));
    Ok(CaseComparison {
        case: case.name.clone(),
        path: case.path.display().to_string(),
        loss_coefficient: case.loss_coefficient,
        rows,
        attribution,
        missing,
        model_by_restitution: model_by_restitution(case, &RESTITUTIONS)?,
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
    pub(crate) fn failures(&self) -> Vec<String> {
        if self.live {
            self.cases.iter().flat_map(|c| c.missing.clone()).collect()
        } else {
            Vec::new()
        }
    }
}

/// Compare `cases`.
pub fn compare(cases: &[Case], options: &CompareOptions) -> Result<CompareReport, CompareError> {
    let cases = cases
        .iter()
        .map(|case| compare_case(case, options.live, &options.reference, options.timeout))
        .collect::<Result<_, _>>()?;
    Ok(CompareReport {
        live: options.live,
        cases,
    })
}

const HEADERS: [&str; 12] = [
    "source",
    "COR",
    "peak (m)",
    "peak force (N)",
    "contact time, overlap (s)",
    "contact time, force (s)",
    "compression (s)",
    "absorbed (J, share)",
    "run time",
    "ΔCOR vs paper",
    "Δpeak / Δforce vs paper",
    "Δtime overlap / force vs paper",
];

fn cells(row: &SourceRow) -> Vec<String> {
    let figures = row.figures.iter().map(|(q, &x)| {
        if q == Quantity::Cor {
            format!("{x:.6}")
        } else {
            sci(x)
        }
    });
    let mut cells: Vec<String> = std::iter::once(row.source.to_string())
        .chain(figures)
        .collect();
    let vs_paper = &row.vs_paper;
    cells.extend([
        format!(
            "{:.4} ({:.1} %)",
            row.absorbed_energy,
            100.0 * row.absorbed_fraction
        ),
        row.run_time.map(seconds).unwrap_or_default(),
        signed(vs_paper.cor),
        format!(
            "{} / {}",
            signed(vs_paper.peak_deformation),
            signed_or_na(vs_paper.peak_force)
        ),
        format!(
            "{} / {}",
            signed(vs_paper.contact_time),
            signed_or_na(vs_paper.force_contact_time)
        ),
    ]);
    cells
}

fn signed_or_na(x: f64) -> String {
    if x.is_nan() { "n/a".into() } else { signed(x) }
}

fn offsets_cell(o: &Offsets) -> String {
    let cells: Vec<String> = o.iter().map(|(_, &x)| signed(x)).collect();
    cells.join(" / ")
}

fn attribution_cells(a: &CodeAttribution) -> Vec<String> {
    let band = |r: &phase::Range| format!("[{}, {}]", signed(r.min), signed(r.max));
    vec![
        a.code.to_string(),
        sci(a.timestep),
        offsets_cell(&a.model_offsets),
        offsets_cell(&a.integration_offsets),
        band(&a.band.ranges.cor),
        band(&a.band.ranges.contact_time),
        signed(a.attribution.remainder.cor),
    ]
}

const ATTRIBUTION_HEADERS: [&str; 7] = [
    "code",
    "Δt (s)",
    "model (COR / peak / force / t overlap / t force)",
    "integration at the stored start",
    "integration band, COR",
    "integration band, t overlap",
    "remainder, COR",
];

const BY_E_HEADERS: [&str; 9] = [
    "e",
    "η",
    "code",
    "law's COR",
    "Δpeak",
    "Δpeak force",
    "Δt overlap",
    "Δt force",
    "Δt compression",
];

fn by_e_cells(p: &ModelPoint) -> Vec<String> {
    // The COR column is the law's COR itself: against the paper's at the same η, it is the
    // COR asked for.
    let offsets = p
        .offsets
        .iter()
        .filter(|&(q, _)| q != Quantity::Cor)
        .map(|(_, &x)| signed(x));
    [
        format!("{}", p.restitution),
        format!("{:.4}", p.loss_coefficient),
        p.code.to_string(),
        format!("{:.6}", p.law_cor),
    ]
    .into_iter()
    .chain(offsets)
    .chain([signed(p.compression_time)])
    .collect()
}

/// One source for one case as a CSV row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CompareRecord {
    /// Case name.
    pub case: String,
    /// η.
    pub loss_coefficient: f64,
    /// The source's figures and their differences (a force contact time not given is an
    /// empty field).
    #[serde(flatten)]
    pub row: SourceRow,
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
                    row: r.clone(),
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
            split.notes.push(format!(
                "integration band: the own law stepped as the code steps, first contact swept over {} start phases within one step; the stored run's start is one point in it",
                DEFAULT_PHASES
            ));
            figures.notes = vec![
                "contact time by overlap: first touch until the overlap returns to zero (the figure quoted before); by force: until the normal force first returns to zero".into(),
            ];
            if c.rows
                .iter()
                .any(|r| r.figures.force_contact_time.is_nan() && r.run_time.is_some())
            {
                figures.notes.push("n/a: a code run stored without its force-based times (by an older millimpact); its own law stepped as it steps (the row below it) gives them, and reproduces the run to its remainder".into());
            }
            let mut by_e = Section::new(
                Some(format!(
                    "{}: each code's law against the paper's law at equal COR, both exact, as a function of e",
                    c.case
                )),
                &BY_E_HEADERS,
            );
            by_e.rows = c.model_by_restitution.iter().map(by_e_cells).collect();
            sections.push(figures);
            sections.push(split);
            sections.push(by_e);
        }
        sections
    }

    fn footer(&self) -> Vec<String> {
        let cases: Vec<String> = self.cases.iter().map(|c| c.path.clone()).collect();
        vec![format!(
            "reproduce: {}",
            Invocation::new("compare")
                .args(&cases)
                .flag("--live", self.live)
        )]
    }
}

#[cfg(test)]
mod tests;
