//! Running an installed code: a scratch directory, a time limit, the log kept on any fault.

use std::path::{Path, PathBuf};
use std::time::Duration;

use thiserror::Error;

pub(crate) mod process;

use self::process::{Output, Process};
pub(crate) use self::process::{stop_all_codes, stop_all_codes_and_exit};
use super::parse::ParseError;
use super::setup::CodeSetup;
use super::{CodeDriver, Executable, ParsedRun, RenderedInput};
use crate::model::trajectory::{CodeTrajectory, check_trajectory};

/// Why a build's executable was not found: each variant names where it was looked for.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum LocateError {
    /// The override variable names something that is not a file.
    #[error("{variable}={} is not a file", path.display())]
    OverrideNotAFile {
        /// The variable, `MILLIMPACT_<CODE>_BINARY`.
        variable: String,
        /// What it names.
        path: PathBuf,
    },
    /// No such executable on PATH.
    #[error("binary `{binary}` not found on PATH (install it with scripts/install-dem-codes.sh)")]
    NotOnPath {
        /// The executable's file name.
        binary: String,
    },
    /// The code's own installation under the codes' folder is missing.
    #[error("no {} ({origin}; bash scripts/install-dem-codes.sh installs the codes in its project's {CODES_FOLDER}, MILLIMPACT_CODES_DIR names another folder, {variable} another build)", folder.join(expected).display())]
    NotInstalled {
        /// What was looked for, relative to `folder`.
        expected: &'static str,
        /// Where.
        folder: PathBuf,
        /// How that folder was chosen.
        origin: CodesDirOrigin,
        /// The override variable that names another build.
        variable: String,
    },
    /// A virtual environment's python links to a Python that is not on this machine: the
    /// environment was made on another one.
    #[error("{} links to {}, which is not on this machine: a Python virtual environment runs the Python that made it, so one made on another machine does not run here; make it again on this machine with bash scripts/install-dem-codes.sh (with the codes' folder as MILLIMPACT_CODES_DIR if it is not the project's {CODES_FOLDER}), or name a python that has the code in {variable}", link.display(), target.display())]
    MovedEnvironment {
        /// The venv's python.
        link: PathBuf,
        /// The missing file it leads to.
        target: PathBuf,
        /// The override variable that names another build.
        variable: String,
    },
}

/// A code that cannot be found is the installation's failure, not the input's.
impl crate::error::Blame for LocateError {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// The name of the codes' folder in a project (where `scripts/install-dem-codes.sh` installs).
pub(crate) const CODES_FOLDER: &str = ".codes";

/// How the codes' folder was chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CodesDirOrigin {
    /// Named by `MILLIMPACT_CODES_DIR`.
    Variable,
    /// The nearest `.codes` in the working directory or a folder above it.
    WorkingDirectory,
    /// The nearest `.codes` in the executable's folder or a folder above it.
    Executable,
    /// None was found: `.codes` in the working directory, where none is.
    NotFound,
}

impl std::fmt::Display for CodesDirOrigin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            CodesDirOrigin::Variable => "the codes' folder named by MILLIMPACT_CODES_DIR",
            CodesDirOrigin::WorkingDirectory => {
                "the codes' folder found in the working directory or above it"
            }
            CodesDirOrigin::Executable => {
                "the codes' folder found beside millimpact's executable or above it"
            }
            CodesDirOrigin::NotFound => {
                "no .codes in the working directory, beside millimpact's executable or above either, and MILLIMPACT_CODES_DIR is unset"
            }
        })
    }
}

/// The codes' folder and how it was chosen.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CodesDir {
    /// The folder.
    pub path: PathBuf,
    /// How it was chosen.
    pub origin: CodesDirOrigin,
}

/// A fault of an external code. Each variant names the code and, where there is one, where
/// its log was kept.
#[derive(Debug, Error)]
pub enum CodeError {
    /// The build's executable is not where it was looked for.
    #[error("{code}: {looked}")]
    MissingBinary {
        /// Code name.
        code: String,
        /// Where it was looked for, and what was found there.
        looked: LocateError,
    },
    /// The code exited with a failure status.
    #[error("{code}: exited with {status}{}; log kept in {}", said_suffix(said), log.display())]
    Crashed {
        /// Code name.
        code: String,
        /// Exit status as text.
        status: String,
        /// The code's own error line, where its log has one (`error_line`).
        said: Option<String>,
        /// The kept log file.
        log: PathBuf,
    },
    /// The code ran past its time limit and was killed.
    #[error("{code}: killed after the time limit of {seconds} s; log kept in {}", log.display())]
    TimedOut {
        /// Code name.
        code: String,
        /// The limit, s.
        seconds: f64,
        /// The kept log file.
        log: PathBuf,
    },
    /// The code's output could not be read.
    #[error("{code}: unparsable output: {reason}; log kept in {}", log.display())]
    Unparsable {
        /// Code name.
        code: String,
        /// What was wrong.
        reason: ParseError,
        /// The kept log file.
        log: PathBuf,
    },
    /// The case cannot be set up in this code.
    #[error("{code}: cannot set up {case}: {reason}")]
    Unsupported {
        /// Code name.
        code: String,
        /// Case name.
        case: String,
        /// Why.
        reason: String,
    },
    /// Scratch-directory or process I/O failed.
    #[error("{code}: {context}: {source}")]
    Io {
        /// Code name.
        code: String,
        /// What was being done.
        context: String,
        /// The I/O error.
        source: std::io::Error,
    },
}

fn said_suffix(said: &Option<String>) -> String {
    said.as_deref()
        .map(|line| format!(", saying `{line}`"))
        .unwrap_or_default()
}

/// The error a code printed before it stopped: the first line of `log` that starts with
/// `ERROR` (how LIGGGHTS and LAMMPS report a fatal error: `ERROR: <what> (<file>:<line>)`).
pub(crate) fn error_line(log: &str) -> Option<String> {
    log.lines()
        .map(str::trim)
        .find(|line| line.starts_with("ERROR"))
        .map(String::from)
}

/// The last line of `log` that starts with `ERROR`: of a code whose output reached the log
/// line by line, the one that stopped it (an earlier one may be a warning's echo).
pub(crate) fn last_error_line(log: &str) -> Option<String> {
    log.lines()
        .map(str::trim)
        .rfind(|line| line.starts_with("ERROR"))
        .map(String::from)
}

/// A finished run of an external code.
#[derive(Clone, Debug)]
pub struct CodeRun {
    /// Code name.
    pub code: String,
    /// Version string as the code printed it.
    pub code_version: String,
    /// The exact input it ran.
    pub input: String,
    /// The trajectory.
    pub trajectory: CodeTrajectory,
    /// Process wall time, s.
    pub wall_time: f64,
    /// The code's own loop time, s, where reported.
    pub loop_time: Option<f64>,
    /// The combined stdout and stderr.
    pub log: String,
    /// An oblique impact's motion along the contact plane after the run, as the code printed
    /// it; `None` for a normal impact.
    pub plane_motion: Option<super::TangentialRun>,
}

/// Time limit and scratch location for [`run_code`].
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Kill the code after this long.
    pub timeout: Duration,
    /// Parent directory for scratch directories (the system temp dir by default).
    pub scratch_parent: Option<PathBuf>,
}

impl RunOptions {
    /// The folder the scratch directories are made in.
    pub(crate) fn scratch_folder(&self) -> PathBuf {
        self.scratch_parent
            .clone()
            .unwrap_or_else(std::env::temp_dir)
    }
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            timeout: Duration::from_secs(120),
            scratch_parent: None,
        }
    }
}

/// Where the codes installed from PyPI (and other builds of the project's own) live, found
/// when the program runs, not where it was built, so that a binary and its project can be
/// copied to a cluster: `MILLIMPACT_CODES_DIR` if set; else the nearest `.codes` in the working
/// directory or a folder above it (a project's checkout, run from anywhere inside it); else the
/// nearest `.codes` in the executable's folder or above it (`target/release/millimpact` finds
/// its checkout's, wherever it runs from).
pub(crate) fn find_codes_dir() -> CodesDir {
    if let Some(dir) = std::env::var_os("MILLIMPACT_CODES_DIR").filter(|d| !d.is_empty()) {
        return CodesDir {
            path: PathBuf::from(dir),
            origin: CodesDirOrigin::Variable,
        };
    }
    let nearest = |start: &Path| {
        start
            .ancestors()
            .map(|dir| dir.join(CODES_FOLDER))
            .find(|candidate| candidate.is_dir())
    };
    let here = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
    if let Some(path) = nearest(&here) {
        return CodesDir {
            path,
            origin: CodesDirOrigin::WorkingDirectory,
        };
    }
    let executable = std::env::current_exe()
        .and_then(std::fs::canonicalize)
        .ok()
        .and_then(|exe| exe.parent().map(Path::to_path_buf));
    if let Some(path) = executable.as_deref().and_then(nearest) {
        return CodesDir {
            path,
            origin: CodesDirOrigin::Executable,
        };
    }
    CodesDir {
        path: here.join(CODES_FOLDER),
        origin: CodesDirOrigin::NotFound,
    }
}

/// Whether `path` is a chain of symbolic links that ends at nothing: the file it was made to
/// lead to is not here. Returns the last link's missing target.
pub(crate) fn dangling_link(path: &Path) -> Option<PathBuf> {
    let mut at = path.to_path_buf();
    // A loop of links is not followed for ever.
    for _ in 0..40 {
        let meta = std::fs::symlink_metadata(&at).ok()?;
        if !meta.file_type().is_symlink() {
            return None;
        }
        let target = std::fs::read_link(&at).ok()?;
        let next = at.parent().unwrap_or(Path::new("")).join(target);
        if std::fs::symlink_metadata(&next).is_err() {
            return Some(next);
        }
        at = next;
    }
    None
}

/// The environment variable that names millimpact's cache folder.
pub(crate) const CACHE_DIR_VARIABLE: &str = "MILLIMPACT_CACHE_DIR";

/// Where millimpact keeps what it measured once and reuses in later runs (each LAMMPS build's
/// probe, under `probe/`): `MILLIMPACT_CACHE_DIR`, else `$XDG_CACHE_HOME/millimpact`, else
/// `$HOME/.cache/millimpact`; `None`, and nothing kept, when none of them is set (a relative
/// `XDG_CACHE_HOME` or `HOME` counts as unset, as the XDG base directory specification says).
pub(crate) fn cache_dir() -> Option<PathBuf> {
    let absolute = |name: &str| {
        std::env::var_os(name)
            .map(PathBuf::from)
            .filter(|p| p.is_absolute())
    };
    if let Some(dir) = std::env::var_os(CACHE_DIR_VARIABLE).filter(|v| !v.is_empty()) {
        return Some(PathBuf::from(dir));
    }
    absolute("XDG_CACHE_HOME")
        .map(|dir| dir.join("millimpact"))
        .or_else(|| absolute("HOME").map(|home| home.join(".cache").join("millimpact")))
}

/// The environment variable that points a code at a user's own build: `MILLIMPACT_<NAME>_BINARY`
/// (the name upper-cased, `-` as `_`; `MILLIMPACT_LAMMPS_2025_BINARY`, say).
pub fn binary_override_variable(code: &str) -> String {
    format!(
        "MILLIMPACT_{}_BINARY",
        code.to_ascii_uppercase().replace('-', "_")
    )
}

/// The executable a build runs: the file named by its [`binary_override_variable`] if that is
/// set, else `binary` on PATH; `Err` says where it was looked for.
pub(crate) fn locate_override_or_path(code: &str, binary: &str) -> Result<Executable, LocateError> {
    let variable = binary_override_variable(code);
    if let Some(path) = std::env::var_os(&variable) {
        let path = PathBuf::from(path);
        return if path.is_file() {
            Ok(Executable::plain(path))
        } else {
            Err(LocateError::OverrideNotAFile { variable, path })
        };
    }
    find_on_path(binary)
        .map(Executable::plain)
        .ok_or_else(|| LocateError::NotOnPath {
            binary: binary.to_string(),
        })
}

/// The executable of a build installed in the codes' folder ([`find_codes_dir`]): as
/// [`locate_override_or_path`] finds it where the build's [`binary_override_variable`] is set
/// (a user's own build), else what `installed` finds in the codes' folder, given the error
/// that names what is missing there (what was looked for, in which folder).
pub(crate) fn locate_override_or_installed(
    driver: &dyn CodeDriver,
    installed: impl FnOnce(
        &CodesDir,
        &dyn Fn(&'static str, PathBuf) -> LocateError,
    ) -> Result<Executable, LocateError>,
) -> Result<Executable, LocateError> {
    let variable = binary_override_variable(driver.name());
    if std::env::var_os(&variable).is_some() {
        return locate_override_or_path(driver.name(), driver.binary());
    }
    let codes = find_codes_dir();
    let missing = |expected, folder| LocateError::NotInstalled {
        expected,
        folder,
        origin: codes.origin,
        variable: variable.clone(),
    };
    installed(&codes, &missing)
}

/// Whether `binary` is an executable on PATH.
pub(crate) fn find_on_path(binary: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(binary))
        .find(|candidate| candidate.is_file())
}

/// Refuse to run `setups` on the build at `executable` when they were planned for other
/// conventions than its probe measures (a record's setup replayed on another build, a setup
/// made without a probe for a build that differs from the driver's fallback): the input would
/// not be the equivalent setup on this build.
pub(crate) fn check_conventions(
    driver: &dyn CodeDriver,
    executable: &Executable,
    setups: &[CodeSetup],
) -> Result<(), CodeError> {
    let planned: Vec<_> = setups
        .iter()
        .filter_map(|s| {
            driver
                .prober()
                .map(|prober| (s, prober.planned_conventions(s)))
        })
        .collect();
    let Some(prober) = driver.prober().filter(|_| !planned.is_empty()) else {
        return Ok(());
    };
    // A build that cannot start or fails the probe's basic deck fails the run the same way,
    // which then says why with its log: only a build that runs is held to its conventions.
    let report = match prober.probe(executable) {
        Ok(report) if report.ran() => report,
        _ => return Ok(()),
    };
    let measured = report
        .conventions()
        .map_err(|reason| CodeError::Unsupported {
            code: driver.name().into(),
            case: setups
                .first()
                .map(|s| s.case_name.clone())
                .unwrap_or_default(),
            reason: reason.to_string(),
        })?;
    match planned.into_iter().find(|(_, c)| *c != measured) {
        None => Ok(()),
        Some((setup, c)) => Err(CodeError::Unsupported {
            code: driver.name().into(),
            case: setup.case_name.clone(),
            reason: format!(
                "planned for the conventions {} but {} measures {}; set it up again (millimpact probe --code {} shows them)",
                serde_json::to_string(&c).unwrap_or_default(),
                executable.program.display(),
                serde_json::to_string(&measured).unwrap_or_default(),
                driver.name()
            ),
        }),
    }
}

/// The build `driver` runs, or the fault of its code that it is missing.
pub(crate) fn locate(driver: &dyn CodeDriver) -> Result<Executable, CodeError> {
    driver.locate().map_err(|looked| CodeError::MissingBinary {
        code: driver.name().to_string(),
        looked,
    })
}

/// Render, run and parse one impact in `driver`'s code.
///
/// The scratch directory is removed after a good run and kept, with its `log.txt`, after any
/// failure, so that the error can point at it.
pub fn run_code(
    driver: &dyn CodeDriver,
    setup: &CodeSetup,
    options: &RunOptions,
) -> Result<CodeRun, CodeError> {
    refuse_oblique(driver, setup)?;
    let executable = locate(driver)?;
    check_conventions(driver, &executable, std::slice::from_ref(setup))?;
    let input = driver.render(setup)?;
    run_rendered(driver, &executable, setup, &input, options, Output::AsIs)
}

/// Run `input`, rendered for `setup` (by `driver` or by a deck's reader), with `executable`,
/// and read it as `driver` reads its runs: its parse, its trajectory's rows, a trajectory that
/// holds together. As [`run_code`], the scratch directory is kept only after a failure.
pub(crate) fn run_rendered(
    driver: &dyn CodeDriver,
    executable: &Executable,
    setup: &CodeSetup,
    input: &RenderedInput,
    options: &RunOptions,
    output: Output,
) -> Result<CodeRun, CodeError> {
    let code = driver.name();
    let prefix = format!("millimpact-{code}-{}-", setup.case_name);
    let parent = options.scratch_folder();
    let (ran, log) = Process::new(
        executable,
        &input.args,
        (&input.file_name, &input.text),
        options.timeout,
        &prefix,
    )
    .in_folder(&parent)
    .output(output)
    .run()
    .map_err(|e| e.code_error(code))?
    .succeeded(code)?;
    let parsed = match driver
        .parse(setup, ran.folder(), &log)
        .and_then(|parsed| whole_trajectory(driver, setup, parsed, || "the trajectory".into()))
    {
        Ok(parsed) => parsed,
        Err(reason) => return Err(ran.unparsable(code, reason)),
    };
    let plane_motion = match setup.oblique {
        None => None,
        Some(_) => match super::TangentialRun::from_log(&log, super::deck::TANGENTIAL_LINE) {
            Some(motion) => Some(motion),
            None => {
                return Err(ran.unparsable(
                    code,
                    ParseError::NoPlaneMotion {
                        word: super::deck::TANGENTIAL_LINE,
                    },
                ));
            }
        },
    };
    Ok(CodeRun {
        code: code.to_string(),
        code_version: parsed.version.unwrap_or_else(|| "unknown".to_string()),
        input: input.text.clone(),
        trajectory: parsed.trajectory,
        wall_time: ran.wall_time,
        loop_time: parsed.loop_time,
        log,
        plane_motion,
    })
}

/// Refuses, as `code`, an oblique setup of two balls: their contact normal turns with their
/// tangential motion while every driver reads the normal trajectory along the fixed line of
/// the centres at the start.
pub(crate) fn refuse_two_oblique_balls(code: &str, setup: &CodeSetup) -> Result<(), CodeError> {
    if setup.oblique.is_some() && setup.scene != crate::model::scene::SceneKind::BallPlate {
        return Err(setup.unsupported(
            code,
            "an oblique ball_ball case turns the contact normal, and the codes' trajectories are \
             read along the line of the centres at the start: the DEM codes run oblique \
             ball_plate cases (`millimpact run` integrates this one)",
        ));
    }
    Ok(())
}

/// Refuses an oblique setup that `driver`'s build does not render, or that no build runs
/// ([`refuse_two_oblique_balls`]).
pub(crate) fn refuse_oblique(driver: &dyn CodeDriver, setup: &CodeSetup) -> Result<(), CodeError> {
    if setup.oblique.is_none() {
        return Ok(());
    }
    refuse_two_oblique_balls(driver.name(), setup)?;
    if !driver.runs_oblique() {
        let builds = super::CodeName::oblique_builds();
        return Err(setup.unsupported(
            driver.name(),
            format!(
                "this build does not run an oblique impact; the builds that do: {}",
                builds.join(", ")
            ),
        ));
    }
    Ok(())
}

/// `run` as a run of `setup` is read: its whole trajectory, no more rows and no fewer than
/// `driver` writes for it (`file` names the trajectory in the error), and one that holds
/// together.
pub(crate) fn whole_trajectory(
    driver: &dyn CodeDriver,
    setup: &CodeSetup,
    run: ParsedRun,
    file: impl FnOnce() -> String,
) -> Result<ParsedRun, ParseError> {
    let rows = run.trajectory.time.len() as u64;
    let expected = driver.trajectory_rows(setup);
    if rows != expected {
        return Err(ParseError::RowCount {
            file: file(),
            rows,
            expected,
        });
    }
    check_trajectory(&run.trajectory)?;
    Ok(run)
}

/// Most bytes of a code's log kept: its first and last halves, with a line saying what was cut.
pub const MAX_LOG_BYTES: usize = 1 << 20;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_codes_own_error_line_is_passed_on() {
        let log = "LIGGGHTS (Version LIGGGHTS-PUBLIC 3.8.0)\n  ERROR: model paper: 0 <= lossCoefficient < 1 required (eta = 1.2) (normal_model_paper.h:83)\nLast command: run 1\n";
        let said = error_line(log);
        assert_eq!(
            said.as_deref(),
            Some(
                "ERROR: model paper: 0 <= lossCoefficient < 1 required (eta = 1.2) (normal_model_paper.h:83)"
            )
        );
        assert_eq!(error_line("Traceback (most recent call last):\n"), None);
        let crashed = CodeError::Crashed {
            code: "liggghts-paper".into(),
            status: "exit status: 1".into(),
            said,
            log: PathBuf::from("/tmp/x/log.txt"),
        };
        assert_eq!(
            crashed.to_string(),
            "liggghts-paper: exited with exit status: 1, saying `ERROR: model paper: 0 <= lossCoefficient < 1 required (eta = 1.2) (normal_model_paper.h:83)`; log kept in /tmp/x/log.txt"
        );
    }
}
