//! `verify`: every case by every method against the closed forms, and every stored DEM-code
//! reference against the code's own law re-stepped by this build.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::analysis::benchmark::{CHUNG_OOI, STEPS_PER_CONTACT, STORED_FOLDER};
use crate::analysis::run::run_case;
use crate::analysis::source::Source;
use crate::analysis::store::{
    OBLIQUE_FOLDER, ReferenceRecord, Shown, StoreError, files_in, hex, load, stored_files,
};
use crate::analysis::tolerance::{Differences, Tolerance};
use crate::codes::{CodeName, prepare_with};
use crate::error::Chain;
use crate::model::case::Case;
use crate::model::exact;
use crate::model::figures::{Figures, Quantity};
use crate::model::trajectory::trajectory_metrics;
use crate::output::{Section, Summary, signed};
use crate::solve::Method;
use crate::solve::dashpot::own_law_metrics;
use crate::solve::paper::Settings;
use sha2::{Digest, Sha256};

/// Bound on a stored run's difference from its code's own law re-stepped now as the code
/// steps (COR, peak deformation, contact time; relative). Measured over the shipped store
/// (`verify --format json`, rows `own_law_stepped`): at most 2.0e-10 in COR, 7.9e-11 in
/// contact time and 1.7e-9 in peak deformation (LIGGGHTS' rod at η = 0.7: LIGGGHTS prints its
/// trajectory to 15 digits and its peak overlap is a difference of two positions); the gate
/// sits at three times the largest, so that a record perturbed by 1e-8 fails.
pub const REMAINDER_TOLERANCE: f64 = 5e-9;
/// Bound on the COR the code's own law realises at zero step error against the COR asked of
/// the code (absolute). Each driver's law realises its target to about 1e-11 (the drivers
/// invert LAMMPS' Tsuji fit and YADE's Thornton fit); dropping a compensation moves it by
/// 1e-4 or more.
pub const TARGET_TOLERANCE: f64 = 1e-9;
/// Bound on the relative difference between a stored record's exact figures (its own law's,
/// the paper law's) and the same figures computed now: both are integrations at tolerances
/// near 1e-13, so anything above this is a changed record or a changed law.
pub(crate) const RECOMPUTE_TOLERANCE: f64 = 1e-9;
/// The η at which the shipped store holds a record of every code on every canonical case.
pub(crate) const STORED_LOSS_COEFFICIENTS: [f64; 3] = [0.0, 0.35, 0.7];
/// The canonical cases the shipped store covers.
pub(crate) const CANONICAL_CASES: [&str; 3] = ["ball_plate", "ball_ball", "rod_end"];

/// What a row of `verify` checks, and so what its numbers are.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Check {
    /// A method against the closed forms: relative errors of COR, peak deformation and
    /// contact time.
    ClosedForm,
    /// A stored run against its code's own law re-stepped now, by this build, as the code
    /// steps: relative differences of COR, peak deformation and contact time (the unexplained
    /// remainder).
    OwnLawStepped,
    /// The code's own law at zero step error against the COR asked of the code: an absolute
    /// difference of COR (the driver's compensation of the code's damping fit).
    Target,
    /// A stored record against what the case file and this build produce now: the equivalent
    /// setup, the rendered input and its hash, the η label, the laws' exact figures.
    Provenance,
    /// The store as a whole: every expected record present, no file that is not one.
    Store,
    /// A stored oblique run's motion after the impact against Coulomb's closed form, taken
    /// again now at the run's stored COR: its change errors as stored and within what is
    /// allowed.
    Tangential,
}

impl Check {
    /// How the check reads in the table.
    pub(crate) fn label(self) -> &'static str {
        match self {
            Check::ClosedForm => "vs closed form (rel)",
            Check::OwnLawStepped => "vs own law stepped now (rel)",
            Check::Target => "own law exact vs target (abs)",
            Check::Provenance => "provenance",
            Check::Store => "store",
            Check::Tangential => "tangential vs closed form",
        }
    }
}

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
    /// What the row checks (and so what its differences are: see [`Check`]).
    pub check: Check,
    /// The differences checked; NaN where the check has no such figure.
    pub differences: Differences,
    /// What they must stay within (same units as the differences).
    pub tolerance: Tolerance,
    /// Whether every check of the row holds.
    pub pass: bool,
    /// What disagrees, by name, and how to regenerate the record.
    pub detail: Option<String>,
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
pub(crate) fn case_files(dir: &Path) -> Result<Vec<PathBuf>, StoreError> {
    let mut files = files_in(dir, "toml").map_err(|reason| StoreError::CasesUnreadable {
        folder: dir.to_path_buf(),
        reason,
    })?;
    files.sort();
    if files.is_empty() {
        return Err(StoreError::NoCaseFiles {
            folder: dir.to_path_buf(),
        });
    }
    Ok(files)
}

/// Check every case in `dir` by every integrating method against the closed forms.
pub(crate) fn verify_cases(dir: &Path) -> Result<Vec<VerifyRow>, StoreError> {
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
                Tolerance::for_method(method, report.timestep, report.exact.figures.contact_time);
            let differences = Differences {
                cor: report.error.cor,
                peak_deformation: report.error.peak_deformation,
                contact_time: report.error.contact_time,
                ..Differences::default()
            };
            rows.push(VerifyRow {
                stored: false,
                pass: tolerance.admits(&differences),
                ..finding(
                    &case.name,
                    None,
                    Source::Method(method),
                    Check::ClosedForm,
                    None,
                )
                .measured(differences, tolerance)
            });
        }
    }
    Ok(rows)
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b) / b
}

const NOT_APPLICABLE: f64 = f64::NAN;

/// A row of a stored record or of the store that is not a comparison of figures.
fn finding(
    case: &str,
    loss_coefficient: Option<f64>,
    source: Source,
    check: Check,
    detail: Option<String>,
) -> VerifyRow {
    VerifyRow {
        case: case.to_string(),
        loss_coefficient,
        source,
        stored: true,
        check,
        differences: Differences::splat(NOT_APPLICABLE),
        tolerance: Tolerance::splat(NOT_APPLICABLE),
        pass: detail.is_none(),
        detail,
    }
}

impl VerifyRow {
    /// The row with the `differences` it checked and their `tolerance`.
    fn measured(self, differences: Differences, tolerance: Tolerance) -> VerifyRow {
        VerifyRow {
            differences,
            tolerance,
            ..self
        }
    }
}

/// Whether a stored exact figure set agrees with the same set computed now, within
/// [`RECOMPUTE_TOLERANCE`] on each figure a record shows (COR, peak deformation, peak force,
/// contact time).
fn recomputed_agrees<const P: u8>(stored: &Figures<f64, P>, now: &Figures<f64, P>) -> bool {
    let (stored, now): (Shown, Shown) = (stored.select(), now.select());
    stored.iter().all(|(q, &x)| {
        let d = relative(x, *now.get(q));
        !(d.is_nan() || d.abs() > RECOMPUTE_TOLERANCE)
    })
}

/// What in `record` differs from what its case file in `cases` and this build produce now,
/// each item by name; empty when the record is what the case makes.
fn provenance(record: &ReferenceRecord, cases: &Path) -> Vec<String> {
    let mut found = Vec::new();
    let hash = hex(&Sha256::digest(record.input.as_bytes()));
    if hash != record.input_sha256 {
        found.push("input_sha256 is not the hash of input".to_string());
    }
    let eta_of_target = exact::loss_coefficient(record.target_restitution);
    if (eta_of_target - record.loss_coefficient).abs() > 1e-12 {
        found.push(format!(
            "loss_coefficient {} is not the η of target_restitution {} ({eta_of_target})",
            record.loss_coefficient, record.target_restitution
        ));
    }
    let path = cases.join(format!("{}.toml", record.case));
    let case = match Case::load(&path) {
        Ok(case) => case.with_loss_coefficient(record.loss_coefficient),
        Err(e) => {
            found.push(format!("its case file: {e}"));
            return found;
        }
    };
    let driver = record.code.driver();
    let steps_per_contact = None;
    // The record's own conventions (those its build was probed to have, or the build's
    // measured ones for a record made before the probe): checkable without the binary.
    match prepare_with(
        driver,
        &case,
        steps_per_contact,
        Some(record.timestep),
        record.setup.clamp_attractive,
        record.setup.conventions,
    ) {
        Ok(mut now) => {
            // The step is the record's own; the rest of the setup must be the case's now.
            now.timestep = record.setup.timestep;
            if now != record.setup {
                found.push(format!(
                    "setup differs from the equivalent setup of {} now",
                    path.display()
                ));
            } else {
                match driver.render(&now) {
                    Ok(input) if input.text != record.input => {
                        found.push("input differs from the driver's rendering now".to_string())
                    }
                    Ok(_) => {}
                    Err(e) => found.push(format!("the driver cannot render it now: {e}")),
                }
            }
            if !driver.law(&now).agrees_with(&record.law, 1e-12) {
                found.push("law differs from the driver's law for this setup now".to_string());
            }
        }
        Err(e) => found.push(format!("cannot set it up now: {e}")),
    }
    match own_law_metrics(&record.law, record.setup.impact_velocity, 1e-13) {
        Ok(m) => {
            if !recomputed_agrees(&record.law_exact, &m) {
                found.push("law_exact differs from its law integrated now".to_string());
            }
        }
        Err(e) => found.push(format!("its law cannot be integrated now: {e}")),
    }
    let paper = exact::paper_impact(&case.law(), case.impact_velocity);
    if !recomputed_agrees(&record.paper_exact, &paper) {
        found.push(format!(
            "paper_exact differs from the closed forms of {} now",
            path.display()
        ));
    }
    found
}

/// The checks of every stored run in `folder`, against the case files in `cases`:
///
/// - provenance: the record is what its case file and this build produce now (an edited case
///   makes its records stale);
/// - the run against its code's own law re-stepped now as the code steps, to
///   [`REMAINDER_TOLERANCE`];
/// - the code's own law against the COR asked of it, to [`TARGET_TOLERANCE`];
/// - the store as a whole: a record for every code on every canonical case at every η of
///   `STORED_LOSS_COEFFICIENTS` (for the canonical cases present in `cases`), and no other
///   file. Records are the `*.json` files directly in `folder/<code>/`; other files there (the
///   conventions notes, probe inputs) are not records.
pub(crate) fn verify_stored(folder: &Path, cases: &Path) -> Result<Vec<VerifyRow>, StoreError> {
    if !folder.is_dir() {
        return Err(StoreError::NoReferenceFolder {
            folder: folder.to_path_buf(),
        });
    }
    let expected: Vec<Expected> = CANONICAL_CASES
        .iter()
        .map(|&case| {
            (
                case,
                STORED_LOSS_COEFFICIENTS.to_vec(),
                CodeName::ALL.to_vec(),
            )
        })
        .collect();
    check_store(folder, cases, &expected, "", "")
}

/// The checks of the stored runs of Chung & Ooi's benchmark, `folder`
/// (`<reference>/benchmarks`) against the benchmark's cases in `cases` (`<cases>/benchmarks`),
/// as [`verify_stored`] checks the canonical store: each run's provenance, its own law
/// re-stepped now, its law against its target, and the store as a whole (a run of every code
/// on every benchmark case at every η the benchmark reads, `PublishedImpact::loss_coefficients`).
/// A folder not there is a store missing every run.
pub(crate) fn verify_benchmark_store(
    folder: &Path,
    cases: &Path,
) -> Result<Vec<VerifyRow>, StoreError> {
    let expected: Vec<Expected> = CHUNG_OOI
        .iter()
        .map(|impact| {
            (
                impact.case,
                impact.loss_coefficients(),
                CodeName::ALL.to_vec(),
            )
        })
        .collect();
    // A stored run's command holds its step already; a run to make needs it given.
    let save_options = format!(" --reference {}", folder.display());
    let make_options = format!(" --steps-per-contact {STEPS_PER_CONTACT}{save_options}");
    check_store(folder, cases, &expected, &make_options, &save_options)
}

/// The checks of the stored oblique runs, `folder` (`<reference>/oblique`), against the
/// oblique cases in `cases` (`<cases>/oblique`), as [`verify_stored`] checks the canonical
/// store, and each run's motion after the impact against Coulomb's closed form
/// ([`Check::Tangential`]): a run, at the case's own η, of every ball-on-plate case there by
/// every build that renders it (one that runs oblique impacts,
/// [`crate::codes::CodeDriver::runs_oblique`], and has the case's tangential law). A record
/// regenerates into `reference` (a save files an oblique run under `oblique/` itself).
pub(crate) fn verify_oblique_store(
    reference: &Path,
    cases: &Path,
) -> Result<Vec<VerifyRow>, StoreError> {
    let folder = reference.join(OBLIQUE_FOLDER);
    let mut held = Vec::new();
    for path in files_in(cases, "toml").map_err(|source| StoreError::Read {
        path: cases.to_path_buf(),
        source,
    })? {
        // A case that does not read is the case check's finding, not the store's.
        let Ok(case) = Case::load(&path) else {
            continue;
        };
        if case.scene.kind() != crate::model::scene::SceneKind::BallPlate || case.oblique.is_none()
        {
            continue;
        }
        let renders = |code: &CodeName| {
            let driver = code.driver();
            driver.runs_oblique()
                && prepare_with(driver, &case, Some(STEPS_PER_CONTACT), None, false, None)
                    .is_ok_and(|setup| driver.render(&setup).is_ok())
        };
        let codes = CodeName::ALL.iter().copied().filter(renders).collect();
        held.push((case.name.clone(), case.loss_coefficient, codes));
    }
    let expected: Vec<Expected> = held
        .iter()
        .map(|(name, eta, codes)| (name.as_str(), vec![*eta], Vec::clone(codes)))
        .collect();
    let save_options = format!(" --reference {}", reference.display());
    let make_options = format!(" --steps-per-contact {STEPS_PER_CONTACT}{save_options}");
    check_store(&folder, cases, &expected, &make_options, &save_options)
}

/// A case a store is expected to hold: its name, the η of its runs and the builds that run it.
type Expected<'a> = (&'a str, Vec<f64>, Vec<CodeName>);

/// The checks of the store in `folder` against the cases in `cases`: every record in it, and a
/// record of every code on each `expected` case (present in `cases`) at each of its η.
/// `make_options` follow `--save` in the command that makes a missing record, `save_options`
/// in the one that regenerates a stored record (its stored command, which holds its step).
fn check_store(
    folder: &Path,
    cases: &Path,
    expected: &[Expected],
    make_options: &str,
    save_options: &str,
) -> Result<Vec<VerifyRow>, StoreError> {
    let mut rows = Vec::new();
    let mut present = Vec::new();
    for path in stored_files(folder)? {
        let code = path
            .parent()
            .and_then(|d| d.file_name())
            .and_then(|n| CodeName::from_name(&n.to_string_lossy()));
        let Some(code) = code else { continue };
        check_stored_file(&path, code, cases, save_options, &mut rows, &mut present);
    }
    rows.extend(missing_runs(expected, cases, &present, make_options));
    let strays = if folder.is_dir() {
        stray_files(folder)?
    } else {
        Vec::new()
    };
    for extra in strays {
        rows.push(finding(
            &extra.display().to_string(),
            None,
            Source::Code(CodeName::ALL[0]),
            Check::Store,
            Some(format!(
                "{} is not a record of a known code (records are reference/<code>/<case>.json)",
                extra.display()
            )),
        ));
    }
    Ok(rows)
}

/// The checks of the record file at `path`, filed under `code`: that it loads, holds runs of
/// that code on its own case, has its case file in `cases`, and each run's checks
/// ([`check_stored_run`]); each run's code, case and η is added to `present`.
fn check_stored_file(
    path: &Path,
    code: CodeName,
    cases: &Path,
    save_options: &str,
    rows: &mut Vec<VerifyRow>,
    present: &mut Vec<(CodeName, String, f64)>,
) {
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let store_finding =
        |detail: String| finding(&name, None, Source::Code(code), Check::Store, Some(detail));
    let file = match load(path) {
        Ok(file) => file,
        Err(e) => {
            rows.push(store_finding(format!("{}: {}", path.display(), Chain(&e))));
            return;
        }
    };
    if file.code != code || file.case != name {
        rows.push(store_finding(format!(
            "{} holds {} on {}, not {code} on {name}",
            path.display(),
            file.code,
            file.case
        )));
        return;
    }
    if file.runs.is_empty() {
        rows.push(store_finding(format!("{} holds no runs", path.display())));
    }
    if !cases.join(format!("{name}.toml")).is_file() {
        rows.push(store_finding(format!(
            "{} has no case file {name}.toml in {}",
            path.display(),
            cases.display()
        )));
        return;
    }
    for record in &file.runs {
        present.push((record.code, record.case.clone(), record.loss_coefficient));
        if record.code != code || record.case != name {
            rows.push(finding(
                &name,
                Some(record.loss_coefficient),
                Source::Code(record.code),
                Check::Store,
                Some(format!(
                    "a run of {} on {} filed under {}",
                    record.code,
                    record.case,
                    path.display()
                )),
            ));
            continue;
        }
        check_stored_run(record, &name, cases, save_options, rows);
    }
}

/// The checks of one stored run of the case `name`: its provenance against the case file and
/// this build, its own law re-stepped now against its stored figures, and its law against the
/// COR it was asked for.
fn check_stored_run(
    record: &ReferenceRecord,
    name: &str,
    cases: &Path,
    save_options: &str,
    rows: &mut Vec<VerifyRow>,
) {
    let eta = Some(record.loss_coefficient);
    let source = Source::Code(record.code);
    let regenerate = format!("{} --save{save_options}", record.command);
    let stale = provenance(record, cases);
    rows.push(finding(
        name,
        eta,
        source,
        Check::Provenance,
        (!stale.is_empty())
            .then(|| format!("stale: {}; regenerate: {regenerate}", stale.join("; "))),
    ));
    if record.steps > MAX_STORED_STEPS {
        rows.push(finding(
            name,
            eta,
            source,
            Check::OwnLawStepped,
            Some(format!(
                "steps = {} is above the {MAX_STORED_STEPS} a stored run may have",
                record.steps
            )),
        ));
        return;
    }
    rows.push(own_law_stepped_row(record, name, &regenerate));
    rows.push(target_row(record, name));
    if record.setup.oblique.is_some() {
        rows.push(finding(
            name,
            eta,
            source,
            Check::Tangential,
            tangential_finding(record, cases, &regenerate),
        ));
    }
}

/// What is wrong with a stored oblique run's tangential half, if anything: none stored, a
/// case that does not read, change errors that are not those of the closed form taken again
/// now at the run's COR (to 1e-9), or a miss beyond what is allowed.
fn tangential_finding(record: &ReferenceRecord, cases: &Path, regenerate: &str) -> Option<String> {
    let Some(stored) = &record.tangential else {
        return Some(format!(
            "no tangential motion stored; regenerate: {regenerate}"
        ));
    };
    let path = cases.join(format!("{}.toml", record.case));
    let case = match Case::load(&path) {
        Ok(case) => case.with_loss_coefficient(record.loss_coefficient),
        Err(e) => return Some(format!("its case file: {e}")),
    };
    let Some(now) = stored.retaken(&case, &record.setup, record.figures.cor) else {
        return Some("the case has no tangential half now".to_string());
    };
    let differs = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() > 1e-9 || a.is_nan() != b.is_nan(),
        (a, b) => a.is_some() != b.is_some(),
    };
    if differs(stored.tangential_change_error, now.tangential_change_error)
        || differs(stored.spin_change_error, now.spin_change_error)
        || stored.closed_form != now.closed_form
    {
        return Some(format!(
            "stored change errors {:?} and {:?} are not the closed form's now ({:?} and {:?}); regenerate: {regenerate}",
            stored.tangential_change_error,
            stored.spin_change_error,
            now.tangential_change_error,
            now.spin_change_error
        ));
    }
    now.missed().then(|| now.verdict())
}

/// The stored run's figures against its own law stepped now as the code steps, each within
/// [`REMAINDER_TOLERANCE`]; a failure says how to regenerate the run.
fn own_law_stepped_row(record: &ReferenceRecord, name: &str, regenerate: &str) -> VerifyRow {
    let eta = Some(record.loss_coefficient);
    let source = Source::Code(record.code);
    let stepped = record.stepping().trajectory(
        &record.law,
        record.setup.impact_velocity,
        record.timestep,
        record.steps,
        0.0,
    );
    let now = match trajectory_metrics(&stepped) {
        Ok(now) => now,
        Err(e) => {
            return finding(
                name,
                eta,
                source,
                Check::OwnLawStepped,
                Some(format!("own law stepped now: {e}")),
            );
        }
    };
    let differences = Differences::from_fn(|q| relative(*record.figures.get(q), *now.get(q)));
    let tolerance = Tolerance::splat(REMAINDER_TOLERANCE);
    // The figures the table has no column for are held to the same bound; one
    // that fails is named with its difference in the row's detail.
    let unshown: Vec<String> = [
        (Quantity::PeakForce, "peak force"),
        (Quantity::ForceContactTime, "contact time by force"),
        (Quantity::CompressionTime, "compression time"),
    ]
    .into_iter()
    .filter_map(|(q, figure)| {
        let stored = *record.figures.get(q);
        let stepped = *now.get(q);
        if stored.is_nan() {
            Some(format!("{figure} not stored"))
        } else {
            let d = relative(stored, stepped);
            (d.is_nan() || d.abs() > REMAINDER_TOLERANCE)
                .then(|| format!("{figure} {d:+.2e} (allowed {REMAINDER_TOLERANCE:.1e})"))
        }
    })
    .collect();
    let pass = tolerance.admits(&differences) && unshown.is_empty();
    let detail = (!pass).then(|| {
        let mut detail = unshown.join("; ");
        if !detail.is_empty() {
            detail += "; ";
        }
        detail + &format!("regenerate: {regenerate}")
    });
    finding(name, eta, source, Check::OwnLawStepped, detail).measured(differences, tolerance)
}

/// The COR the stored run's own law realises, exactly, against the COR the code was asked for,
/// within [`TARGET_TOLERANCE`].
fn target_row(record: &ReferenceRecord, name: &str) -> VerifyRow {
    let realised = own_law_metrics(&record.law, record.setup.impact_velocity, 1e-13)
        .map(|m| m.cor)
        .unwrap_or(f64::NAN);
    let differences = Differences {
        cor: realised - record.cor_target(),
        ..Differences::splat(NOT_APPLICABLE)
    };
    let pass = differences.cor.abs() <= TARGET_TOLERANCE;
    let detail = (!pass).then(|| {
        format!(
            "its own law realises {realised}, the code was asked for {}",
            record.cor_target()
        )
    });
    let tolerance = Tolerance {
        cor: TARGET_TOLERANCE,
        ..Tolerance::splat(NOT_APPLICABLE)
    };
    let eta = Some(record.loss_coefficient);
    finding(name, eta, Source::Code(record.code), Check::Target, detail)
        .measured(differences, tolerance)
}

/// A finding for each run of every code on each `expected` case (present in `cases`) at each
/// of its η that the store does not hold, with the command that makes it.
fn missing_runs(
    expected: &[Expected],
    cases: &Path,
    present: &[(CodeName, String, f64)],
    make_options: &str,
) -> Vec<VerifyRow> {
    let mut rows = Vec::new();
    for (case, etas, codes) in expected {
        let case = *case;
        if !cases.join(format!("{case}.toml")).is_file() {
            continue;
        }
        for &code in codes {
            for &eta in etas {
                let held = present
                    .iter()
                    .any(|(c, n, e)| *c == code && n == case && (e - eta).abs() <= 1e-12);
                if !held {
                    rows.push(finding(
                        case,
                        Some(eta),
                        Source::Code(code),
                        Check::Store,
                        Some(format!(
                            "no stored run; make it: millimpact reference --code {code} {}/{case}.toml --loss-coefficient {eta} --save{make_options}",
                            cases.display()
                        )),
                    ));
                }
            }
        }
    }
    rows
}

/// Most steps a stored run may claim before it is re-stepped (10⁷: a thousand times the
/// finest resolution the harness stores).
pub(crate) const MAX_STORED_STEPS: u64 = 10_000_000;

/// JSON files in `folder` that are not records: directly in `folder`, or in a folder that is
/// not a known code's.
fn stray_files(folder: &Path) -> Result<Vec<PathBuf>, StoreError> {
    let read = |source| StoreError::Read {
        path: folder.to_path_buf(),
        source,
    };
    let mut out: Vec<PathBuf> = files_in(folder, "json").map_err(read)?;
    out.retain(|p| p.is_file());
    for entry in std::fs::read_dir(folder).map_err(read)?.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        if path.is_dir() && CodeName::from_name(&name).is_none() {
            out.extend(files_in(&path, "json").unwrap_or_default());
        }
    }
    out.sort();
    Ok(out)
}

/// `verify`: the cases in `cases` and the stored references in `reference`, and, where `cases`
/// holds the benchmark's cases (`benchmarks/`), the stored benchmark runs in
/// `reference/benchmarks/`.
pub fn verify(cases: &Path, reference: &Path) -> Result<VerifyReport, StoreError> {
    let mut rows = verify_cases(cases)?;
    rows.extend(verify_stored(reference, cases)?);
    let oblique_cases = cases.join(OBLIQUE_FOLDER);
    if oblique_cases.is_dir() {
        rows.extend(verify_oblique_store(reference, &oblique_cases)?);
    }
    let benchmark_cases = cases.join(STORED_FOLDER);
    if benchmark_cases.is_dir() {
        rows.extend(verify_benchmark_store(
            &reference.join(STORED_FOLDER),
            &benchmark_cases,
        )?);
    }
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
    /// What the row checks.
    pub check: Check,
    /// The differences checked (`cor_error`, `peak_deformation_error`, `contact_time_error`).
    #[serde(flatten, serialize_with = "crate::model::figures::suffix::error")]
    pub differences: Differences,
    /// What they must stay within (`cor_tolerance`, …).
    #[serde(flatten, serialize_with = "crate::model::figures::suffix::tolerance")]
    pub tolerance: Tolerance,
    /// Whether every check of the row holds.
    pub pass: bool,
    /// What disagrees, if anything.
    pub detail: Option<String>,
}

/// A difference or a tolerance as a cell: `—` where the check has no such figure.
fn cell(x: f64, text: impl Fn(f64) -> String) -> String {
    if x.is_nan() {
        "—".to_string()
    } else {
        text(x)
    }
}

impl Summary for VerifyReport {
    type Record = VerifyRecord;

    /// The case, the source and the check.
    fn key_columns(&self) -> usize {
        3
    }

    fn records(&self) -> Vec<VerifyRecord> {
        self.rows
            .iter()
            .map(|r| VerifyRecord {
                case: r.case.clone(),
                loss_coefficient: r.loss_coefficient,
                source_kind: r.source.kind(),
                source: r.source.name(),
                stored: r.stored,
                check: r.check,
                differences: r.differences,
                tolerance: r.tolerance,
                pass: r.pass,
                detail: r.detail.clone(),
            })
            .collect()
    }

    fn sections(&self) -> Vec<Section> {
        let mut t = Section::new(
            None,
            &[
                "case",
                "source",
                "check",
                "COR",
                "peak",
                "contact time",
                "tolerance (COR / peak / time)",
                "",
            ],
        );
        let tolerance = |x: f64| cell(x, |v| format!("{v:.1e}"));
        for r in &self.rows {
            let mut row = vec![
                match r.loss_coefficient {
                    Some(eta) => format!("{} η={eta}", r.case),
                    None => r.case.clone(),
                },
                if r.stored {
                    format!("{} (stored)", r.source)
                } else {
                    r.source.to_string()
                },
                r.check.label().to_string(),
            ];
            row.extend(r.differences.iter().map(|(_, &d)| cell(d, signed)));
            row.push(
                r.tolerance
                    .iter()
                    .map(|(_, &x)| tolerance(x))
                    .collect::<Vec<_>>()
                    .join(" / "),
            );
            row.push(if r.pass { "ok" } else { "FAIL" }.to_string());
            t.rows.push(row);
        }
        let failed = self.failed();
        t.notes.push(format!(
            "{} checks, {} passed, {} failed",
            self.rows.len(),
            self.rows.len() - failed,
            failed
        ));
        for r in self.rows.iter().filter(|r| !r.pass) {
            t.notes.push(format!(
                "FAIL {} {} {}: {}",
                r.source,
                r.case,
                r.loss_coefficient
                    .map(|e| format!("η={e}"))
                    .unwrap_or_default(),
                r.detail.as_deref().unwrap_or("outside its tolerance")
            ));
        }
        vec![t]
    }

    fn footer(&self) -> Vec<String> {
        vec![
            format!(
                "reproduce a method row: millimpact run {}/CASE.toml --method METHOD --format json",
                self.cases.display()
            ),
            format!(
                "reproduce a stored row: the `command` field of {0}/CODE/CASE.json ({0}/{STORED_FOLDER}/CODE/CASE.json for the benchmark's runs, {0}/{OBLIQUE_FOLDER}/CODE/CASE.json for the oblique ones)",
                self.reference.display()
            ),
        ]
    }
}
