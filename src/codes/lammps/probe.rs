//! What a LAMMPS build does, measured: a handful of runs of a few steps each, one per
//! convention the drivers depend on, each read against the value every hypothesis predicts.
//!
//! The same code changes conventions between releases (the wall modulus between 2021 and 2025,
//! `coeff_restitution` from 2023, the √2 of `damping tsuji` in source newer than 2025), and a
//! user may bring a build of their own, so a driver decides from what the build does, not
//! from its version string. Each probe is a sphere on `fix wall/gran` (the driver's own wall
//! template) started at a chosen overlap and speed; the force the build reports at step 0 or
//! step 1 is compared with the force each hypothesis gives. A probe whose number matches no
//! hypothesis, or more than one, is inconclusive and says why; a driver refuses to plan from
//! inconclusive conventions.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::codes::lammps::conventions::{
    Conventions, DampingVelocity, TsujiFit, WallModulus, exact_hertz_alpha, tsuji_alpha,
};
use crate::codes::lammps::{Build, WALL_TEMPLATE, parse_trajectory, parse_version};
use crate::codes::probe::{Hypothesis, Measured, ProbeError, ProbeItem, ProbeReport, decide};
use crate::codes::runner::process::Process;
use crate::codes::runner::{self, cache_dir};
use crate::codes::template::{TemplateError, exact_number, fill_template};
use crate::codes::{CodeSetup, Executable, Prober};
use crate::model::trajectory::CodeTrajectory;

/// One probe run: a sphere on the wall, started at `overlap` (m; 0 is exactly touching)
/// approaching at `approach` (m/s).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ProbeRun {
    /// The probe's name (also the first line of its input).
    pub name: &'static str,
    /// The contact model's arguments.
    pub contact: String,
    /// Initial overlap, m.
    pub overlap: f64,
    /// Initial approach speed, m/s.
    pub approach: f64,
    /// Time step, s.
    pub timestep: f64,
    /// Steps.
    pub steps: u64,
}

/// The probe sphere's radius, m, and mass, kg.
pub(crate) const PROBE_RADIUS: f64 = 0.02;
/// The probe sphere's mass, kg.
pub(crate) const PROBE_MASS: f64 = 0.25;
/// `E` given to `hertz/material`, Pa.
pub(crate) const PROBE_MODULUS: f64 = 2e11;
/// `ν` of the wall-modulus probe: far enough from 0 that the two conventions differ by 30 %.
pub(crate) const PROBE_POISSON: f64 = 0.3;
/// The `e` given to `coeff_restitution` and `tsuji`.
pub(crate) const PROBE_RESTITUTION: f64 = 0.5;
/// Hertz overlap at step 0, m.
pub(crate) const HERTZ_OVERLAP: f64 = 2e-7;
/// Linear probes: spring, N/m, and dashpot, N·s/m.
pub(crate) const HOOKE: (f64, f64) = (1e6, 100.0);
/// Overlap of the half-step probe, m, and its step, s: the first half kick changes the
/// velocity by 0.4 %, a thousand times what the comparison resolves.
pub(crate) const HALF_STEP_PROBE: (f64, f64) = (1e-4, 1e-5);

/// The runs of the LAMMPS probe, in order: one step each.
pub(crate) fn probe_runs() -> Vec<ProbeRun> {
    let (k, d) = HOOKE;
    let (overlap, dt) = HALF_STEP_PROBE;
    let (e, y) = (exact_number(PROBE_MODULUS), HERTZ_OVERLAP);
    let hertz = |rest: String| format!("hertz/material {e} {rest}");
    let hooke = format!(
        "hooke {} {} damping velocity",
        exact_number(k),
        exact_number(d)
    );
    [
        (
            "wall-modulus",
            hertz(format!("0 {PROBE_POISSON} damping velocity")),
            y,
            0.0,
            1e-7,
        ),
        (
            "coeff-restitution",
            hertz(format!("{PROBE_RESTITUTION} 0 damping coeff_restitution")),
            y,
            1.0,
            1e-7,
        ),
        (
            "tsuji-fit",
            hertz(format!("{PROBE_RESTITUTION} 0 damping tsuji")),
            y,
            1.0,
            1e-7,
        ),
        ("touching", hooke.clone(), 0.0, 1.0, 1e-7),
        ("damping-velocity", hooke, overlap, 1.0, dt),
    ]
    .into_iter()
    .map(|(name, contact, overlap, approach, timestep)| ProbeRun {
        name,
        contact,
        overlap,
        approach,
        timestep,
        steps: 1,
    })
    .collect()
}

/// The input of one probe run (the driver's wall template, so the probe exercises the same
/// deck as the impacts).
pub(crate) fn render_probe(run: &ProbeRun) -> Result<String, TemplateError> {
    let r = PROBE_RADIUS;
    let values = [
        ("contact", run.contact.clone()),
        ("limit_damping", String::new()),
        ("timestep", exact_number(run.timestep)),
        ("steps", run.steps.to_string()),
        ("box_lo", exact_number(-4.0 * r)),
        ("box_hi", exact_number(4.0 * r)),
        ("box_top", exact_number(8.0 * r)),
        ("z0", exact_number(r - run.overlap)),
        ("radius", exact_number(r)),
        ("diameter", exact_number(2.0 * r)),
        ("mass", exact_number(PROBE_MASS)),
        ("vz", exact_number(-run.approach)),
    ];
    let text = fill_template(WALL_TEMPLATE, &values)?;
    Ok(format!("# millimpact probe: {}\n{text}", run.name))
}

/// What one probe run gave: its trajectory, or the build's refusal (the first `ERROR` line).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum ProbeOutcome {
    /// The run finished.
    Ran(CodeTrajectory),
    /// The run failed; the build's message.
    Refused(String),
}

/// The build's first `ERROR` line, else its last line.
fn error_line(log: &str) -> String {
    runner::error_line(log)
        .unwrap_or_else(|| log.lines().last().unwrap_or("no output").trim().to_string())
}

/// Time limit of one probe run: a one-step run is start-up alone (0.1 to 0.7 s here), so a
/// build that takes this long is not running the deck; the probe stops there.
pub(crate) const PROBE_TIMEOUT: Duration = Duration::from_secs(10);

/// Run one probe in a scratch directory; `Err` only when the build could not be started at
/// all. Returns the outcome and the log.
pub(crate) fn run_probe(
    executable: &Executable,
    run: &ProbeRun,
) -> Result<(ProbeOutcome, String), ProbeError> {
    let text = render_probe(run)?;
    let args = [
        "-in", "probe.in", "-log", "none", "-nocite", "-echo", "none",
    ]
    .map(String::from);
    let ran = Process::new(
        executable,
        &args,
        ("probe.in", &text),
        PROBE_TIMEOUT,
        "millimpact-probe-",
    )
    .run()
    .map_err(|e| ProbeError::Io {
        doing: e.step.doing(),
        path: e.path,
        source: e.source,
    })?;
    let log = ran.log().unwrap_or_default();
    let Some(status) = ran.status else {
        return Ok((
            ProbeOutcome::Refused(format!("killed after {} s", PROBE_TIMEOUT.as_secs())),
            log,
        ));
    };
    if !status.success() {
        return Ok((ProbeOutcome::Refused(error_line(&log)), log));
    }
    let outcome = match std::fs::read_to_string(ran.folder().join("trajectory.txt")) {
        Ok(t) => match parse_trajectory(&t) {
            Ok(traj) if traj.time.len() as u64 > run.steps => ProbeOutcome::Ran(traj),
            Ok(_) => ProbeOutcome::Refused("the trajectory is short".into()),
            Err(e) => ProbeOutcome::Refused(format!("unreadable trajectory: {e}")),
        },
        Err(e) => ProbeOutcome::Refused(format!("no trajectory: {e}")),
    };
    Ok((outcome, log))
}

fn hertz_stiffness(modulus: f64) -> f64 {
    4.0 / 3.0 * modulus * PROBE_RADIUS.sqrt()
}

/// The damping ratio a Hertz probe run measured: `(F − k δ^1.5) / (√(m k) δ^¼ v)` at step 0,
/// with `k` from `E* = E/2` (ν = 0 reads the same under both wall conventions).
pub(crate) fn measured_hertz_alpha(t: &CodeTrajectory) -> f64 {
    let k = hertz_stiffness(PROBE_MODULUS / 2.0);
    let (y, v, f) = (t.overlap[0], t.approach_velocity[0], t.normal_force[0]);
    (f - k * y.powf(1.5)) / ((PROBE_MASS * k).sqrt() * y.powf(0.25) * v)
}

fn item(run: &ProbeRun, question: &str) -> ProbeItem {
    ProbeItem {
        item: run.name.to_string(),
        question: question.to_string(),
        input: format!(
            "{} | start overlap {} m, approach {} m/s, Δt {} s, {} step",
            run.contact,
            exact_number(run.overlap),
            exact_number(run.approach),
            exact_number(run.timestep),
            run.steps
        ),
        measured: Vec::new(),
        hypotheses: Vec::new(),
        verdict: None,
        note: None,
    }
}

fn measured(name: &str, value: f64) -> Measured {
    Measured {
        name: name.to_string(),
        value,
    }
}

fn judge(
    mut it: ProbeItem,
    quantity: (&str, f64),
    hypotheses: &[(&str, f64)],
    scale: f64,
) -> ProbeItem {
    let (list, verdict, note) = decide(quantity.1, hypotheses, scale);
    it.measured.push(measured(quantity.0, quantity.1));
    it.hypotheses = list;
    it.verdict = verdict;
    it.note = note;
    it
}

fn refused(mut it: ProbeItem, message: &str) -> ProbeItem {
    it.note = Some(format!("the run failed: {message}"));
    it
}

/// Hypothesis names, as the verdicts read.
pub(crate) mod verdicts {
    /// Wall `E* = E/(2(1−ν))`.
    pub(crate) const ONE_MINUS_NU: &str = "E/(2(1-nu))";
    /// Wall `E* = E/(2(1−ν²))`.
    pub(crate) const ONE_MINUS_NU_SQUARED: &str = "E/(2(1-nu^2))";
    /// `coeff_restitution` applies `√5 β(e)`.
    pub(crate) const PRESENT: &str = "present: alpha = sqrt5 beta(e)";
    /// The build refuses `coeff_restitution`.
    pub(crate) const ABSENT: &str = "absent (input refused)";
    /// `tsuji` applies `poly(e)`.
    pub(crate) const POLY: &str = "poly(e)";
    /// `tsuji` applies `√2 poly(e)`.
    pub(crate) const SQRT2_POLY: &str = "sqrt2 poly(e)";
    /// Touching is contact: the dashpot pushes at step 0.
    pub(crate) const CONTACT: &str = "contact: F = d v0";
    /// Touching is not contact.
    pub(crate) const NO_CONTACT: &str = "no contact: F = 0";
    /// The dashpot sees `v(n+½)`.
    pub(crate) const HALF_STEP: &str = "half-step v(n+1/2)";
    /// The dashpot sees `v(n+1)`.
    pub(crate) const FULL_STEP: &str = "full-step v(n+1)";
}

/// Read the five probe outcomes (in [`probe_runs`] order) into items and conventions. Pure:
/// the unit tests and a recorded build feed it directly.
pub(crate) fn judge_outcomes(outcomes: &[ProbeOutcome]) -> (Vec<ProbeItem>, Option<Conventions>) {
    use verdicts::*;
    let runs = probe_runs();
    let mut items = Vec::new();
    let get = |i: usize| {
        outcomes.get(i).cloned().unwrap_or(ProbeOutcome::Refused(
            "not run: the build failed the basic deck".into(),
        ))
    };

    // Wall modulus: the elastic force at step 0, at rest, read as E*.
    let it = item(&runs[0], "E* of fix wall/gran hertz/material E d nu");
    items.push(match get(0) {
        ProbeOutcome::Ran(t) => {
            let e_star = t.normal_force[0] / (hertz_stiffness(1.0) * t.overlap[0].powf(1.5));
            let nu = PROBE_POISSON;
            let a = PROBE_MODULUS / (2.0 * (1.0 - nu));
            let b = PROBE_MODULUS / (2.0 * (1.0 - nu * nu));
            judge(
                it,
                ("E* from the step-0 force (Pa)", e_star),
                &[(ONE_MINUS_NU, a), (ONE_MINUS_NU_SQUARED, b)],
                b,
            )
        }
        ProbeOutcome::Refused(m) => refused(it, &m),
    });

    // coeff_restitution: refused, or the damping ratio it applies.
    let mut it = item(
        &runs[1],
        "does damping coeff_restitution exist, and what does it apply",
    );
    let exact = exact_hertz_alpha(PROBE_RESTITUTION);
    items.push(match get(1) {
        ProbeOutcome::Ran(t) => judge(
            it,
            ("alpha from the step-0 force", measured_hertz_alpha(&t)),
            &[(PRESENT, exact), (ABSENT, f64::NAN)],
            exact,
        ),
        ProbeOutcome::Refused(m) if m.contains("damping") => {
            it.hypotheses = vec![
                Hypothesis {
                    name: PRESENT.into(),
                    expected: exact,
                    matches: false,
                },
                Hypothesis {
                    name: ABSENT.into(),
                    expected: f64::NAN,
                    matches: true,
                },
            ];
            it.verdict = Some(ABSENT.into());
            it.note = Some(m);
            it
        }
        ProbeOutcome::Refused(m) => refused(it, &m),
    });

    // tsuji: the damping ratio it applies for e_in, against the fit and √2 times it.
    let it = item(&runs[2], "the damping ratio damping tsuji applies for e_in");
    let poly = tsuji_alpha(PROBE_RESTITUTION);
    items.push(match get(2) {
        ProbeOutcome::Ran(t) => judge(
            it,
            ("alpha from the step-0 force", measured_hertz_alpha(&t)),
            &[(POLY, poly), (SQRT2_POLY, std::f64::consts::SQRT_2 * poly)],
            poly,
        ),
        ProbeOutcome::Refused(m) => refused(it, &m),
    });

    // Touching: the force at step 0 of a linear dashpot started at overlap 0.
    let (_, d) = HOOKE;
    let it = item(&runs[3], "is a wall started exactly touching in contact");
    items.push(match get(3) {
        ProbeOutcome::Ran(t) => {
            let v0 = t.approach_velocity[0];
            judge(
                it,
                ("force at step 0 (N)", t.normal_force[0]),
                &[(CONTACT, d * v0), (NO_CONTACT, 0.0)],
                d * v0,
            )
        }
        ProbeOutcome::Refused(m) => refused(it, &m),
    });

    // Damping velocity: the velocity in the step-1 force, against v(½) and v(1).
    let (k, _) = HOOKE;
    let (_, dt) = HALF_STEP_PROBE;
    let it = item(&runs[4], "the velocity the dashpot sees");
    items.push(match get(4) {
        ProbeOutcome::Ran(t) => {
            let used = (t.normal_force[1] - k * t.overlap[1]) / d;
            let half = t.approach_velocity[0] - 0.5 * dt * t.normal_force[0] / PROBE_MASS;
            judge(
                it,
                ("velocity in the step-1 force (m/s)", used),
                &[(HALF_STEP, half), (FULL_STEP, t.approach_velocity[1])],
                half,
            )
        }
        ProbeOutcome::Refused(m) => refused(it, &m),
    });

    let v = |i: usize| items[i].verdict.as_deref();
    let conventions = (|| {
        Some(Conventions {
            wall_modulus: match v(0)? {
                ONE_MINUS_NU => WallModulus::HalfOverOneMinusNu,
                _ => WallModulus::HalfOverOneMinusNuSquared,
            },
            coeff_restitution: v(1)? == PRESENT,
            tsuji_fit: match v(2)? {
                POLY => TsujiFit::Polynomial,
                _ => TsujiFit::Sqrt2Polynomial,
            },
            touching_is_contact: v(3)? == CONTACT,
            damping_velocity: match v(4)? {
                HALF_STEP => DampingVelocity::HalfStep,
                _ => DampingVelocity::FullStep,
            },
        })
    })();
    (items, conventions)
}

/// Probe the LAMMPS build at `executable` (the driver `code`), without the cache.
pub(crate) fn probe_lammps(code: &str, executable: &Executable) -> Result<ProbeReport, ProbeError> {
    let started = Instant::now();
    let mut outcomes = Vec::new();
    let mut version = None;
    for (i, run) in probe_runs().iter().enumerate() {
        let (outcome, log) = run_probe(executable, run)?;
        version = version.or_else(|| parse_version(&log));
        let basic_failed = i == 0 && matches!(outcome, ProbeOutcome::Refused(_));
        outcomes.push(outcome);
        if basic_failed {
            break;
        }
    }
    let (items, conventions) = judge_outcomes(&outcomes);
    Ok(ProbeReport {
        code: code.to_string(),
        program: executable.program.clone(),
        version,
        items,
        conventions,
        wall_time: started.elapsed().as_secs_f64(),
        kept_in: None,
    })
}

/// What a kept probe is valid for: the build's executable as it is on disk (its resolved path,
/// size and modification time), the environment it is started with, and the probe's own decks.
/// A rebuilt or replaced executable, another library path, or a changed probe, and the kept
/// probe no longer applies. (A shared library the executable loads, replaced under it, is not
/// seen: `millimpact probe --refresh` probes again.)
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct BuildIdentity {
    /// The driver's name.
    pub code: String,
    /// The executable, symbolic links resolved.
    pub program: PathBuf,
    /// Its size, bytes.
    pub size: u64,
    /// Its modification time: seconds and nanoseconds since the Unix epoch.
    pub modified: (u64, u32),
    /// The variables it is started with.
    pub env: Vec<(String, String)>,
    /// SHA-256 of every probe deck, in order (hex).
    pub probe_sha256: String,
}

impl BuildIdentity {
    /// The identity of `executable` as the driver `code` probes it now.
    pub(crate) fn of(code: &str, executable: &Executable) -> Result<BuildIdentity, ProbeError> {
        let io = |doing: &'static str| {
            let path = executable.program.clone();
            move |source| ProbeError::Io {
                doing,
                path,
                source,
            }
        };
        let program = std::fs::canonicalize(&executable.program).map_err(io("resolving"))?;
        let meta = std::fs::metadata(&program).map_err(io("reading the metadata of"))?;
        let since = meta
            .modified()
            .map_err(io("reading the modification time of"))?
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap_or_default();
        let mut decks = Sha256::new();
        for run in probe_runs() {
            decks.update(render_probe(&run)?.as_bytes());
        }
        Ok(BuildIdentity {
            code: code.to_string(),
            program,
            size: meta.len(),
            modified: (since.as_secs(), since.subsec_nanos()),
            env: executable
                .env
                .iter()
                .map(|(k, v)| ((*k).to_string(), v.to_string_lossy().into_owned()))
                .collect(),
            probe_sha256: decks
                .finalize()
                .iter()
                .map(|b| format!("{b:02x}"))
                .collect(),
        })
    }

    /// The file a probe of this build is kept in under the cache folder `dir`: one per driver
    /// and executable path, rewritten when the executable changes.
    pub(crate) fn cache_file(&self, dir: &Path) -> PathBuf {
        let path = Sha256::digest(self.program.as_os_str().as_encoded_bytes());
        let short: String = path.iter().take(8).map(|b| format!("{b:02x}")).collect();
        dir.join("probe")
            .join(format!("{}-{short}.json", self.code))
    }
}

/// A kept probe: the build it was made of, and its report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct KeptProbe {
    identity: BuildIdentity,
    report: ProbeReport,
}

/// The report kept in `file` for `identity`, if the file holds one for this very build; an
/// unreadable or foreign file holds none (it is replaced by the next probe).
fn read_kept(file: &Path, identity: &BuildIdentity) -> Option<ProbeReport> {
    let text = std::fs::read_to_string(file).ok()?;
    let kept: KeptProbe = serde_json::from_str(&text).ok()?;
    (kept.identity == *identity).then_some(kept.report)
}

/// [`probe_lammps`] kept on disk: the report kept under the cache folder `dir` for this very
/// build (see [`BuildIdentity`]), else a fresh probe, kept there when it is conclusive (a probe
/// cut short by a loaded machine, or a build that does not run, is probed again next time).
/// `refresh` probes afresh whatever is kept. Without a cache folder, or when the executable's
/// identity cannot be read, it probes.
pub(crate) fn probe_lammps_kept(
    code: &str,
    executable: &Executable,
    dir: Option<&Path>,
    refresh: bool,
) -> Result<ProbeReport, ProbeError> {
    let kept = dir.and_then(|dir| {
        let identity = BuildIdentity::of(code, executable).ok()?;
        Some((identity.cache_file(dir), identity))
    });
    if !refresh
        && let Some((file, identity)) = &kept
        && let Some(mut report) = read_kept(file, identity)
    {
        report.kept_in = Some(file.clone());
        return Ok(report);
    }
    let report = probe_lammps(code, executable)?;
    if let Some((file, identity)) = kept
        && report.conventions.is_some()
    {
        let text = serde_json::to_string_pretty(&KeptProbe {
            identity,
            report: report.clone(),
        })
        .unwrap_or_default();
        // Written to a temporary file and renamed, so that a reader never sees half a file;
        // a cache that cannot be written costs the next run a probe, nothing more.
        if let Some(parent) = file.parent()
            && std::fs::create_dir_all(parent).is_ok()
            && let Ok(mut tmp) = tempfile::NamedTempFile::new_in(parent)
            && std::io::Write::write_all(&mut tmp, text.as_bytes()).is_ok()
        {
            let _ = tmp.persist(&file);
        }
    }
    Ok(report)
}

/// Probe results of this process, by driver and executable.
static CACHE: Mutex<Vec<(String, PathBuf, ProbeReport)>> = Mutex::new(Vec::new());

/// [`probe_lammps_kept`] in the cache folder `dir` (the [`cache_dir`] for a driver), once per
/// executable per process: a build does not change under a running process, and every run of
/// it is sized and rendered from the same conventions. The lock is held while a build is
/// probed, so that workers asking together wait for one probe instead of each running their
/// own.
pub(crate) fn probe_lammps_cached(
    code: &str,
    executable: &Executable,
    dir: Option<&Path>,
    refresh: bool,
) -> Result<ProbeReport, ProbeError> {
    let key = executable.program.clone();
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    if !refresh && let Some((_, _, r)) = cache.iter().find(|(c, p, _)| c == code && *p == key) {
        return Ok(r.clone());
    }
    let report = probe_lammps_kept(code, executable, dir, refresh)?;
    cache.retain(|(c, p, _)| !(c == code && *p == key));
    cache.push((code.to_string(), key, report.clone()));
    Ok(report)
}

/// A LAMMPS build's probe: its conventions measured by one-step runs.
pub(crate) struct LammpsProber(pub &'static Build);

impl Prober for LammpsProber {
    fn probe(&self, executable: &Executable) -> Result<ProbeReport, ProbeError> {
        probe_lammps_cached(self.0.name, executable, cache_dir().as_deref(), false)
    }

    fn probe_afresh(&self, executable: &Executable) -> Result<ProbeReport, ProbeError> {
        probe_lammps_cached(self.0.name, executable, cache_dir().as_deref(), true)
    }

    fn planned_conventions(&self, setup: &CodeSetup) -> Conventions {
        self.0.conventions(setup)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(y: f64, v: f64, f: f64) -> (f64, f64, f64) {
        (y, v, f)
    }

    fn traj(rows: &[(f64, f64, f64)]) -> CodeTrajectory {
        CodeTrajectory {
            time: (0..rows.len()).map(|i| i as f64 * 1e-7).collect(),
            overlap: rows.iter().map(|r| r.0).collect(),
            approach_velocity: rows.iter().map(|r| r.1).collect(),
            normal_force: rows.iter().map(|r| r.2).collect(),
        }
    }

    /// The five outcomes a build with the given conventions gives, computed from the
    /// hypotheses (what the probes read back).
    fn synthetic(c: Conventions) -> Vec<ProbeOutcome> {
        let y = HERTZ_OVERLAP;
        let nu = PROBE_POISSON;
        let e_star = match c.wall_modulus {
            WallModulus::HalfOverOneMinusNu => PROBE_MODULUS / (2.0 * (1.0 - nu)),
            WallModulus::HalfOverOneMinusNuSquared => PROBE_MODULUS / (2.0 * (1.0 - nu * nu)),
        };
        let k = hertz_stiffness(PROBE_MODULUS / 2.0);
        let damped = |alpha: f64| {
            ProbeOutcome::Ran(traj(&[
                row(
                    y,
                    1.0,
                    k * y.powf(1.5) + alpha * (PROBE_MASS * k).sqrt() * y.powf(0.25),
                ),
                row(y, 1.0, 0.0),
            ]))
        };
        let (kh, d) = HOOKE;
        let (y4, dt) = HALF_STEP_PROBE;
        let f0 = kh * y4 + d;
        let half = 1.0 - 0.5 * dt * f0 / PROBE_MASS;
        let y1 = y4 + dt * half;
        let full = half - 0.5 * dt * (kh * y1 + d * half) / PROBE_MASS;
        let seen = match c.damping_velocity {
            DampingVelocity::HalfStep => half,
            DampingVelocity::FullStep => full,
        };
        vec![
            ProbeOutcome::Ran(traj(&[
                row(y, 0.0, hertz_stiffness(e_star) * y.powf(1.5)),
                row(y, 0.0, 0.0),
            ])),
            if c.coeff_restitution {
                damped(exact_hertz_alpha(PROBE_RESTITUTION))
            } else {
                ProbeOutcome::Refused(
                    "ERROR: Illegal wall/gran command, unrecognized damping model".into(),
                )
            },
            damped(c.tsuji_fit.alpha(PROBE_RESTITUTION)),
            ProbeOutcome::Ran(traj(&[
                row(0.0, 1.0, if c.touching_is_contact { d } else { 0.0 }),
                row(1e-7, 1.0, 0.0),
            ])),
            ProbeOutcome::Ran(traj(&[row(y4, 1.0, f0), row(y1, full, kh * y1 + d * seen)])),
        ]
    }

    #[test]
    fn every_combination_of_conventions_is_read_back() {
        for wall_modulus in [
            WallModulus::HalfOverOneMinusNu,
            WallModulus::HalfOverOneMinusNuSquared,
        ] {
            for coeff_restitution in [false, true] {
                for tsuji_fit in [TsujiFit::Polynomial, TsujiFit::Sqrt2Polynomial] {
                    for touching_is_contact in [false, true] {
                        for damping_velocity in
                            [DampingVelocity::HalfStep, DampingVelocity::FullStep]
                        {
                            let c = Conventions {
                                wall_modulus,
                                coeff_restitution,
                                tsuji_fit,
                                touching_is_contact,
                                damping_velocity,
                            };
                            let (items, read) = judge_outcomes(&synthetic(c));
                            assert_eq!(read, Some(c), "{items:#?}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_failed_run_leaves_its_item_inconclusive_and_no_conventions() {
        let mut outcomes = synthetic(Conventions::JUL_2025);
        outcomes[2] = ProbeOutcome::Refused("ERROR: something else".into());
        let (items, read) = judge_outcomes(&outcomes);
        assert_eq!(read, None);
        assert!(items[2].note.as_deref().unwrap().contains("something else"));
        // A refusal that is not about the damping model does not read as "absent".
        let mut outcomes = synthetic(Conventions::DEBIAN_2021);
        outcomes[1] = ProbeOutcome::Refused("ERROR: Cannot open input".into());
        let (items, _) = judge_outcomes(&outcomes);
        assert_eq!(items[1].verdict, None);
    }

    #[test]
    fn a_build_that_fails_the_basic_deck_did_not_run_the_probe() {
        let (items, conventions) =
            judge_outcomes(&[ProbeOutcome::Refused("ERROR: not LAMMPS".into())]);
        let report = ProbeReport {
            code: "lammps".into(),
            program: "/fake/lmp".into(),
            version: None,
            items,
            conventions,
            wall_time: 0.0,
            kept_in: None,
        };
        assert!(!report.ran());
        assert!(
            report
                .conventions()
                .unwrap_err()
                .to_string()
                .contains("not LAMMPS")
        );
        let (items, conventions) = judge_outcomes(&synthetic(Conventions::DEBIAN_2021));
        let report = ProbeReport {
            items,
            conventions,
            ..report
        };
        assert!(report.ran());
    }

    /// A stand-in for a LAMMPS build, in `dir`: a script that counts its starts in
    /// `dir/starts` and answers each probe deck (named on its first line) as a build with the
    /// conventions `c` would, from the [`synthetic`] outcomes written beside it.
    fn fake_build(dir: &Path, c: Conventions) -> Executable {
        for (run, outcome) in probe_runs().iter().zip(synthetic(c)) {
            let (ext, text) = match outcome {
                ProbeOutcome::Ran(t) => (
                    "txt",
                    (0..t.time.len())
                        .map(|i| {
                            format!(
                                "{:e} {:e} {:e} {:e}\n",
                                t.time[i], t.overlap[i], t.approach_velocity[i], t.normal_force[i]
                            )
                        })
                        .collect::<String>(),
                ),
                ProbeOutcome::Refused(message) => ("err", message + "\n"),
            };
            std::fs::write(dir.join(format!("{}.{ext}", run.name)), text).unwrap();
        }
        let d = dir.display();
        let program = dir.join("lmp");
        std::fs::write(
            &program,
            format!(
                "#!/bin/sh\necho started >> '{d}/starts'\nname=$(head -n 1 probe.in | sed 's/^# millimpact probe: //')\n\
                 echo 'LAMMPS (fake build)'\nif [ -f \"{d}/$name.err\" ]; then cat \"{d}/$name.err\"; exit 1; fi\n\
                 cp \"{d}/$name.txt\" trajectory.txt\n"
            ),
        )
        .unwrap();
        let mut permissions = std::fs::metadata(&program).unwrap().permissions();
        std::os::unix::fs::PermissionsExt::set_mode(&mut permissions, 0o755);
        std::fs::set_permissions(&program, permissions).unwrap();
        Executable::plain(program)
    }

    /// A report as JSON, where a prediction of no number (NaN) equals itself.
    fn json(report: &ProbeReport) -> serde_json::Value {
        serde_json::to_value(report).unwrap()
    }

    fn starts(dir: &Path) -> usize {
        std::fs::read_to_string(dir.join("starts"))
            .map(|s| s.lines().count())
            .unwrap_or(0)
    }

    #[test]
    fn a_kept_probe_is_read_instead_of_starting_the_build() {
        let build = tempfile::tempdir().unwrap();
        let cache = tempfile::tempdir().unwrap();
        let lmp = fake_build(build.path(), Conventions::DEBIAN_2021);
        let first = probe_lammps_kept("lammps", &lmp, Some(cache.path()), false).unwrap();
        assert_eq!(
            first.conventions,
            Some(Conventions::DEBIAN_2021),
            "{first:#?}"
        );
        assert_eq!(first.kept_in, None);
        assert_eq!(starts(build.path()), probe_runs().len());
        let second = probe_lammps_kept("lammps", &lmp, Some(cache.path()), false).unwrap();
        assert_eq!(
            starts(build.path()),
            probe_runs().len(),
            "the build was not started"
        );
        let file = BuildIdentity::of("lammps", &lmp)
            .unwrap()
            .cache_file(cache.path());
        assert_eq!(second.kept_in.as_deref(), Some(file.as_path()));
        assert_eq!(
            json(&ProbeReport {
                kept_in: None,
                ..second
            }),
            json(&first)
        );
        // Another driver's probe of the same executable is its own.
        probe_lammps_kept("lammps-2025", &lmp, Some(cache.path()), false).unwrap();
        assert_eq!(starts(build.path()), 2 * probe_runs().len());
        // A refresh probes again, and keeps what it measured.
        probe_lammps_kept("lammps", &lmp, Some(cache.path()), true).unwrap();
        assert_eq!(starts(build.path()), 3 * probe_runs().len());
        probe_lammps_kept("lammps", &lmp, Some(cache.path()), false).unwrap();
        assert_eq!(starts(build.path()), 3 * probe_runs().len());
    }

    /// Gives the file at `path` one fixed modification time.
    fn set_modified(path: &Path) {
        let file = std::fs::File::options().write(true).open(path).unwrap();
        file.set_modified(std::time::UNIX_EPOCH + Duration::from_secs(1_000_000))
            .unwrap();
    }

    #[test]
    fn a_changed_executable_is_probed_again() {
        let build = tempfile::tempdir().unwrap();
        let cache = tempfile::tempdir().unwrap();
        let lmp = fake_build(build.path(), Conventions::DEBIAN_2021);
        let n = probe_runs().len();
        probe_lammps_kept("lammps", &lmp, Some(cache.path()), false).unwrap();
        assert_eq!(starts(build.path()), n);
        // Touched: same size, another modification time.
        set_modified(&lmp.program);
        probe_lammps_kept("lammps", &lmp, Some(cache.path()), false).unwrap();
        assert_eq!(starts(build.path()), 2 * n, "a new modification time");
        probe_lammps_kept("lammps", &lmp, Some(cache.path()), false).unwrap();
        assert_eq!(starts(build.path()), 2 * n);
        // Rebuilt: another size, the same modification time.
        let mut script = std::fs::read_to_string(&lmp.program).unwrap();
        script.push_str("# rebuilt\n");
        std::fs::write(&lmp.program, script).unwrap();
        set_modified(&lmp.program);
        probe_lammps_kept("lammps", &lmp, Some(cache.path()), false).unwrap();
        assert_eq!(starts(build.path()), 3 * n, "another size");
        // Started with another environment.
        let with_env = Executable {
            env: vec![("OMP_NUM_THREADS", "1".into())],
            ..lmp.clone()
        };
        probe_lammps_kept("lammps", &with_env, Some(cache.path()), false).unwrap();
        assert_eq!(starts(build.path()), 4 * n, "another environment");
    }

    #[test]
    fn a_corrupt_kept_probe_is_ignored_and_rewritten() {
        let build = tempfile::tempdir().unwrap();
        let cache = tempfile::tempdir().unwrap();
        let lmp = fake_build(build.path(), Conventions::JUL_2025);
        let n = probe_runs().len();
        let file = BuildIdentity::of("lammps-2025", &lmp)
            .unwrap()
            .cache_file(cache.path());
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        for corrupt in ["{\"identity\": ", "not json at all", "{}"] {
            std::fs::write(&file, corrupt).unwrap();
            let before = starts(build.path());
            let report = probe_lammps_kept("lammps-2025", &lmp, Some(cache.path()), false).unwrap();
            assert_eq!(report.conventions, Some(Conventions::JUL_2025));
            assert_eq!(starts(build.path()), before + n, "{corrupt}: probed");
            let kept: KeptProbe =
                serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
            assert_eq!(json(&kept.report), json(&report), "{corrupt}: rewritten");
        }
    }

    #[test]
    fn a_probe_that_settles_nothing_is_not_kept() {
        let build = tempfile::tempdir().unwrap();
        let cache = tempfile::tempdir().unwrap();
        let lmp = fake_build(build.path(), Conventions::DEBIAN_2021);
        // The tsuji deck refused for another reason than the damping model: inconclusive.
        std::fs::write(build.path().join("tsuji-fit.err"), "ERROR: Lost atoms\n").unwrap();
        let n = probe_runs().len();
        for round in 1..=2 {
            let report = probe_lammps_kept("lammps", &lmp, Some(cache.path()), false).unwrap();
            assert_eq!(report.conventions, None);
            assert_eq!(starts(build.path()), round * n);
        }
        let kept = std::fs::read_dir(cache.path().join("probe"))
            .map(|entries| entries.count())
            .unwrap_or(0);
        assert_eq!(kept, 0, "nothing kept");
    }

    #[test]
    fn workers_asking_together_wait_for_one_probe() {
        let build = tempfile::tempdir().unwrap();
        let cache = tempfile::tempdir().unwrap();
        let lmp = fake_build(build.path(), Conventions::DEBIAN_2021);
        let reports: Vec<ProbeReport> = std::thread::scope(|s| {
            let workers: Vec<_> = (0..4)
                .map(|_| {
                    s.spawn(|| {
                        probe_lammps_cached("lammps", &lmp, Some(cache.path()), false).unwrap()
                    })
                })
                .collect();
            workers.into_iter().map(|w| w.join().unwrap()).collect()
        });
        assert_eq!(starts(build.path()), probe_runs().len());
        assert!(reports.iter().all(|r| json(r) == json(&reports[0])));
    }

    #[test]
    fn the_probe_inputs_name_themselves_and_use_the_wall_template() {
        for run in probe_runs() {
            let text = render_probe(&run).unwrap();
            assert!(text.starts_with(&format!("# millimpact probe: {}\n", run.name)));
            assert!(text.contains(&run.contact));
            assert!(!text.contains("{{"));
        }
    }
}
