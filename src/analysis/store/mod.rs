//! Runs of the DEM codes on the equivalent setups, and their stored results in `reference/`
//! with provenance (code version, the exact input and its hash, time step, date, command).
//!
//! A stored run keeps, beside the code's figures, the code's own law as the driver read it and
//! that law integrated twice: stepped the way the code steps, and at zero step error. The
//! difference between the code and the paper's law then splits into a difference of model
//! (own law exact − paper law exact), an integration error (own law stepped − own law exact)
//! and a remainder (code − own law stepped) that nothing explains.

pub mod tangential;

/// The folder of the stored oblique runs inside a reference store:
/// `<reference>/oblique/<code>/<case>.json`, beside the cases of `<cases>/oblique/`.
pub(crate) const OBLIQUE_FOLDER: &str = "oblique";
pub mod verify;

use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use thiserror::Error;

use super::tolerance::Differences;
use crate::analysis::run::RunError;
use crate::codes::{self, CodeError, CodeName, CodeSetup, RunOptions, SetupError, run_code};
use crate::error::Blame;
use crate::model::case::Case;
use crate::model::case::CaseError;
use crate::model::exact::{self, ImpactFigures};
use crate::model::figures::{Figures, quantity};
use crate::model::law::CodeLaw;
use crate::model::scene::SceneKind;
use crate::model::trajectory::{
    CodeTrajectory, TrajectoryError, TrajectoryMetrics, trajectory_metrics,
};
use crate::output::files::write_atomic;
use crate::output::invocation::Invocation;
use crate::output::{Section, Summary, sci, seconds, signed};
use crate::solve::SolveError;
use crate::solve::dashpot::{CodeStepping, StepScheme, own_law_metrics};

/// Why a reference could not be run, read or stored, or the store not verified. Each variant
/// names the code, the file or the folder it concerns.
#[derive(Debug, Error)]
pub enum StoreError {
    /// The code's run could not be sized, or its trajectory or its own law gave no figures.
    #[error(transparent)]
    Law(#[from] CodeLawError),
    /// The code failed to run, or its output could not be read.
    #[error(transparent)]
    Code(#[from] CodeError),
    /// A file or folder could not be read.
    #[error("reading {}", path.display())]
    Read {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file is not a stored reference file.
    #[error("{}: not a reference file", path.display())]
    NotAReferenceFile {
        /// The file.
        path: PathBuf,
        /// What the JSON reader found.
        source: serde_json::Error,
    },
    /// The store's folder for a code could not be made, the lock that serialises saves not
    /// opened or taken, or the reference file not written.
    #[error("{doing} {}", path.display())]
    Io {
        /// What was being done (`creating`, `opening the lock`, `locking`, `writing`).
        doing: &'static str,
        /// The folder, lock or file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The reference file could not be encoded as JSON.
    #[error("encoding {}", path.display())]
    Encode {
        /// The reference file.
        path: PathBuf,
        /// Why.
        source: serde_json::Error,
    },
    /// The reference file holds runs of other bodies under the same case name: the user's.
    #[error(
        "--save = {}: holds runs of another `{case}` (other bodies, materials or speed; stored from `{command}`); \
         store your case under another name, or in a folder of your own with --reference DIR",
        file.display()
    )]
    ForeignRuns {
        /// The reference file.
        file: PathBuf,
        /// The case's name.
        case: String,
        /// The command that stored the other runs.
        command: String,
    },
    /// The cases' folder cannot be read: the user's.
    #[error("--cases = {}: cannot read the folder: {reason}", folder.display())]
    CasesUnreadable {
        /// The folder.
        folder: PathBuf,
        /// Why.
        reason: std::io::Error,
    },
    /// The cases' folder holds no case file: the user's.
    #[error("--cases = {}: holds no .toml case files", folder.display())]
    NoCaseFiles {
        /// The folder.
        folder: PathBuf,
    },
    /// The stored references' folder is not there: the user's.
    #[error("--reference = {}: no such folder of stored references", folder.display())]
    NoReferenceFolder {
        /// The folder.
        folder: PathBuf,
    },
    /// A case file is invalid: the user's.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// A case could not be integrated.
    #[error(transparent)]
    Run(#[from] RunError),
}

impl Blame for StoreError {
    fn is_user_error(&self) -> bool {
        match self {
            StoreError::ForeignRuns { .. }
            | StoreError::CasesUnreadable { .. }
            | StoreError::NoCaseFiles { .. }
            | StoreError::NoReferenceFolder { .. }
            | StoreError::Case(_) => true,
            StoreError::Run(e) => e.is_user_error(),
            _ => false,
        }
    }
}

/// Why a code's run could not be sized, or its trajectory or its own law gave no figures; each
/// variant names the code.
#[derive(Debug, Error)]
pub enum CodeLawError {
    /// The code's run could not be sized from its own law.
    #[error("{code}: sizing the run from the code's law")]
    Setup {
        /// The code.
        code: CodeName,
        /// Why.
        source: SetupError,
    },
    /// The code's trajectory gives no impact figures.
    #[error("{code}")]
    Trajectory {
        /// The code.
        code: CodeName,
        /// What is wrong with the trajectory.
        source: TrajectoryError,
    },
    /// The code's own law, stepped as the code steps, gives no impact figures.
    #[error("{code}: own law stepped")]
    SteppedLaw {
        /// The code.
        code: CodeName,
        /// What is wrong with the trajectory.
        source: TrajectoryError,
    },
    /// The code's own law could not be integrated at zero step error.
    #[error("{code}: its own law at zero step error")]
    OwnLaw {
        /// The code.
        code: CodeName,
        /// Why.
        source: SolveError,
    },
}

/// A run that cannot be sized or read is the code's or the solver's failure, not the input's.
impl Blame for CodeLawError {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// The equivalent setup of `case` in `code` (see [`codes::prepare`]).
pub(crate) fn prepare(
    code: CodeName,
    case: &Case,
    steps_per_contact: Option<u32>,
    timestep: Option<f64>,
    clamp_attractive: bool,
) -> Result<CodeSetup, CodeLawError> {
    codes::prepare(
        code.driver(),
        case,
        steps_per_contact,
        timestep,
        clamp_attractive,
    )
    .map_err(|source| CodeLawError::Setup { code, source })
}

/// The impact figures of a code's `trajectory`.
pub(crate) fn code_metrics(
    code: CodeName,
    trajectory: &CodeTrajectory,
) -> Result<TrajectoryMetrics, CodeLawError> {
    trajectory_metrics(trajectory).map_err(|source| CodeLawError::Trajectory { code, source })
}

/// The figures of `law` (the law of `code`) at `v0`, integrated to `rtol`: at zero step error.
pub(crate) fn own_law_exact(
    code: CodeName,
    law: &CodeLaw,
    v0: f64,
    rtol: f64,
) -> Result<TrajectoryMetrics, CodeLawError> {
    own_law_metrics(law, v0, rtol).map_err(|source| CodeLawError::OwnLaw { code, source })
}

/// The code's own law for `setup`, stepped as the code steps it at the setup's step and at
/// zero step error (rtol 1e-13).
pub(crate) fn own_law(
    code: CodeName,
    setup: &CodeSetup,
) -> Result<(CodeLaw, TrajectoryMetrics, TrajectoryMetrics), CodeLawError> {
    let driver = code.driver();
    let law = driver.law(setup);
    let stepped = driver.stepping(setup).trajectory(
        &law,
        setup.impact_velocity,
        setup.timestep,
        setup.steps,
        0.0,
    );
    let at_step =
        trajectory_metrics(&stepped).map_err(|source| CodeLawError::SteppedLaw { code, source })?;
    let exact = own_law_exact(code, &law, setup.impact_velocity, 1e-13)?;
    Ok((law, at_step, exact))
}

/// One run of one code on one case at one η.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReferenceRecord {
    /// The code.
    pub code: CodeName,
    /// Version string as the code printed it.
    pub code_version: String,
    /// Case name.
    pub case: String,
    /// The scene.
    pub scene: SceneKind,
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
    /// The code's figures, read from its trajectory as [`trajectory_metrics`] reads them (COR,
    /// peak overlap, peak normal force, contact times by overlap and by force, compression
    /// time); the force contact time and the compression time are NaN in a record stored
    /// without them.
    #[serde(flatten)]
    pub figures: TrajectoryMetrics,
    /// Process wall time, s: the code from start to exit, its start-up included.
    pub wall_time: f64,
    /// The code's own loop time, s.
    pub loop_time: Option<f64>,
    /// Wall time of the whole reference run, s: sizing it (the build's probe included, where
    /// this run made it), the code's process, reading and checking its output, and the
    /// attribution's integrations; absent from records stored without it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub whole_wall_time: Option<f64>,
    /// The law the code integrates, as the driver reads it.
    pub law: CodeLaw,
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
    /// An oblique impact's tangential half against its closed form; `None` for a normal one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential: Option<tangential::CodeTangential>,
}

/// The file `reference/<code>/<case>.json`: the runs of one code on one case, one per η.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReferenceFile {
    /// The code.
    pub code: CodeName,
    /// Case name.
    pub case: String,
    /// The runs, sorted by η.
    pub runs: Vec<ReferenceRecord>,
}

/// Relative differences of one source against another.
pub(crate) type Split = Differences;

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
        let split = |a: &TrajectoryMetrics, b: &TrajectoryMetrics| {
            Split::from_fn(|q| (a.get(q) - b.get(q)) / p.get(q))
        };
        let paper = p.metrics();
        Attribution {
            total: split(&self.figures, &paper),
            model: split(&self.law_exact, &paper),
            integration: split(&self.law_at_step, &self.law_exact),
            remainder: split(&self.figures, &self.law_at_step),
        }
    }

    /// How its code steps its law: the stored scheme, and the code's frame for the stored
    /// setup.
    pub(crate) fn stepping(&self) -> CodeStepping {
        CodeStepping {
            scheme: self.step_scheme,
            frame: self.code.driver().frame(&self.setup),
        }
    }

    /// The COR the code should realise: the documented one, or the target.
    pub fn cor_target(&self) -> f64 {
        self.expected_restitution.unwrap_or(self.target_restitution)
    }
}

/// How to run a code for a reference.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceOptions {
    /// Steps per elastic contact time (the default step when no `timestep` is given).
    pub steps_per_contact: Option<u32>,
    /// The code's time step, s, instead.
    pub timestep: Option<f64>,
    /// Let the code cut off attractive force.
    pub clamp_attractive: bool,
    /// Kill the code after this long.
    pub timeout: Duration,
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            steps_per_contact: None,
            timestep: None,
            clamp_attractive: false,
            timeout: Duration::from_secs(300),
        }
    }
}

/// Run `case` in `code` and assemble the record.
pub fn run_reference(
    code: CodeName,
    case: &Case,
    options: &ReferenceOptions,
) -> Result<ReferenceRecord, StoreError> {
    let started = std::time::Instant::now();
    let driver = code.driver();
    let setup = prepare(
        code,
        case,
        options.steps_per_contact,
        options.timestep,
        options.clamp_attractive,
    )?;
    let run_options = RunOptions {
        timeout: options.timeout,
        ..RunOptions::default()
    };
    let run = run_code(driver, &setup, &run_options)?;
    let metrics = code_metrics(code, &run.trajectory)?;
    let tangential = run.plane_motion.as_ref().and_then(|motion| {
        tangential::CodeTangential::of_run(case, &setup, &run.trajectory, metrics.cor, motion)
    });
    let (law, law_at_step, law_exact) = own_law(code, &setup)?;
    let command = Invocation::new("reference")
        .option("--code", code)
        .arg(case.path.display())
        .option("--loss-coefficient", case.loss_coefficient)
        .option_if("--timestep", options.timestep.map(|dt| format!("{dt:e}")))
        .option_if(
            "--steps-per-contact",
            options
                .steps_per_contact
                .filter(|_| options.timestep.is_none()),
        )
        .flag("--clamp", options.clamp_attractive)
        .to_string();
    Ok(ReferenceRecord {
        code,
        code_version: run.code_version,
        case: case.name.clone(),
        scene: case.scene.kind(),
        loss_coefficient: case.loss_coefficient,
        target_restitution: setup.target_restitution,
        expected_restitution: driver.expected_restitution(&setup),
        timestep: setup.timestep,
        steps: setup.steps,
        figures: metrics,
        wall_time: run.wall_time,
        loop_time: run.loop_time,
        whole_wall_time: Some(started.elapsed().as_secs_f64()),
        law,
        step_scheme: driver.step_scheme(),
        law_at_step,
        law_exact,
        paper_exact: exact::paper_impact(&case.law(), case.impact_velocity),
        input_sha256: hex(&Sha256::digest(run.input.as_bytes())),
        input: run.input,
        setup,
        date: chrono::Utc::now().to_rfc3339_opts(chrono::SecondsFormat::Secs, true),
        command,
        tangential,
    })
}

/// Bytes as lowercase hexadecimal (a SHA-256 digest as stored).
pub(crate) fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Where the runs of `code` on `case` are stored.
pub fn reference_path(folder: &Path, code: CodeName, case: &str) -> PathBuf {
    folder.join(code.name()).join(format!("{case}.json"))
}

/// Read a stored reference file.
pub fn load(path: &Path) -> Result<ReferenceFile, StoreError> {
    let text = std::fs::read_to_string(path).map_err(|source| StoreError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| StoreError::NotAReferenceFile {
        path: path.to_path_buf(),
        source,
    })
}

/// Store `record`, replacing a stored run of the same η.
pub fn save(folder: &Path, record: &ReferenceRecord) -> Result<PathBuf, StoreError> {
    // An oblique run is a store of its own, as the benchmark's runs are: the canonical store's
    // readers (its whole-ness check, `compare`) see none of it.
    let oblique_store;
    let folder = if record.setup.oblique.is_some() {
        oblique_store = folder.join(OBLIQUE_FOLDER);
        &oblique_store
    } else {
        folder
    };
    let path = reference_path(folder, record.code, &record.case);
    let dir = path.parent().unwrap_or(folder);
    let io = |doing, path: &Path| {
        let path = path.to_path_buf();
        move |source| StoreError::Io {
            doing,
            path,
            source,
        }
    };
    std::fs::create_dir_all(dir).map_err(io("creating", dir))?;
    // Saves of one record file are serialised across processes, and the file is read under the
    // lock: two saves finishing together both land, neither replaces the other's run.
    let lock_path = dir.join(format!(".{}.lock", record.case));
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&lock_path)
        .map_err(io("opening the lock", &lock_path))?;
    lock.lock().map_err(io("locking", &lock_path))?;
    let mut file = if path.exists() {
        load(&path)?
    } else {
        ReferenceFile {
            code: record.code,
            case: record.case.clone(),
            runs: Vec::new(),
        }
    };
    if let Some(other) = file
        .runs
        .iter()
        .find(|r| !same_bodies(&r.setup, &record.setup))
    {
        return Err(StoreError::ForeignRuns {
            file: path,
            case: record.case.clone(),
            command: other.command.clone(),
        });
    }
    file.runs
        .retain(|r| (r.loss_coefficient - record.loss_coefficient).abs() > 1e-12);
    file.runs.push(record.clone());
    file.runs
        .sort_by(|a, b| a.loss_coefficient.total_cmp(&b.loss_coefficient));
    let text = serde_json::to_string_pretty(&file).map_err(|source| StoreError::Encode {
        path: path.clone(),
        source,
    })? + "\n";
    write_atomic(&path, text.as_bytes()).map_err(io("writing", &path))?;
    drop(lock);
    Ok(path)
}

/// Whether two setups are of the same bodies, materials and speed (they may differ in η, the
/// time step and the run length). Exact: both come from a case file's numbers by the same
/// arithmetic.
#[allow(clippy::float_cmp)]
fn same_bodies(a: &CodeSetup, b: &CodeSetup) -> bool {
    a.scene == b.scene
        && a.sphere == b.sphere
        && a.other_sphere == b.other_sphere
        && a.plate_material == b.plate_material
        && a.impact_velocity == b.impact_velocity
}

/// The files in `dir` whose extension is `extension`, unsorted.
pub(crate) fn files_in(dir: &Path, extension: &str) -> std::io::Result<Vec<PathBuf>> {
    Ok(std::fs::read_dir(dir)?
        .flatten()
        .map(|entry| entry.path())
        .filter(|p| p.extension().is_some_and(|x| x == extension))
        .collect())
}

/// Every stored reference file under `folder`, sorted.
pub(crate) fn stored_files(folder: &Path) -> Result<Vec<PathBuf>, StoreError> {
    let mut files: Vec<PathBuf> = CodeName::ALL
        .iter()
        .flat_map(|code| files_in(&folder.join(code.name()), "json").unwrap_or_default())
        .collect();
    files.sort();
    Ok(files)
}

/// The stored run of `code` on `case` at η, if any.
pub fn find_stored(
    folder: &Path,
    code: CodeName,
    case: &str,
    loss_coefficient: f64,
) -> Result<Option<ReferenceRecord>, StoreError> {
    let path = reference_path(folder, code, case);
    if !path.exists() {
        return Ok(None);
    }
    Ok(load(&path)?
        .runs
        .into_iter()
        .find(|r| (r.loss_coefficient - loss_coefficient).abs() <= 1e-12))
}

/// The figures a record's table and CSV row show, and those of its exact integrations that
/// `verify` recomputes: COR, peak overlap, peak normal force, contact time by overlap.
pub(crate) type Shown = Figures<
    f64,
    { quantity::COR | quantity::PEAK_DEFORMATION | quantity::PEAK_FORCE | quantity::CONTACT_TIME },
>;

/// One record as a CSV row: its figures and the split of its COR difference from the paper's
/// law.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RecordRow {
    /// The code.
    pub code: CodeName,
    /// Version string.
    pub code_version: String,
    /// Case name.
    pub case: String,
    /// η.
    pub loss_coefficient: f64,
    /// The COR asked of the code.
    pub target_restitution: f64,
    /// Time step, s.
    pub timestep: f64,
    /// COR, peak overlap (m), peak normal force (N), contact time by overlap (s).
    #[serde(flatten)]
    pub figures: Shown,
    /// Relative COR difference from the paper's law: the model's part.
    pub model_cor: f64,
    /// The integration's part.
    pub integration_cor: f64,
    /// What nothing explains.
    pub remainder_cor: f64,
    /// Process wall time, s.
    pub wall_time: f64,
    /// The code's own loop time, s.
    pub loop_time: Option<f64>,
    /// Wall time of the whole run (sizing and probe included), s; empty in a record stored
    /// without it.
    pub whole_wall_time: Option<f64>,
    /// An oblique impact's velocity along the plane after it, m/s; empty for a normal one.
    pub tangential_velocity_out: Option<f64>,
    /// Its spin after it, rad/s.
    pub angular_velocity_out: Option<f64>,
    /// Its change of velocity along the plane against the closed form's, relative.
    pub tangential_change_error: Option<f64>,
    /// Its change of spin against the closed form's, relative.
    pub spin_change_error: Option<f64>,
}

impl Summary for ReferenceRecord {
    type Record = RecordRow;

    fn records(&self) -> Vec<RecordRow> {
        let a = self.attribution();
        vec![RecordRow {
            code: self.code,
            code_version: self.code_version.clone(),
            case: self.case.clone(),
            loss_coefficient: self.loss_coefficient,
            target_restitution: self.target_restitution,
            timestep: self.timestep,
            figures: self.figures.select(),
            model_cor: a.model.cor,
            integration_cor: a.integration.cor,
            remainder_cor: a.remainder.cor,
            wall_time: self.wall_time,
            loop_time: self.loop_time,
            whole_wall_time: self.whole_wall_time,
            tangential_velocity_out: self.tangential.as_ref().map(|t| t.tangential_velocity_out),
            angular_velocity_out: self.tangential.as_ref().map(|t| t.angular_velocity_out),
            tangential_change_error: self
                .tangential
                .as_ref()
                .and_then(|t| t.tangential_change_error),
            spin_change_error: self.tangential.as_ref().and_then(|t| t.spin_change_error),
        }]
    }

    fn sections(&self) -> Vec<Section> {
        let r = self;
        let mut t = Section::new(
            Some(format!(
                "{} on {} (η = {}, target COR {:.6}{}), Δt = {} s, {} steps",
                r.code,
                r.case,
                r.loss_coefficient,
                r.target_restitution,
                r.expected_restitution
                    .map(|e| format!(", realisable {e:.6}"))
                    .unwrap_or_default(),
                sci(r.timestep),
                r.steps
            )),
            &[
                "source",
                "COR",
                "peak deformation (m)",
                "peak force (N)",
                "contact time (s)",
            ],
        );
        let paper = r.paper_exact.metrics();
        for (name, m) in [
            (format!("{} {}", r.code, r.code_version), &r.figures),
            ("own law, stepped as the code".to_string(), &r.law_at_step),
            ("own law, exact".to_string(), &r.law_exact),
            ("paper's law, exact".to_string(), &paper),
        ] {
            let shown: Shown = m.select();
            t.rows.push(
                std::iter::once(name)
                    .chain(shown.iter().map(|(_, x)| sci(*x)))
                    .collect(),
            );
        }
        let a = r.attribution();
        let split = |s: &Split| {
            s.iter()
                .map(|(_, x)| signed(*x))
                .collect::<Vec<_>>()
                .join(" / ")
        };
        t.notes = vec![
            format!(
                "difference from the paper's law (COR / peak / contact time): model {}, integration {}, remainder {}",
                split(&a.model),
                split(&a.integration),
                split(&a.remainder)
            ),
            format!(
                "wall time {}{}{}",
                seconds(r.wall_time),
                r.loop_time
                    .map(|l| format!(", the code's loop time {}", seconds(l)))
                    .unwrap_or_default(),
                r.whole_wall_time
                    .map(|w| format!(
                        ", the whole run {} (sizing, probe and reading included)",
                        seconds(w)
                    ))
                    .unwrap_or_default()
            ),
            format!("reproduce: {}", r.command),
        ];
        let mut sections = vec![t];
        if let Some(tan) = &r.tangential {
            let mut s = Section::new(
                Some(format!(
                    "{} on {}, the tangential half: v_t = {} m/s, ω = {} rad/s, μ = {}",
                    r.code,
                    r.case,
                    tan.tangential_velocity,
                    tan.angular_velocity,
                    tan.friction_coefficient
                )),
                &[
                    "source",
                    "tangential velocity out (m/s)",
                    "angular velocity out (rad/s)",
                ],
            );
            s.rows.push(vec![
                format!("{} {}", r.code, r.code_version),
                sci(tan.tangential_velocity_out),
                sci(tan.angular_velocity_out),
            ]);
            if let (Some(kind), Some(v), Some(w)) = (
                tan.closed_form,
                tan.tangential_velocity_closed_form,
                tan.angular_velocity_closed_form,
            ) {
                s.rows.push(vec![
                    format!("closed form ({})", kind.describe()),
                    sci(v),
                    sci(w),
                ]);
            }
            if let (Some(v), Some(w)) = (
                tan.tangential_velocity_case_law,
                tan.angular_velocity_case_law,
            ) {
                s.rows.push(vec![
                    "the case's law (paper's normal law), dopri5".to_string(),
                    sci(v),
                    sci(w),
                ]);
            }
            s.notes = vec![tan.verdict()];
            sections.push(s);
        }
        sections
    }
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
                for (q, total) in a.total.iter() {
                    let parts = a.model.get(q) + a.integration.get(q) + a.remainder.get(q);
                    assert!(
                        (total - parts).abs() < 1e-14,
                        "{} {q}: {total} vs {parts}",
                        path.display()
                    );
                }
            }
        }
    }
}
