//! Starting a code: the one way every run of an external code is made (a single impact, a
//! batch, YADE's reading of a script, a LAMMPS probe, a mill run). A scratch folder with the
//! input written in it, the code's standard output and error in its `log.txt`, the code in a
//! process group of its own under a time limit, and the folder removed afterwards unless the
//! caller keeps it (with its log, to point at, after a failure).
//!
//! Only this module starts a code, so that every code running is in the registry that a stop of
//! millimpact ends ([`stop_all_codes`]).

use std::ffi::OsString;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use thiserror::Error;

use super::{CodeError, MAX_LOG_BYTES, error_line, last_error_line};
use crate::codes::{Executable, ParseError};

/// The log's file name in the scratch folder.
pub(crate) const LOG_FILE: &str = "log.txt";

/// coreutils' library behind `stdbuf`, which sets a program's standard streams' buffering.
const LINE_BUFFERING: &str = "/usr/libexec/coreutils/libstdbuf.so";

/// How a code's standard output reaches its log, and so which of its `ERROR` lines a crash
/// quotes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Output {
    /// As the code buffers it; a crash quotes the first `ERROR` line ([`error_line`]).
    AsIs,
    /// Line-buffered (coreutils' `stdbuf -oL`, preloaded, where it is installed). LIGGGHTS
    /// stops on a fault found by one process (`error->one`: too many sorting bins, a particle
    /// lost) with `MPI_Abort`, which drops what its buffered standard output still holds, its
    /// `ERROR` line among it, and writes no log file of its own: line-buffered, the kept log
    /// has the code's reason. A crash quotes the last `ERROR` line, the one that stopped it
    /// (an earlier one may be a warning's echo).
    LineBuffered,
}

/// The step of starting a code that failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Step {
    /// Creating the folder the scratch folder is made in.
    Parent,
    /// Creating the scratch folder.
    Scratch,
    /// Writing the input.
    Input,
    /// Creating the log.
    Log,
    /// Duplicating the log's handle for standard error.
    DuplicateLog,
    /// Starting the program.
    Start,
    /// Waiting for it.
    Wait,
    /// Reading the log.
    ReadLog,
}

impl Step {
    /// What was being done, as a [`CodeError::Io`] says it.
    pub(crate) fn context(self) -> &'static str {
        match self {
            Step::Parent => "creating the scratch parent",
            Step::Scratch => "creating a scratch directory",
            Step::Input => "writing the input",
            Step::Log => "creating the log",
            Step::DuplicateLog => "duplicating the log handle",
            Step::Start => "starting the code",
            Step::Wait => "waiting for the code",
            Step::ReadLog => "reading the log",
        }
    }

    /// What was being done, as the words before the path of [`ProcessError`]'s message.
    pub(crate) fn doing(self) -> &'static str {
        match self {
            Step::Parent | Step::Log => "creating",
            Step::Scratch => "creating a scratch directory in",
            Step::Input => "writing",
            Step::DuplicateLog => "duplicating",
            Step::Start => "starting",
            Step::Wait => "waiting for",
            Step::ReadLog => "reading",
        }
    }
}

/// A step of starting a code failed: the scratch folder, the input, the log, the start or the
/// wait.
#[derive(Debug, Error)]
#[error("{} {}: {source}", step.doing(), path.display())]
pub(crate) struct ProcessError {
    /// The step.
    pub step: Step,
    /// The file, folder or program concerned.
    pub path: PathBuf,
    /// The error.
    pub source: std::io::Error,
}

impl ProcessError {
    /// The fault of `code` it is, in the words of [`Step::context`].
    pub(crate) fn code_error(self, code: &str) -> CodeError {
        self.code_error_saying(code, |_| None)
    }

    /// The fault of `code` it is, in `own` words for the steps it names and in those of
    /// [`Step::context`] for the others.
    pub(crate) fn code_error_saying(
        self,
        code: &str,
        own: impl Fn(Step) -> Option<&'static str>,
    ) -> CodeError {
        CodeError::Io {
            code: code.to_string(),
            context: own(self.step).unwrap_or(self.step.context()).to_string(),
            source: self.source,
        }
    }
}

/// One start of a code: what it runs, with what, where and for how long.
pub(crate) struct Process<'a> {
    executable: &'a Executable,
    args: &'a [String],
    input: (&'a str, &'a str),
    time_limit: Duration,
    prefix: &'a str,
    parent: Option<&'a Path>,
    links: Vec<(OsString, PathBuf)>,
    output: Output,
}

impl<'a> Process<'a> {
    /// `executable` started with `args` in a fresh scratch folder named from `prefix`, in the
    /// system's temporary folder, with `input` (file name, text) written in it, and killed
    /// past `time_limit`.
    pub(crate) fn new(
        executable: &'a Executable,
        args: &'a [String],
        input: (&'a str, &'a str),
        time_limit: Duration,
        prefix: &'a str,
    ) -> Self {
        Process {
            executable,
            args,
            input,
            time_limit,
            prefix,
            parent: None,
            links: Vec::new(),
            output: Output::AsIs,
        }
    }

    /// The scratch folder made in `parent`, which is created if it is missing.
    pub(crate) fn in_folder(mut self, parent: &'a Path) -> Self {
        self.parent = Some(parent);
        self
    }

    /// Entries of other folders linked into the scratch folder (name there, what it leads
    /// to); one that cannot be linked is left out.
    pub(crate) fn linking(mut self, links: Vec<(OsString, PathBuf)>) -> Self {
        self.links = links;
        self
    }

    /// How its standard output reaches the log.
    pub(crate) fn output(mut self, output: Output) -> Self {
        self.output = output;
        self
    }

    /// Start it and wait for it to end, by itself or at the time limit.
    pub(crate) fn run(self) -> Result<Ran, ProcessError> {
        let failed = |step: Step, path: &Path| {
            let path = path.to_path_buf();
            move |source| ProcessError { step, path, source }
        };
        let mut scratch = tempfile::Builder::new();
        scratch.prefix(self.prefix);
        let scratch = match self.parent {
            Some(parent) => {
                std::fs::create_dir_all(parent).map_err(failed(Step::Parent, parent))?;
                scratch.tempdir_in(parent)
            }
            None => scratch.tempdir(),
        }
        .map_err(failed(
            Step::Scratch,
            &self
                .parent
                .map_or_else(std::env::temp_dir, Path::to_path_buf),
        ))?;
        let folder = scratch.path();
        #[cfg(unix)]
        for (name, target) in &self.links {
            let _ = std::os::unix::fs::symlink(target, folder.join(name));
        }
        let input = folder.join(self.input.0);
        std::fs::write(&input, self.input.1).map_err(failed(Step::Input, &input))?;
        let log_path = folder.join(LOG_FILE);
        let log = File::create(&log_path).map_err(failed(Step::Log, &log_path))?;
        let log_err = log
            .try_clone()
            .map_err(failed(Step::DuplicateLog, &log_path))?;
        let mut command = self.executable.command();
        if self.output == Output::LineBuffered && Path::new(LINE_BUFFERING).is_file() {
            command
                .env("LD_PRELOAD", LINE_BUFFERING)
                .env("_STDBUF_O", "L");
        }
        command
            .args(self.args)
            .current_dir(folder)
            .stdin(Stdio::null())
            .stdout(Stdio::from(log))
            .stderr(Stdio::from(log_err));
        let program = &self.executable.program;
        let started = Instant::now();
        let mut child =
            spawn_contained(&mut command, folder).map_err(failed(Step::Start, program))?;
        let status =
            wait_contained(&mut child, self.time_limit).map_err(failed(Step::Wait, program))?;
        Ok(Ran {
            wall_time: started.elapsed().as_secs_f64(),
            status,
            scratch,
            time_limit: self.time_limit,
            output: self.output,
        })
    }
}

/// A code's run that ended, by itself or at its time limit. Its scratch folder is removed when
/// this is dropped, unless it is kept.
#[derive(Debug)]
pub(crate) struct Ran {
    scratch: tempfile::TempDir,
    /// How the code exited; `None` when it was killed at the time limit.
    pub status: Option<ExitStatus>,
    /// Process wall time, s.
    pub wall_time: f64,
    time_limit: Duration,
    output: Output,
}

impl Ran {
    /// The scratch folder, where the code ran.
    pub(crate) fn folder(&self) -> &Path {
        self.scratch.path()
    }

    /// The code's combined standard output and error (capped at [`MAX_LOG_BYTES`]).
    pub(crate) fn log(&self) -> Result<String, ProcessError> {
        let path = self.folder().join(LOG_FILE);
        read_log(&path).map_err(|source| ProcessError {
            step: Step::ReadLog,
            path,
            source,
        })
    }

    /// Keep the scratch folder; its path.
    pub(crate) fn keep(self) -> PathBuf {
        self.scratch.keep()
    }

    /// Keep the scratch folder; the path of its log.
    pub(crate) fn keep_log(self) -> PathBuf {
        self.keep().join(LOG_FILE)
    }

    /// The run killed at its time limit, as a fault of `code`, with its scratch folder kept.
    pub(crate) fn timed_out(self, code: &str) -> CodeError {
        CodeError::TimedOut {
            code: code.to_string(),
            seconds: self.time_limit.as_secs_f64(),
            log: self.keep_log(),
        }
    }

    /// The run that exited with the failure `status`, `said` being the code's own reason, as a
    /// fault of `code`, with its scratch folder kept.
    pub(crate) fn crashed(self, code: &str, status: ExitStatus, said: Option<String>) -> CodeError {
        CodeError::Crashed {
            code: code.to_string(),
            status: status.to_string(),
            said,
            log: self.keep_log(),
        }
    }

    /// The run whose output could not be read, for `reason`, as a fault of `code`, with its
    /// scratch folder kept.
    pub(crate) fn unparsable(self, code: &str, reason: ParseError) -> CodeError {
        CodeError::Unparsable {
            code: code.to_string(),
            reason,
            log: self.keep_log(),
        }
    }

    /// The run and its log where the code exited well; else the fault of `code` it is, killed
    /// at the time limit or crashed (with the `ERROR` line its [`Output`] says to quote), its
    /// scratch folder kept.
    pub(crate) fn succeeded(self, code: &str) -> Result<(Ran, String), CodeError> {
        let Some(status) = self.status else {
            return Err(self.timed_out(code));
        };
        let log = self.log().map_err(|e| e.code_error(code))?;
        if !status.success() {
            let said = match self.output {
                Output::AsIs => error_line(&log),
                Output::LineBuffered => last_error_line(&log),
            };
            return Err(self.crashed(code, status, said));
        }
        Ok((self, log))
    }
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
fn spawn_contained(command: &mut Command, scratch: &Path) -> std::io::Result<Child> {
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
fn wait_contained(child: &mut Child, timeout: Duration) -> std::io::Result<Option<ExitStatus>> {
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

/// Read a code's log as text whatever bytes it holds (invalid UTF-8 is replaced, not an error),
/// and cap the kept file at [`MAX_LOG_BYTES`], keeping its head and tail.
fn read_log(path: &Path) -> std::io::Result<String> {
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
