//! The commands behind the command line.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde::Serialize;
use thiserror::Error;

use crate::case::{Case, CaseError};
use crate::cli::{IntegrationArgs, RunArgs, SweepArgs, VerifyArgs};
use crate::report::{self, Format, RunReport};
use crate::solve::paper::{self, Settings};
use crate::solve::{Method, SolveError};

/// An error in what the user asked for: exit code 2.
#[derive(Debug, Error)]
pub enum UserError {
    /// A case file is invalid.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// A command-line value is invalid.
    #[error("{option} = {value}: {allowed}")]
    Argument {
        /// The option.
        option: String,
        /// Its value.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A command-line value is invalid for the case it is applied to.
    #[error("{case}: {option} = {value}: {allowed}")]
    CaseArgument {
        /// The case file.
        case: String,
        /// The option.
        option: String,
        /// Its value.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// The integration cannot be done as asked (a step beyond the stability limit).
    #[error("{case}: --timestep: {source}")]
    Unsolvable {
        /// The case file.
        case: String,
        /// Why.
        source: SolveError,
    },
}

/// A check that ran and disagreed: exit code 1.
#[derive(Debug, Error)]
#[error("{0}")]
pub struct CheckFailed(pub String);

fn argument(option: &str, value: impl ToString, allowed: &str) -> anyhow::Error {
    UserError::Argument {
        option: option.to_string(),
        value: value.to_string(),
        allowed: allowed.to_string(),
    }
    .into()
}

/// An invalid option value, named together with the case file it was applied to.
fn case_argument(case: &Case, option: &str, value: impl ToString, allowed: &str) -> anyhow::Error {
    UserError::CaseArgument {
        case: case.path.display().to_string(),
        option: option.to_string(),
        value: value.to_string(),
        allowed: allowed.to_string(),
    }
    .into()
}

/// Validate the integration options and turn them into solver settings.
pub fn settings(args: &IntegrationArgs, case: &Case, record: bool) -> Result<Settings> {
    let argument =
        |option: &str, value: f64, allowed: &str| case_argument(case, option, value, allowed);
    if !(args.rtol > 0.0 && args.rtol < 1.0) {
        return Err(argument("--rtol", args.rtol, "must be in (0, 1)"));
    }
    if let Some(dt) = args.timestep {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(argument(
                "--timestep",
                dt,
                "must be a finite number > 0 (seconds)",
            ));
        }
        if !args.method.is_fixed_step() {
            return Err(argument(
                "--timestep",
                dt,
                "applies to the fixed-step methods rk4, rk4-event and verlet only",
            ));
        }
    }
    if !(args.periods.is_finite() && args.periods > 0.0) {
        return Err(argument(
            "--periods",
            args.periods,
            "must be a finite number > 0",
        ));
    }
    Ok(Settings {
        method: args.method,
        steps_per_period: args.steps_per_period,
        timestep: args.timestep,
        rtol: args.rtol,
        contact: case.contact,
        periods: args.periods,
        record,
    })
}

/// Integrate `case` with `settings` and report against the closed forms.
pub fn run_case(case: &Case, settings: &Settings) -> Result<(RunReport, paper::Outcome)> {
    let outcome =
        paper::solve(&case.law(), case.impact_velocity, settings).map_err(|e| match e {
            SolveError::Unstable { .. } => anyhow::Error::from(UserError::Unsolvable {
                case: case.path.display().to_string(),
                source: e,
            }),
            other => anyhow::Error::from(other)
                .context(format!("{}: integration failed", case.path.display())),
        })?;
    Ok((RunReport::new(case, settings.method, &outcome), outcome))
}

/// `millimpact run`.
pub fn run(args: &RunArgs) -> Result<String> {
    let case = Case::load(&args.case)?;
    if let Some(path) = &args.trajectory
        && args.integration.method == Method::Exact
    {
        return Err(argument(
            "--trajectory",
            path.display(),
            "the exact method has no time history; use rk4, rk4-event, dopri5 or verlet",
        ));
    }
    let settings = settings(&args.integration, &case, args.trajectory.is_some())?;
    let (report, outcome) = run_case(&case, &settings)?;
    let text = match args.format {
        Format::Table => format!(
            "{}reproduce: millimpact run {}\n",
            report.table(),
            reproduce_arguments(&args.case, &args.integration)
        ),
        Format::Json => serde_json::to_string_pretty(&report)? + "\n",
        Format::Csv => report::csv_string(&[report.row()])?,
        Format::Markdown => {
            let row = report.row();
            report::markdown_table(
                &[
                    "case",
                    "method",
                    "η",
                    "COR",
                    "COR error",
                    "peak (m)",
                    "contact time (s)",
                ],
                &[vec![
                    row.case,
                    row.method.to_string(),
                    row.loss_coefficient.to_string(),
                    report::sci(row.cor),
                    format!("{:+.2e}", row.cor_error),
                    report::sci(row.peak_deformation),
                    report::sci(row.contact_time),
                ]],
            )
        }
    };
    if let Some(path) = &args.trajectory {
        let csv = report::trajectory_csv(&case, &outcome.trajectory)?;
        report::write_atomic(path, csv.as_bytes())
            .with_context(|| format!("writing the trajectory to {}", path.display()))?;
    }
    Ok(text)
}

/// The arguments that repeat a run: the case and the settings that shaped it.
fn reproduce_arguments(case: &Path, args: &IntegrationArgs) -> String {
    let mut text = format!("{} --method {}", case.display(), args.method.name());
    match (args.method, args.timestep) {
        (_, Some(dt)) => text += &format!(" --timestep {dt:e}"),
        (Method::Dopri5, None) => text += &format!(" --rtol {:e}", args.rtol),
        (Method::Exact, None) => {}
        (_, None) => text += &format!(" --steps-per-period {}", args.steps_per_period),
    }
    text
}

/// Parse `START:STOP:STEP` into the values of η it names, STOP included.
pub fn parse_range(text: &str) -> Result<Vec<f64>> {
    let allowed = "START:STOP:STEP with 0 <= START <= STOP < 1 and STEP > 0";
    let parts: Vec<&str> = text.split(':').collect();
    let numbers: Option<Vec<f64>> = parts.iter().map(|p| p.trim().parse().ok()).collect();
    let Some([start, stop, step]) = numbers
        .as_deref()
        .and_then(|v| <[f64; 3]>::try_from(v).ok())
    else {
        return Err(argument("--loss-coefficient", text, allowed));
    };
    let finite = start.is_finite() && stop.is_finite() && step.is_finite();
    if !finite || start < 0.0 || stop >= 1.0 || start > stop || step <= 0.0 {
        return Err(argument("--loss-coefficient", text, allowed));
    }
    let count = ((stop - start) / step + 1e-9).floor() as usize + 1;
    if count > 100_000 {
        return Err(argument(
            "--loss-coefficient",
            text,
            "at most 100000 values",
        ));
    }
    Ok((0..count).map(|i| start + i as f64 * step).collect())
}

/// `millimpact sweep`.
pub fn sweep(args: &SweepArgs) -> Result<String> {
    let case = Case::load(&args.case)?;
    let values =
        parse_range(&args.loss_coefficient).map_err(|e| match e.downcast::<UserError>() {
            Ok(UserError::Argument {
                option,
                value,
                allowed,
            }) => case_argument(&case, &option, value, &allowed),
            Ok(other) => other.into(),
            Err(other) => other,
        })?;
    let mut rows = Vec::with_capacity(values.len());
    for eta in values {
        let at = case.with_loss_coefficient(eta);
        let settings = settings(&args.integration, &at, false)?;
        rows.push(run_case(&at, &settings)?.0.row());
    }
    if let Some(path) = &args.plot {
        let svg = crate::figures::restitution_svg(&case.name, &rows)?;
        report::write_atomic(path, svg.as_bytes())
            .with_context(|| format!("writing the figure to {}", path.display()))?;
    }
    report::csv_string(&rows)
}

/// The agreement a method must reach against the closed forms, relative.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Tolerance {
    /// On the COR.
    pub cor: f64,
    /// On the peak deformation.
    pub peak_deformation: f64,
    /// On the contact time.
    pub contact_time: f64,
}

/// The stated tolerance of `method` for a run that reported `report`.
///
/// Event-located and adaptive methods must meet 1e-9. The fixed-step methods that end the
/// contact at the first step past zero (the paper's rk4, and Verlet) cannot place the end
/// closer than one step, so their contact time is allowed one step; their COR and peak are
/// allowed 1e-3, what DEM practice asks of an impact.
pub fn tolerance(method: Method, report: &RunReport) -> Tolerance {
    match method {
        Method::Rk4Event | Method::Dopri5 | Method::Exact => Tolerance {
            cor: 1e-9,
            peak_deformation: 1e-9,
            contact_time: 1e-9,
        },
        Method::Rk4 | Method::Verlet => Tolerance {
            cor: 1e-3,
            peak_deformation: 1e-3,
            contact_time: report.timestep.unwrap_or(0.0) / report.exact.contact_time,
        },
    }
}

/// One line of `millimpact verify`.
#[derive(Clone, Debug, Serialize)]
pub struct VerifyRow {
    /// Case name, or code and case for a stored reference.
    pub case: String,
    /// Method, or the source checked.
    pub method: String,
    /// Relative errors.
    pub cor_error: f64,
    /// Relative error of the peak deformation.
    pub peak_deformation_error: f64,
    /// Relative error of the contact time.
    pub contact_time_error: f64,
    /// The tolerance.
    pub tolerance: Tolerance,
    /// Whether every error is within its tolerance.
    pub pass: bool,
}

/// The case files in `dir`, sorted by name.
pub fn case_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| {
            argument(
                "--cases",
                dir.display(),
                &format!("cannot read the folder: {e}"),
            )
        })?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(argument(
            "--cases",
            dir.display(),
            "holds no .toml case files",
        ));
    }
    Ok(files)
}

/// Check every case by every method against the closed forms.
pub fn verify_cases(dir: &Path) -> Result<Vec<VerifyRow>> {
    let mut rows = Vec::new();
    for path in case_files(dir)? {
        let case = Case::load(&path)?;
        for method in Method::ALL {
            if method == Method::Exact {
                continue;
            }
            let settings = Settings {
                method,
                contact: case.contact,
                ..Settings::default()
            };
            let (report, _) = run_case(&case, &settings)?;
            let tol = tolerance(method, &report);
            let e = report.error;
            let pass = e.cor.abs() <= tol.cor
                && e.peak_deformation.abs() <= tol.peak_deformation
                && e.contact_time.abs() <= tol.contact_time;
            rows.push(VerifyRow {
                case: case.name.clone(),
                method: method.name().to_string(),
                cor_error: e.cor,
                peak_deformation_error: e.peak_deformation,
                contact_time_error: e.contact_time,
                tolerance: tol,
                pass,
            });
        }
    }
    Ok(rows)
}

/// `millimpact verify`.
pub fn verify(args: &VerifyArgs) -> Result<String> {
    let mut rows = verify_cases(&args.cases)?;
    rows.extend(crate::references::verify_rows(
        &args.reference,
        &args.cases,
    )?);
    let failed = rows.iter().filter(|r| !r.pass).count();
    let text = match args.format {
        Format::Json => serde_json::to_string_pretty(&rows)? + "\n",
        Format::Csv => {
            let flat: Vec<_> = rows
                .iter()
                .map(|r| {
                    (
                        &r.case,
                        &r.method,
                        r.cor_error,
                        r.peak_deformation_error,
                        r.contact_time_error,
                        r.tolerance.cor,
                        r.tolerance.peak_deformation,
                        r.tolerance.contact_time,
                        r.pass,
                    )
                })
                .collect();
            let mut text = "case,method,cor_error,peak_deformation_error,contact_time_error,cor_tolerance,peak_deformation_tolerance,contact_time_tolerance,pass\n".to_string();
            let body = report::csv_string(&flat)?;
            text += &body;
            text
        }
        Format::Table | Format::Markdown => {
            let headers = [
                "case",
                "source",
                "COR error",
                "peak error",
                "contact-time error",
                "tolerance (COR / peak / time)",
                "",
            ];
            let cells: Vec<Vec<String>> = rows
                .iter()
                .map(|r| {
                    vec![
                        r.case.clone(),
                        r.method.clone(),
                        format!("{:+.2e}", r.cor_error),
                        format!("{:+.2e}", r.peak_deformation_error),
                        format!("{:+.2e}", r.contact_time_error),
                        format!(
                            "{:.0e} / {:.0e} / {:.1e}",
                            r.tolerance.cor, r.tolerance.peak_deformation, r.tolerance.contact_time
                        ),
                        if r.pass { "ok" } else { "FAIL" }.to_string(),
                    ]
                })
                .collect();
            let table = if args.format == Format::Markdown {
                report::markdown_table(&headers, &cells)
            } else {
                let mut t = report::new_table(&headers);
                for row in cells {
                    t.add_row(row);
                }
                format!("{t}\n")
            };
            format!(
                "{table}{} checks, {} passed, {} failed\n\
                 reproduce a method row: millimpact run {}/CASE.toml --method METHOD --format json\n\
                 reproduce a stored row: the `command` field of {}/CODE/CASE.json\n",
                rows.len(),
                rows.len() - failed,
                failed,
                args.cases.display(),
                args.reference.display()
            )
        }
    };
    if failed > 0 {
        print!("{text}");
        return Err(CheckFailed(format!(
            "verify: {failed} of {} checks disagree",
            rows.len()
        ))
        .into());
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_includes_its_stop() {
        let v = parse_range("0:0.9:0.1").unwrap();
        assert_eq!(v.len(), 10);
        assert!((v[9] - 0.9).abs() < 1e-12);
        assert_eq!(parse_range("0.35:0.35:0.1").unwrap(), vec![0.35]);
    }

    #[test]
    fn range_refuses_what_is_not_allowed() {
        for bad in [
            "0:1:0.1",
            "0.5:0.1:0.1",
            "0:0.5:0",
            "-0.1:0.5:0.1",
            "0:0.5",
            "a:b:c",
            "0:nan:0.1",
        ] {
            assert!(parse_range(bad).is_err(), "{bad}");
        }
    }
}
