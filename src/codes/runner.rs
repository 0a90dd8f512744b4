//! Running an installed code: a scratch directory, a time limit, the log kept on any fault.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use thiserror::Error;

use super::parse::ParseError;
use super::setup::CodeSetup;
use super::{CodeDriver, Executable};
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
}

/// Time limit and scratch location for [`run_code`].
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Kill the code after this long.
    pub timeout: Duration,
    /// Parent directory for scratch directories (the system temp dir by default).
    pub scratch_parent: Option<PathBuf>,
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

/// Render, run and parse one impact in `driver`'s code.
///
/// The scratch directory is removed after a good run and kept, with its `log.txt`, after any
/// failure, so that the error can point at it.
pub fn run_code(
    driver: &dyn CodeDriver,
    setup: &CodeSetup,
    options: &RunOptions,
) -> Result<CodeRun, CodeError> {
    let code = driver.name().to_string();
    let io_error = |context: &str| {
        let code = code.clone();
        let context = context.to_string();
        move |source| CodeError::Io {
            code,
            context,
            source,
        }
    };
    let executable = driver.locate().map_err(|looked| CodeError::MissingBinary {
        code: code.clone(),
        looked,
    })?;
    check_conventions(driver, &executable, std::slice::from_ref(setup))?;
    let input = driver.render(setup)?;
    let parent = options
        .scratch_parent
        .clone()
        .unwrap_or_else(std::env::temp_dir);
    std::fs::create_dir_all(&parent).map_err(io_error("creating the scratch parent"))?;
    let scratch = tempfile::Builder::new()
        .prefix(&format!("millimpact-{}-{}-", code, setup.case_name))
        .tempdir_in(&parent)
        .map_err(io_error("creating a scratch directory"))?;
    let workdir = scratch.path().to_path_buf();
    std::fs::write(workdir.join(&input.file_name), &input.text)
        .map_err(io_error("writing the input"))?;
    let log_path = workdir.join("log.txt");
    let log_file = std::fs::File::create(&log_path).map_err(io_error("creating the log"))?;
    let log_err = log_file
        .try_clone()
        .map_err(io_error("duplicating the log handle"))?;

    let started = Instant::now();
    let mut child = executable.command();
    child
        .args(&input.args)
        .current_dir(&workdir)
        .stdin(Stdio::null())
        .stdout(Stdio::from(log_file))
        .stderr(Stdio::from(log_err));
    let mut child = spawn_contained(&mut child, &workdir).map_err(io_error("starting the code"))?;
    let status =
        wait_contained(&mut child, options.timeout).map_err(io_error("waiting for the code"))?;
    let wall_time = started.elapsed().as_secs_f64();
    let keep = |scratch: tempfile::TempDir| scratch.keep().join("log.txt");
    let status = match status {
        Some(status) => status,
        None => {
            return Err(CodeError::TimedOut {
                code,
                seconds: options.timeout.as_secs_f64(),
                log: keep(scratch),
            });
        }
    };
    let log = read_log(&log_path).map_err(io_error("reading the log"))?;
    if !status.success() {
        return Err(CodeError::Crashed {
            code,
            status: status.to_string(),
            said: error_line(&log),
            log: keep(scratch),
        });
    }
    let parsed = match driver.parse(setup, &workdir, &log) {
        Ok(parsed) => parsed,
        Err(reason) => {
            return Err(CodeError::Unparsable {
                code,
                reason,
                log: keep(scratch),
            });
        }
    };
    let rows = parsed.trajectory.time.len() as u64;
    let expected = driver.trajectory_rows(setup);
    if rows != expected {
        return Err(CodeError::Unparsable {
            code,
            reason: ParseError::RowCount {
                file: "the trajectory".to_string(),
                rows,
                expected,
            },
            log: keep(scratch),
        });
    }
    if let Err(reason) = check_trajectory(&parsed.trajectory) {
        return Err(CodeError::Unparsable {
            code,
            reason: reason.into(),
            log: keep(scratch),
        });
    }
    Ok(CodeRun {
        code,
        code_version: parsed.version.unwrap_or_else(|| "unknown".to_string()),
        input: input.text,
        trajectory: parsed.trajectory,
        wall_time,
        loop_time: parsed.loop_time,
        log,
    })
}

/// The process groups of the codes running now, with their scratch directories: what
/// [`stop_all_codes`] ends when millimpact itself is stopped.
static LIVE: Mutex<Vec<(i32, PathBuf)>> = Mutex::new(Vec::new());

/// Set once millimpact is exiting on a stop: from then on no code starts, and a code that ends is
/// not reported as failed (it was stopped), so that the stop's own clean-up and exit are what
/// happen.
static STOPPING: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Wait, without return, for the stop in progress to exit the process.
fn await_stop() -> ! {
    loop {
        std::thread::park();
    }
}

/// Start `command` in a process group of its own, so that the code and every process it starts
/// can be ended together, and register it with its scratch directory `scratch`.
pub(crate) fn spawn_contained(command: &mut Command, scratch: &Path) -> std::io::Result<Child> {
    #[cfg(unix)]
    std::os::unix::process::CommandExt::process_group(command, 0);
    // Open MPI processes started alone (the Debian LIGGGHTS and LAMMPS) all put their session
    // directory at the same place under TMPDIR (`ompi.<host>.<uid>/jf.0/1`), and two starting at
    // once race on it: one fails `MPI_Init` ("mkdir ... File exists"). The run's own scratch
    // folder as its TMPDIR gives each process its own, and goes with the scratch folder.
    command.env("TMPDIR", scratch);
    let mut live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
    if STOPPING.load(std::sync::atomic::Ordering::SeqCst) {
        drop(live);
        await_stop();
    }
    let child = command.spawn()?;
    if let Ok(pid) = i32::try_from(child.id()) {
        live.push((pid, scratch.to_path_buf()));
    }
    Ok(child)
}

/// Wait for a contained code at most `timeout`; past it, kill its whole process group (the code
/// and any process it started, whatever signals they ignore) and return `None`.
pub(crate) fn wait_contained(
    child: &mut Child,
    timeout: Duration,
) -> std::io::Result<Option<ExitStatus>> {
    let status = wait_timeout::ChildExt::wait_timeout(child, timeout);
    if STOPPING.load(std::sync::atomic::Ordering::SeqCst) {
        // The code ended because millimpact is being stopped: not a fault of the code to report.
        await_stop();
    }
    let pid = i32::try_from(child.id()).unwrap_or(0);
    if !matches!(status, Ok(Some(_))) {
        kill_group(pid);
        let _ = child.kill();
        let _ = child.wait();
    }
    // The group may hold processes the code left behind: they go with it.
    kill_group(pid);
    LIVE.lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|(p, _)| *p != pid);
    status
}

fn kill_group(pid: i32) {
    #[cfg(unix)]
    if pid > 0 {
        // SAFETY: kill(2) with a negative pid signals the process group; no memory is shared.
        unsafe {
            libc::kill(-pid, libc::SIGKILL);
        }
    }
}

/// The environment variable that keeps the scratch directories of codes stopped by a Ctrl-C or
/// SIGTERM of millimpact (any value but empty or `0`), to read what a stopped run had written.
pub(crate) const KEEP_SCRATCH_VARIABLE: &str = "MILLIMPACT_KEEP_SCRATCH";

/// End every code running now (their whole process groups) and remove their scratch
/// directories, or keep them (each named on standard error) when [`KEEP_SCRATCH_VARIABLE`] asks.
/// The runs they belonged to end as failed runs; millimpact goes on (a sweep keeps its rows).
pub(crate) fn stop_all_codes() {
    stop_codes(false);
}

/// Stop millimpact: no code starts from now on, every code running ends as [`stop_all_codes`]
/// ends it (and is not reported as a failure of its own), and the process exits with `code`.
/// What a Ctrl-C or SIGTERM of millimpact does.
pub(crate) fn stop_all_codes_and_exit(code: i32) -> ! {
    stop_codes(true);
    std::process::exit(code);
}

fn stop_codes(exiting: bool) {
    let keep = std::env::var_os(KEEP_SCRATCH_VARIABLE).is_some_and(|v| !v.is_empty() && v != "0");
    let live = {
        let mut live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
        if exiting {
            STOPPING.store(true, std::sync::atomic::Ordering::SeqCst);
        }
        std::mem::take(&mut *live)
    };
    for (pid, scratch) in live {
        kill_group(pid);
        if keep {
            eprintln!("stopped: scratch kept in {}", scratch.display());
        } else {
            let _ = std::fs::remove_dir_all(scratch);
        }
    }
}

/// Most bytes of a code's log kept: its first and last halves, with a line saying what was cut.
pub const MAX_LOG_BYTES: usize = 1 << 20;

/// Read a code's log as text whatever bytes it holds (invalid UTF-8 is replaced, not an error),
/// and cap the kept file at [`MAX_LOG_BYTES`], keeping its head and tail.
pub(crate) fn read_log(path: &Path) -> std::io::Result<String> {
    let bytes = std::fs::read(path)?;
    if bytes.len() <= MAX_LOG_BYTES {
        return Ok(String::from_utf8_lossy(&bytes).into_owned());
    }
    let half = MAX_LOG_BYTES / 2;
    let mut kept = bytes[..half].to_vec();
    kept.extend_from_slice(
        format!(
            "\n[millimpact: {} bytes of this log cut; the first and last {half} kept]\n",
            bytes.len() - 2 * half
        )
        .as_bytes(),
    );
    kept.extend_from_slice(&bytes[bytes.len() - half..]);
    std::fs::write(path, &kept)?;
    Ok(String::from_utf8_lossy(&kept).into_owned())
}

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
