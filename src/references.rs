//! Runs of the DEM codes on the equivalent setups, and their stored results in `reference/`
//! with provenance (code version, the exact input and its hash, time step, date, command).
//!
//! A stored run keeps, beside the code's figures, the code's own law as the driver read it and
//! that law integrated twice: stepped the way the code steps, and at zero step error. The
//! difference between the code and the paper's law then splits into a difference of model
//! (own law exact − paper law exact), an integration error (own law stepped − own law exact)
//! and a remainder (code − own law stepped) that nothing explains.

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::app::{Tolerance, UserError, VerifyRow};
use crate::case::Case;
use crate::cli::ReferenceArgs;
use crate::codes::{
    self, CodeDriver, CodeSetup, RunOptions, TrajectoryMetrics, run_code, trajectory_metrics,
};
use crate::exact::{self, ImpactFigures};
use crate::law::DashpotLaw;
use crate::report::{self, Format};
use crate::solve::dashpot::{StepScheme, accurate_metrics, step_trajectory};

/// Tolerance on a code's realised COR against its target (or documented value), absolute.
pub const COR_TOLERANCE: f64 = 0.01;
/// Tolerance on a code's peak deformation against its own law stepped as it steps, relative.
pub const EMULATION_TOLERANCE: f64 = 1e-3;
/// Bound on the unexplained remainder against the paper's law, relative.
pub const REMAINDER_TOLERANCE: f64 = 1e-3;

/// One run of one code on one case at one η.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReferenceRecord {
    /// Code name.
    pub code: String,
    /// Version string as the code printed it.
    pub code_version: String,
    /// Case name.
    pub case: String,
    /// Scene name.
    pub scene: String,
    /// η of the paper's law this run is equivalent to.
    pub loss_coefficient: f64,
    /// The COR asked of the code, `e(η)`.
    pub target_restitution: f64,
    /// The COR the code is documented to realise where it allows no equivalent setup.
    pub expected_restitution: Option<f64>,
    /// Time step, s.
    pub timestep: f64,
    /// Steps run.
    pub steps: u64,
    /// The code's COR.
    pub cor: f64,
    /// The code's peak overlap, m.
    pub peak_deformation: f64,
    /// The code's peak normal force, N.
    pub peak_force: f64,
    /// The code's contact time, s.
    pub contact_time: f64,
    /// Process wall time, s.
    pub wall_time: f64,
    /// The code's own loop time, s.
    pub loop_time: Option<f64>,
    /// The law the code integrates, as the driver reads it.
    pub law: DashpotLaw,
    /// How the code steps.
    pub step_scheme: StepScheme,
    /// That law stepped the way the code steps, at the code's step.
    pub law_at_step: TrajectoryMetrics,
    /// That law at zero step error.
    pub law_exact: TrajectoryMetrics,
    /// The paper's law at the same η, exact.
    pub paper_exact: ImpactFigures,
    /// The setup given to the code.
    pub setup: CodeSetup,
    /// The exact input the code ran.
    pub input: String,
    /// SHA-256 of the input, hex.
    pub input_sha256: String,
    /// When it ran (UTC, RFC 3339).
    pub date: String,
    /// The command that reproduces it.
    pub command: String,
}

/// The file `reference/<code>/<case>.json`: the runs of one code on one case, one per η.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ReferenceFile {
    /// Code name.
    pub code: String,
    /// Case name.
    pub case: String,
    /// The runs, sorted by η.
    pub runs: Vec<ReferenceRecord>,
}

/// Relative differences of one source against another.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Split {
    /// Of the COR.
    pub cor: f64,
    /// Of the peak deformation.
    pub peak_deformation: f64,
    /// Of the contact time.
    pub contact_time: f64,
}

/// A code's difference from the paper's law, split into its parts (each relative to the
/// paper's law).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Attribution {
    /// Code − paper law.
    pub total: Split,
    /// Own law exact − paper law exact: the difference of model.
    pub model: Split,
    /// Own law stepped − own law exact: the code's integration error.
    pub integration: Split,
    /// Code − own law stepped: what nothing explains.
    pub remainder: Split,
}

impl ReferenceRecord {
    /// The split of the code's difference from the paper's law.
    pub fn attribution(&self) -> Attribution {
        let p = &self.paper_exact;
        let split = |a: (f64, f64, f64), b: (f64, f64, f64)| Split {
            cor: (a.0 - b.0) / p.cor,
            peak_deformation: (a.1 - b.1) / p.peak_deformation,
            contact_time: (a.2 - b.2) / p.contact_time,
        };
        let code = (self.cor, self.peak_deformation, self.contact_time);
        let m = |t: &TrajectoryMetrics| (t.cor, t.peak_deformation, t.contact_time);
        let paper = (p.cor, p.peak_deformation, p.contact_time);
        Attribution {
            total: split(code, paper),
            model: split(m(&self.law_exact), paper),
            integration: split(m(&self.law_at_step), m(&self.law_exact)),
            remainder: split(code, m(&self.law_at_step)),
        }
    }

    /// The COR the code should realise: the documented one, or the target.
    pub fn cor_target(&self) -> f64 {
        self.expected_restitution.unwrap_or(self.target_restitution)
    }
}

/// Run `case` in `driver`'s code and assemble the record.
pub fn run_reference(
    driver: &dyn CodeDriver,
    case: &Case,
    steps_per_contact: Option<u32>,
    timestep: Option<f64>,
    clamp_attractive: bool,
    timeout: Duration,
) -> Result<ReferenceRecord> {
    let setup = codes::prepare(driver, case, steps_per_contact, timestep, clamp_attractive)
        .with_context(|| format!("{}: sizing the run from the code's law", driver.name()))?;
    let options = RunOptions {
        timeout,
        ..RunOptions::default()
    };
    let run = run_code(driver, &setup, &options)?;
    let metrics = trajectory_metrics(&run.trajectory)
        .map_err(|reason| anyhow::anyhow!("{}: {reason}", driver.name()))?;
    let law = driver.law(&setup);
    let scheme = driver.step_scheme();
    let stepped = step_trajectory(
        &law,
        setup.impact_velocity,
        setup.timestep,
        setup.steps,
        scheme,
    );
    let law_at_step = trajectory_metrics(&stepped)
        .map_err(|reason| anyhow::anyhow!("{}: own law stepped: {reason}", driver.name()))?;
    let law_exact = accurate_metrics(&law, setup.impact_velocity, 1e-13)?;
    let mut command = format!(
        "millimpact reference --code {} {} --loss-coefficient {}",
        driver.name(),
        case.path.display(),
        case.loss_coefficient
    );
    match (steps_per_contact, timestep) {
        (_, Some(dt)) => command += &format!(" --timestep {dt:e}"),
        (Some(n), None) => command += &format!(" --steps-per-contact {n}"),
        (None, None) => {}
    }
    if clamp_attractive {
        command += " --clamp";
    }
    Ok(ReferenceRecord {
        code: driver.name().to_string(),
        code_version: run.code_version,
        case: case.name.clone(),
        scene: case.scene.kind().name().to_string(),
        loss_coefficient: case.loss_coefficient,
        target_restitution: setup.target_restitution,
        expected_restitution: driver.expected_restitution(&setup),
        timestep: setup.timestep,
        steps: setup.steps,
        cor: metrics.cor,
        peak_deformation: metrics.peak_deformation,
        peak_force: metrics.peak_force,
        contact_time: metrics.contact_time,
        wall_time: run.wall_time,
        loop_time: run.loop_time,
        law,
        step_scheme: scheme,
        law_at_step,
        law_exact,
        paper_exact: exact::paper_impact(&case.law(), case.impact_velocity),
        input_sha256: hex(&Sha256::digest(run.input.as_bytes())),
        input: run.input,
        setup,
        date: chrono::Utc::now().to_rfc3339_opts(chrono::SecondsFormat::Secs, true),
        command,
    })
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Where the runs of `code` on `case` are stored.
pub fn reference_path(folder: &Path, code: &str, case: &str) -> PathBuf {
    folder.join(code).join(format!("{case}.json"))
}

/// Read a stored reference file.
pub fn load(path: &Path) -> Result<ReferenceFile> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{}: not a reference file", path.display()))
}

/// Store `record`, replacing a stored run of the same η.
pub fn save(folder: &Path, record: &ReferenceRecord) -> Result<PathBuf> {
    let path = reference_path(folder, &record.code, &record.case);
    let mut file = if path.exists() {
        load(&path)?
    } else {
        ReferenceFile {
            code: record.code.clone(),
            case: record.case.clone(),
            runs: Vec::new(),
        }
    };
    file.runs
        .retain(|r| (r.loss_coefficient - record.loss_coefficient).abs() > 1e-12);
    file.runs.push(record.clone());
    file.runs
        .sort_by(|a, b| a.loss_coefficient.total_cmp(&b.loss_coefficient));
    let text = serde_json::to_string_pretty(&file)? + "\n";
    report::write_atomic(&path, text.as_bytes())
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(path)
}

/// Every stored reference file under `folder`, sorted.
pub fn stored_files(folder: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    if !folder.is_dir() {
        return Ok(files);
    }
    for code in codes::all_drivers() {
        let dir = folder.join(code.name());
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.extension().is_some_and(|x| x == "json") {
                files.push(path);
            }
        }
    }
    files.sort();
    Ok(files)
}

/// The stored run of `code` on `case` at η, if any.
pub fn find_stored(
    folder: &Path,
    code: &str,
    case: &str,
    loss_coefficient: f64,
) -> Result<Option<ReferenceRecord>> {
    let path = reference_path(folder, code, case);
    if !path.exists() {
        return Ok(None);
    }
    Ok(load(&path)?
        .runs
        .into_iter()
        .find(|r| (r.loss_coefficient - loss_coefficient).abs() <= 1e-12))
}

/// The checks `verify` makes of every stored run: the realised COR against its target, the
/// code's peak against its own law stepped now by this build (so a change in the emulation or
/// the law shows), and the remainder against the paper's law.
pub fn verify_rows(folder: &Path, _cases: &Path) -> Result<Vec<VerifyRow>> {
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
                .map_err(|reason| anyhow::anyhow!("{}: {reason}", path.display()))?;
            let peak_error =
                (record.peak_deformation - now.peak_deformation) / now.peak_deformation;
            let time_error = (record.contact_time - now.contact_time) / now.contact_time;
            let cor_error = record.cor - record.cor_target();
            let remainder = record.attribution().remainder;
            let step_share = record.timestep / now.contact_time;
            let tolerance = Tolerance {
                cor: COR_TOLERANCE,
                peak_deformation: EMULATION_TOLERANCE,
                contact_time: step_share,
            };
            let remainder_ok = remainder.cor.abs() <= REMAINDER_TOLERANCE
                && remainder.peak_deformation.abs() <= REMAINDER_TOLERANCE;
            rows.push(VerifyRow {
                case: format!("{} η={}", record.case, record.loss_coefficient),
                method: format!("{} (stored)", record.code),
                cor_error,
                peak_deformation_error: peak_error,
                contact_time_error: time_error,
                tolerance,
                pass: cor_error.abs() <= tolerance.cor
                    && peak_error.abs() <= tolerance.peak_deformation
                    && time_error.abs() <= tolerance.contact_time
                    && remainder_ok,
            });
        }
    }
    Ok(rows)
}

/// Run `millimpact reference`.
pub fn reference_command(args: &ReferenceArgs) -> Result<String> {
    let mut case = Case::load(&args.case)?;
    if let Some(eta) = args.loss_coefficient {
        if !(0.0..1.0).contains(&eta) {
            return Err(UserError::Argument {
                option: "--loss-coefficient".into(),
                value: eta.to_string(),
                allowed: "must be in [0, 1)".into(),
            }
            .into());
        }
        case = case.with_loss_coefficient(eta);
    }
    if let Some(dt) = args.timestep
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(UserError::Argument {
            option: "--timestep".into(),
            value: dt.to_string(),
            allowed: "must be a finite number > 0 (seconds)".into(),
        }
        .into());
    }
    if let Some(0) = args.steps_per_contact {
        return Err(UserError::Argument {
            option: "--steps-per-contact".into(),
            value: "0".into(),
            allowed: "must be at least 1".into(),
        }
        .into());
    }
    if !(args.timeout.is_finite() && args.timeout > 0.0) {
        return Err(UserError::Argument {
            option: "--timeout".into(),
            value: args.timeout.to_string(),
            allowed: "must be a finite number of seconds > 0".into(),
        }
        .into());
    }
    if args.clamp && args.save {
        return Err(UserError::Argument {
            option: "--save".into(),
            value: "with --clamp".into(),
            allowed: "reference/ stores the equivalent setups only; run --clamp without --save"
                .into(),
        }
        .into());
    }
    let driver = codes::driver(args.code.name()).expect("every CodeName has a driver");
    let record = run_reference(
        driver.as_ref(),
        &case,
        args.steps_per_contact,
        args.timestep,
        args.clamp,
        Duration::from_secs_f64(args.timeout),
    )?;
    let mut text = match args.format {
        Format::Json => serde_json::to_string_pretty(&record)? + "\n",
        _ => record_table(&record),
    };
    if args.save {
        let path = save(&args.reference, &record)?;
        if args.format != Format::Json {
            text += &format!("stored in {}\n", path.display());
        }
    }
    Ok(text)
}

/// A run of a code as a table for people.
pub fn record_table(r: &ReferenceRecord) -> String {
    let mut t = report::new_table(&[
        "source",
        "COR",
        "peak deformation (m)",
        "peak force (N)",
        "contact time (s)",
    ]);
    let sci = report::sci;
    t.add_row(vec![
        format!("{} {}", r.code, r.code_version),
        sci(r.cor),
        sci(r.peak_deformation),
        sci(r.peak_force),
        sci(r.contact_time),
    ]);
    for (name, m) in [
        ("own law, stepped as the code", &r.law_at_step),
        ("own law, exact", &r.law_exact),
    ] {
        t.add_row(vec![
            name.to_string(),
            sci(m.cor),
            sci(m.peak_deformation),
            sci(m.peak_force),
            sci(m.contact_time),
        ]);
    }
    let p = &r.paper_exact;
    t.add_row(vec![
        "paper's law, exact".to_string(),
        sci(p.cor),
        sci(p.peak_deformation),
        sci(p.peak_force),
        sci(p.contact_time),
    ]);
    let a = r.attribution();
    let mut text = format!(
        "{} on {} (η = {}, target COR {:.6}{}), Δt = {} s, {} steps\n{t}\n",
        r.code,
        r.case,
        r.loss_coefficient,
        r.target_restitution,
        r.expected_restitution
            .map(|e| format!(", realisable {e:.6}"))
            .unwrap_or_default(),
        sci(r.timestep),
        r.steps
    );
    text += &format!(
        "difference from the paper's law (COR / peak / contact time): model {:+.2e} / {:+.2e} / {:+.2e}, integration {:+.2e} / {:+.2e} / {:+.2e}, remainder {:+.2e} / {:+.2e} / {:+.2e}\n",
        a.model.cor,
        a.model.peak_deformation,
        a.model.contact_time,
        a.integration.cor,
        a.integration.peak_deformation,
        a.integration.contact_time,
        a.remainder.cor,
        a.remainder.peak_deformation,
        a.remainder.contact_time
    );
    text += &format!(
        "wall time {}{}\nreproduce: {}\n",
        report::seconds(r.wall_time),
        r.loop_time
            .map(|l| format!(", the code's loop time {}", report::seconds(l)))
            .unwrap_or_default(),
        r.command
    );
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_split_adds_up_to_the_total() {
        let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("reference");
        let files = stored_files(&folder).unwrap();
        assert!(!files.is_empty(), "stored references exist");
        for path in files {
            for r in load(&path).unwrap().runs {
                let a = r.attribution();
                for (total, parts) in [
                    (
                        a.total.cor,
                        a.model.cor + a.integration.cor + a.remainder.cor,
                    ),
                    (
                        a.total.peak_deformation,
                        a.model.peak_deformation
                            + a.integration.peak_deformation
                            + a.remainder.peak_deformation,
                    ),
                    (
                        a.total.contact_time,
                        a.model.contact_time
                            + a.integration.contact_time
                            + a.remainder.contact_time,
                    ),
                ] {
                    assert!(
                        (total - parts).abs() < 1e-14,
                        "{}: {total} vs {parts}",
                        path.display()
                    );
                }
            }
        }
    }
}
