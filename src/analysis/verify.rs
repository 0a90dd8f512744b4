//! `verify`: every case by every method against the closed forms, and every stored DEM-code
//! reference against the code's own law re-stepped by this build.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde::Serialize;

use super::run::run_case;
use super::source::Source;
use super::store::{load, stored_files};
use super::tolerance::{Differences, Tolerance};
use crate::error::UserError;
use crate::model::case::Case;
use crate::model::trajectory::trajectory_metrics;
use crate::output::{Section, Summary, signed};
use crate::solve::Method;
use crate::solve::dashpot::step_trajectory;
use crate::solve::paper::Settings;

/// Tolerance on a code's realised COR against its target (or documented value), absolute.
pub const COR_TOLERANCE: f64 = 0.01;
/// Tolerance on a code's peak deformation against its own law stepped as it steps, relative.
pub const EMULATION_TOLERANCE: f64 = 1e-3;
/// Bound on the unexplained remainder against the paper's law, relative.
pub const REMAINDER_TOLERANCE: f64 = 1e-3;

/// One check of `verify`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VerifyRow {
    /// Case name.
    pub case: String,
    /// η of a stored reference (`None` for a case checked at its own η).
    pub loss_coefficient: Option<f64>,
    /// What was checked.
    pub source: Source,
    /// Whether it is a stored reference.
    pub stored: bool,
    /// The differences checked (relative, but a code's COR: absolute against its target).
    pub differences: Differences,
    /// What they must stay within.
    pub tolerance: Tolerance,
    /// Whether every difference is within its tolerance.
    pub pass: bool,
}

/// Everything `verify` checked.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VerifyReport {
    /// The case folder.
    pub cases: PathBuf,
    /// The reference folder.
    pub reference: PathBuf,
    /// The checks.
    pub rows: Vec<VerifyRow>,
}

impl VerifyReport {
    /// The checks that disagree.
    pub fn failed(&self) -> usize {
        self.rows.iter().filter(|r| !r.pass).count()
    }
}

/// The case files in `dir`, sorted by name.
pub fn case_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| {
            UserError::argument(
                "--cases",
                dir.display(),
                format!("cannot read the folder: {e}"),
            )
        })?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(
            UserError::argument("--cases", dir.display(), "holds no .toml case files").into(),
        );
    }
    Ok(files)
}

/// Check every case in `dir` by every integrating method against the closed forms.
pub fn verify_cases(dir: &Path) -> Result<Vec<VerifyRow>> {
    let mut rows = Vec::new();
    for path in case_files(dir)? {
        let case = Case::load(&path)?;
        for &method in Method::ALL.iter().filter(|m| m.integrates()) {
            let settings = Settings {
                method,
                contact: case.contact,
                ..Settings::default()
            };
            let (report, _) = run_case(&case, &settings)?;
            let tolerance =
                Tolerance::for_method(method, report.timestep, report.exact.contact_time);
            let differences = Differences {
                cor: report.error.cor,
                peak_deformation: report.error.peak_deformation,
                contact_time: report.error.contact_time,
            };
            rows.push(VerifyRow {
                case: case.name.clone(),
                loss_coefficient: None,
                source: Source::Method(method),
                stored: false,
                pass: tolerance.admits(&differences),
                differences,
                tolerance,
            });
        }
    }
    Ok(rows)
}

/// The checks of every stored run: the realised COR against its target, the code's peak
/// against its own law stepped now by this build (so a change in the emulation or the law
/// shows), and the remainder against the paper's law.
pub fn verify_stored(folder: &Path) -> Result<Vec<VerifyRow>> {
    let mut rows = Vec::new();
    for path in stored_files(folder)? {
        let file = load(&path)?;
        for record in &file.runs {
            let stepped = step_trajectory(
                &record.law,
                record.setup.impact_velocity,
                record.timestep,
                record.steps,
                record.step_scheme,
            );
            let now = trajectory_metrics(&stepped)
                .with_context(|| format!("{}: own law stepped", path.display()))?;
            let differences = Differences {
                cor: record.cor - record.cor_target(),
                peak_deformation: (record.peak_deformation - now.peak_deformation)
                    / now.peak_deformation,
                contact_time: (record.contact_time - now.contact_time) / now.contact_time,
            };
            let remainder = record.attribution().remainder;
            let tolerance = Tolerance {
                cor: COR_TOLERANCE,
                peak_deformation: EMULATION_TOLERANCE,
                contact_time: record.timestep / now.contact_time,
            };
            let remainder_ok = remainder.cor.abs() <= REMAINDER_TOLERANCE
                && remainder.peak_deformation.abs() <= REMAINDER_TOLERANCE;
            rows.push(VerifyRow {
                case: record.case.clone(),
                loss_coefficient: Some(record.loss_coefficient),
                source: Source::Code(record.code),
                stored: true,
                pass: tolerance.admits(&differences) && remainder_ok,
                differences,
                tolerance,
            });
        }
    }
    Ok(rows)
}

/// `verify`: the cases in `cases` and the stored references in `reference`.
pub fn verify(cases: &Path, reference: &Path) -> Result<VerifyReport> {
    let mut rows = verify_cases(cases)?;
    rows.extend(verify_stored(reference)?);
    Ok(VerifyReport {
        cases: cases.to_path_buf(),
        reference: reference.to_path_buf(),
        rows,
    })
}

/// One check as a CSV row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VerifyRecord {
    /// Case name.
    pub case: String,
    /// η of a stored reference, empty otherwise.
    pub loss_coefficient: Option<f64>,
    /// `method` or `code`.
    pub source_kind: &'static str,
    /// The method's or code's name.
    pub source: &'static str,
    /// Whether it is a stored reference.
    pub stored: bool,
    /// COR difference.
    pub cor_error: f64,
    /// Peak deformation difference.
    pub peak_deformation_error: f64,
    /// Contact time difference.
    pub contact_time_error: f64,
    /// Tolerance on the COR.
    pub cor_tolerance: f64,
    /// Tolerance on the peak deformation.
    pub peak_deformation_tolerance: f64,
    /// Tolerance on the contact time.
    pub contact_time_tolerance: f64,
    /// Whether every difference is within its tolerance.
    pub pass: bool,
}

impl Summary for VerifyReport {
    type Record = VerifyRecord;

    fn records(&self) -> Vec<VerifyRecord> {
        self.rows
            .iter()
            .map(|r| VerifyRecord {
                case: r.case.clone(),
                loss_coefficient: r.loss_coefficient,
                source_kind: r.source.kind(),
                source: r.source.name(),
                stored: r.stored,
                cor_error: r.differences.cor,
                peak_deformation_error: r.differences.peak_deformation,
                contact_time_error: r.differences.contact_time,
                cor_tolerance: r.tolerance.cor,
                peak_deformation_tolerance: r.tolerance.peak_deformation,
                contact_time_tolerance: r.tolerance.contact_time,
                pass: r.pass,
            })
            .collect()
    }

    fn sections(&self) -> Vec<Section> {
        let mut t = Section::new(
            None,
            &[
                "case",
                "source",
                "COR error",
                "peak error",
                "contact-time error",
                "tolerance (COR / peak / time)",
                "",
            ],
        );
        for r in &self.rows {
            t.rows.push(vec![
                match r.loss_coefficient {
                    Some(eta) => format!("{} η={eta}", r.case),
                    None => r.case.clone(),
                },
                if r.stored {
                    format!("{} (stored)", r.source)
                } else {
                    r.source.to_string()
                },
                signed(r.differences.cor),
                signed(r.differences.peak_deformation),
                signed(r.differences.contact_time),
                format!(
                    "{:.0e} / {:.0e} / {:.1e}",
                    r.tolerance.cor, r.tolerance.peak_deformation, r.tolerance.contact_time
                ),
                if r.pass { "ok" } else { "FAIL" }.to_string(),
            ]);
        }
        let failed = self.failed();
        t.notes.push(format!(
            "{} checks, {} passed, {} failed",
            self.rows.len(),
            self.rows.len() - failed,
            failed
        ));
        vec![t]
    }

    fn footer(&self) -> Vec<String> {
        vec![
            format!(
                "reproduce a method row: millimpact run {}/CASE.toml --method METHOD --format json",
                self.cases.display()
            ),
            format!(
                "reproduce a stored row: the `command` field of {}/CODE/CASE.json",
                self.reference.display()
            ),
        ]
    }
}
