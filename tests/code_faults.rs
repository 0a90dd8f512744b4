//! Faults of the external codes: a missing binary, a crash, a time-out and unparsable output
//! each give a clear error naming the code and keeping its log. A fake binary placed first on
//! PATH plays the faulty code; everything else is real.

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};

mod common;

use common::millimpact;
use predicates::prelude::*;
use tempfile::TempDir;

fn fake_binary(dir: &Path, name: &str, script: &str) {
    let path = dir.join(name);
    std::fs::write(&path, format!("#!/bin/sh\n{script}\n")).unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
}

fn path_with(dir: &Path) -> String {
    format!(
        "{}:{}",
        dir.display(),
        std::env::var("PATH").unwrap_or_default()
    )
}

/// Run millimpact with `bin` first on PATH and scratch directories under `scratch`; expect exit
/// code 1 and return the standard error.
fn failing_run(bin: &Path, scratch: &Path, args: &[&str]) -> String {
    let out = millimpact()
        .env("PATH", path_with(bin))
        .env("TMPDIR", scratch)
        .args(args)
        .assert()
        .code(1)
        .get_output()
        .clone();
    String::from_utf8(out.stderr).unwrap()
}

/// The log file named in an error message, which must exist.
fn kept_log(stderr: &str) -> PathBuf {
    let at = stderr
        .find("log kept in ")
        .expect("the error names the kept log")
        + 12;
    let path = PathBuf::from(stderr[at..].lines().next().unwrap().trim());
    assert!(path.is_file(), "kept log {} exists", path.display());
    path
}

#[test]
fn missing_binary_names_the_code_and_the_binary() {
    let empty = TempDir::new().unwrap();
    for (code, binary) in [
        ("liggghts", "liggghts"),
        ("yade", "yade"),
        ("lammps", "lmp"),
    ] {
        let out = millimpact()
            .env("PATH", empty.path())
            .args(["reference", "--code", code, "cases/ball_plate.toml"])
            .assert()
            .code(1)
            .get_output()
            .clone();
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(
            stderr.contains(&format!("{code}: binary `{binary}` not found on PATH")),
            "{stderr}"
        );
        assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
    }
}

/// A user's own build is named by `MILLIMPACT_<CODE>_BINARY`: a path that is not a file is
/// refused with the variable named, and a file there is what runs (PATH is not consulted).
#[test]
fn a_build_named_by_its_variable_is_the_one_that_runs() {
    let empty = TempDir::new().unwrap();
    let out = millimpact()
        .env("MILLIMPACT_LAMMPS_BINARY", empty.path().join("no-such-lmp"))
        .args(["reference", "--code", "lammps", "cases/ball_plate.toml"])
        .assert()
        .code(1)
        .get_output()
        .clone();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains("lammps: MILLIMPACT_LAMMPS_BINARY=")
            && stderr.contains("no-such-lmp is not a file"),
        "{stderr}"
    );
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    fake_binary(bin.path(), "my-lmp", "echo 'my own lammps build'; exit 3");
    let out = millimpact()
        .env("MILLIMPACT_LAMMPS_BINARY", bin.path().join("my-lmp"))
        .env("PATH", empty.path())
        .env("TMPDIR", scratch.path())
        .args(["reference", "--code", "lammps", "cases/ball_plate.toml"])
        .assert()
        .code(1)
        .get_output()
        .clone();
    let stderr = String::from_utf8(out.stderr).unwrap();
    let log = std::fs::read_to_string(kept_log(&stderr)).unwrap();
    assert!(log.contains("my own lammps build"), "{log}");
}

#[test]
fn crash_keeps_the_log() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    fake_binary(
        bin.path(),
        "liggghts",
        "echo 'ERROR: segmentation fault in fix wall/gran'; exit 3",
    );
    let stderr = failing_run(
        bin.path(),
        scratch.path(),
        &["reference", "--code", "liggghts", "cases/ball_plate.toml"],
    );
    assert!(
        stderr.contains("liggghts: exited with exit status: 3"),
        "{stderr}"
    );
    let log = std::fs::read_to_string(kept_log(&stderr)).unwrap();
    assert!(log.contains("segmentation fault"), "{log}");
}

#[test]
fn time_out_kills_the_code_and_keeps_the_log() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    fake_binary(
        bin.path(),
        "lmp",
        "echo 'LAMMPS (fake) starting'; exec sleep 30",
    );
    let started = std::time::Instant::now();
    let out = millimpact()
        .env("PATH", path_with(bin.path()))
        .env("TMPDIR", scratch.path())
        .args([
            "reference",
            "--code",
            "lammps",
            "cases/rod_end.toml",
            "--timeout",
            "1",
        ])
        .assert()
        .code(1)
        .get_output()
        .clone();
    assert!(
        started.elapsed().as_secs_f64() < 20.0,
        "the code was killed"
    );
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains("lammps: killed after the time limit of 1 s"),
        "{stderr}"
    );
    let log = std::fs::read_to_string(kept_log(&stderr)).unwrap();
    assert!(log.contains("LAMMPS (fake) starting"), "{log}");
}

#[test]
fn unparsable_output_keeps_the_log() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    // Exits cleanly but writes no trajectory, only noise.
    fake_binary(
        bin.path(),
        "yade",
        "echo 'Welcome to Yade (fake)'; echo 'garbage 1 2 x'",
    );
    let stderr = failing_run(
        bin.path(),
        scratch.path(),
        &["reference", "--code", "yade", "cases/ball_ball.toml"],
    );
    assert!(stderr.contains("yade: unparsable output"), "{stderr}");
    let log = std::fs::read_to_string(kept_log(&stderr)).unwrap();
    assert!(log.contains("garbage 1 2 x"), "{log}");
}

#[test]
#[ignore = "live: runs LIGGGHTS, YADE, LAMMPS 2025 and Kratos (bash scripts/test.sh)"]
fn a_failing_code_loses_nothing_the_others_computed() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    fake_binary(bin.path(), "lmp", "echo 'fake lammps dies'; exit 1");
    millimpact()
        .env("PATH", path_with(bin.path()))
        .env("TMPDIR", scratch.path())
        .args(["compare", "--live", "cases/rod_end.toml"])
        .assert()
        .code(1)
        .stdout(
            predicate::str::contains("liggghts")
                .and(predicate::str::contains("yade 2023"))
                .and(predicate::str::contains("missing: lammps: lammps: exited")),
        )
        .stderr(predicate::str::contains("compare --live: lammps"));
}

#[test]
fn a_fault_writes_no_reference_file() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    let store = TempDir::new().unwrap();
    fake_binary(bin.path(), "liggghts", "exit 9");
    millimpact()
        .env("PATH", path_with(bin.path()))
        .env("TMPDIR", scratch.path())
        .args([
            "reference",
            "--code",
            "liggghts",
            "cases/ball_plate.toml",
            "--save",
        ])
        .arg("--reference")
        .arg(store.path())
        .assert()
        .code(1);
    assert_eq!(std::fs::read_dir(store.path()).unwrap().count(), 0);
}

/// Whether process `pid` still exists (a zombie counts as gone).
fn alive(pid: i32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .map(|stat| !stat.contains(") Z "))
        .unwrap_or(false)
}

#[test]
fn a_time_out_ends_the_codes_whole_process_group() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    let pids = scratch.path().join("pids");
    // The code starts a helper that ignores SIGTERM, then both hang.
    fake_binary(
        bin.path(),
        "lmp",
        &format!(
            "sh -c 'trap \"\" TERM; echo $$ >> {p}; sleep 300' &\necho $$ >> {p}\nsleep 300",
            p = pids.display()
        ),
    );
    let stderr = failing_run(
        bin.path(),
        scratch.path(),
        &[
            "reference",
            "--code",
            "lammps",
            "cases/ball_plate.toml",
            "--timeout",
            "1",
        ],
    );
    assert!(stderr.contains("killed after the time limit"), "{stderr}");
    kept_log(&stderr);
    let started: Vec<i32> = std::fs::read_to_string(&pids)
        .unwrap()
        .lines()
        .map(|l| l.trim().parse().unwrap())
        .collect();
    // The probe's basic deck runs the build first (and is killed at its own limit), then the
    // impact: each start is the code and its helper, and none may outlive the run.
    assert!(
        started.len() >= 2 && started.len().is_multiple_of(2),
        "the code and its helper started: {started:?}"
    );
    std::thread::sleep(std::time::Duration::from_millis(200));
    for pid in started {
        assert!(!alive(pid), "process {pid} outlived the run");
    }
}

#[test]
fn output_that_is_not_utf8_keeps_the_log_and_the_exit_status() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    fake_binary(
        bin.path(),
        "lmp",
        "printf 'LAMMPS \\377\\376 broken\\n'\nexit 3",
    );
    let stderr = failing_run(
        bin.path(),
        scratch.path(),
        &["reference", "--code", "lammps", "cases/ball_plate.toml"],
    );
    assert!(stderr.contains("exited with exit status: 3"), "{stderr}");
    assert!(!stderr.contains("UTF-8"), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let log = std::fs::read(kept_log(&stderr)).unwrap();
    assert!(
        log.windows(2).any(|w| w == [0xff, 0xfe]),
        "the bytes are kept as written"
    );
}

#[test]
fn an_oversized_log_is_kept_as_its_head_and_tail() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    // About 4 MB of output, then a failure.
    fake_binary(
        bin.path(),
        "lmp",
        "echo FIRST-LINE\nyes 'chatter chatter chatter chatter' | head -c 4000000\necho\necho LAST-LINE\nexit 1",
    );
    let stderr = failing_run(
        bin.path(),
        scratch.path(),
        &["reference", "--code", "lammps", "cases/ball_plate.toml"],
    );
    let log = std::fs::read_to_string(kept_log(&stderr)).unwrap();
    assert!(
        log.len() <= millimpact::codes::runner::MAX_LOG_BYTES + 200,
        "{}",
        log.len()
    );
    assert!(log.starts_with("FIRST-LINE") && log.trim_end().ends_with("LAST-LINE"));
    assert!(log.contains("bytes of this log cut"), "the cut is said");
}

/// A run cut short (here: a LIGGGHTS, which no probe runs before, that writes three rows and
/// exits 0, as a full disk or a killed writer would leave it) is refused by its row count, with
/// the log kept, however the rows it has look: whether the contact had ended in them or not.
#[test]
fn a_truncated_trajectory_is_refused_with_its_log() {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    for (label, rows) in [
        (
            "in contact",
            "0 -1e-9 2 0\n1e-7 1e-7 2 5\n2e-7 2e-7 1.9 9\n",
        ),
        (
            "after the contact",
            "0 -1e-9 2 0\n1e-7 1e-7 2 5\n2e-7 -1e-7 -1.4 0\n",
        ),
    ] {
        fake_binary(
            bin.path(),
            "liggghts",
            &format!(
                "echo 'LIGGGHTS (fake, {label})'; printf '{}' > traj.txt",
                rows.replace('\n', "\\n")
            ),
        );
        let stderr = failing_run(
            bin.path(),
            scratch.path(),
            &["reference", "--code", "liggghts", "cases/ball_plate.toml"],
        );
        assert!(
            stderr.contains("liggghts: unparsable output: the trajectory has 3 rows, expected"),
            "{label}: {stderr}"
        );
        let log = std::fs::read_to_string(kept_log(&stderr)).unwrap();
        assert!(log.contains(label), "{log}");
    }
}

/// A full disk under standard output is one line and exit 1; a reader that has gone (`| head`)
/// ends the command quietly with 141, as a shell pipeline expects; neither panics.
#[test]
fn broken_pipes_and_full_disks_are_one_line_not_a_panic() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_millimpact"))
        .arg("verify")
        .current_dir(common::root())
        .stdout(full)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(
        stderr.trim(),
        "error: writing standard output: No space left on device (os error 28)"
    );
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_millimpact"))
        .args(["stability", "--format", "json"])
        .current_dir(common::root())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(141), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// Start `reference --code liggghts` with a fake LIGGGHTS that starts a helper ignoring SIGTERM
/// and hangs; once both are up, stop millimpact with SIGTERM. Returns millimpact's exit code,
/// its standard error, the code's and the helper's pids, and the scratch parent.
fn stop_during_a_run(keep_scratch: bool) -> (Option<i32>, String, Vec<i32>, TempDir) {
    let bin = TempDir::new().unwrap();
    let scratch = TempDir::new().unwrap();
    let pids = bin.path().join("pids");
    fake_binary(
        bin.path(),
        "liggghts",
        &format!(
            "sh -c 'trap \"\" TERM; echo $$ >> {p}; sleep 300' &\necho $$ >> {p}\nsleep 300",
            p = pids.display()
        ),
    );
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_millimpact"));
    command
        .current_dir(common::root())
        .env("PATH", path_with(bin.path()))
        .env("TMPDIR", scratch.path())
        .args(["reference", "--code", "liggghts", "cases/ball_plate.toml"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped());
    if keep_scratch {
        command.env("MILLIMPACT_KEEP_SCRATCH", "1");
    } else {
        command.env_remove("MILLIMPACT_KEEP_SCRATCH");
    }
    let child = command.spawn().unwrap();
    let started = || {
        std::fs::read_to_string(&pids)
            .map(|t| t.lines().count())
            .unwrap_or(0)
    };
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
    while started() < 2 {
        assert!(
            std::time::Instant::now() < deadline,
            "the fake code never started"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // SAFETY: kill(2) on the child's pid; no memory is shared.
    unsafe {
        libc::kill(i32::try_from(child.id()).unwrap(), libc::SIGTERM);
    }
    let out = child.wait_with_output().unwrap();
    std::thread::sleep(std::time::Duration::from_millis(200));
    let started: Vec<i32> = std::fs::read_to_string(&pids)
        .unwrap()
        .lines()
        .map(|l| l.trim().parse().unwrap())
        .collect();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        started,
        scratch,
    )
}

/// A SIGTERM (or Ctrl-C) of millimpact ends the code's whole process group, helpers that ignore
/// SIGTERM included, and removes its scratch directory; `MILLIMPACT_KEEP_SCRATCH=1` keeps it
/// and says where.
#[test]
fn stopping_millimpact_ends_the_code_and_its_scratch() {
    let (code, stderr, started, scratch) = stop_during_a_run(false);
    assert_eq!(code, Some(130), "{stderr}");
    for pid in &started {
        assert!(!alive(*pid), "process {pid} outlived millimpact");
    }
    let left: Vec<_> = std::fs::read_dir(scratch.path())
        .unwrap()
        .flatten()
        .collect();
    assert!(left.is_empty(), "scratch left behind: {left:?}");

    let (code, stderr, started, scratch) = stop_during_a_run(true);
    assert_eq!(code, Some(130), "{stderr}");
    for pid in &started {
        assert!(!alive(*pid), "process {pid} outlived millimpact");
    }
    let kept = stderr
        .split("scratch kept in ")
        .nth(1)
        .map(|rest| PathBuf::from(rest.lines().next().unwrap().trim()))
        .unwrap_or_else(|| panic!("no kept scratch named: {stderr}"));
    assert!(
        kept.starts_with(scratch.path()) && kept.is_dir(),
        "{stderr}"
    );
    assert!(kept.join("impact.in").is_file() || std::fs::read_dir(&kept).unwrap().count() > 0);
}

/// `reference --code kratos` run by `binary` from `cwd`, with no codes' folder named: the
/// first line of its error (no process starts: the Kratos python is missing or broken).
fn kratos_error(binary: &Path, cwd: &Path) -> String {
    let out = std::process::Command::new(binary)
        .current_dir(cwd)
        .env_remove("MILLIMPACT_CODES_DIR")
        .env_remove("MILLIMPACT_KRATOS_BINARY")
        .args(["reference", "--code", "kratos"])
        .arg(common::case_path("ball_plate"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    stderr
}

/// The codes' folder is found when millimpact runs, not where it was built: the nearest
/// `.codes` in or above the working directory, else in or above the executable's folder.
#[test]
fn the_codes_folder_is_found_from_the_working_directory_then_the_executable() {
    let place = TempDir::new().unwrap();
    let place = place.path().canonicalize().unwrap();
    // A copy of the binary, as on a cluster: nothing of the build machine's paths is in it.
    let bin = place.join("install/bin");
    std::fs::create_dir_all(&bin).unwrap();
    let binary = bin.join("millimpact");
    std::fs::copy(env!("CARGO_BIN_EXE_millimpact"), &binary).unwrap();
    let elsewhere = place.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    let python = |codes: &Path| codes.join("kratos/bin/python").display().to_string();

    // None anywhere: the error says where it looked.
    let err = kratos_error(&binary, &elsewhere);
    assert!(
        err.contains(&format!(
            "no {} (no .codes in the working directory",
            python(&elsewhere.join(".codes"))
        )),
        "{err}"
    );

    // Beside the executable, or above its folder.
    let installed = place.join("install/.codes");
    std::fs::create_dir_all(&installed).unwrap();
    let err = kratos_error(&binary, &elsewhere);
    assert!(
        err.contains(&format!(
            "no {} (the codes' folder found beside millimpact's executable or above it",
            python(&installed)
        )),
        "{err}"
    );

    // A project's checkout, run from a folder inside it, comes first.
    let project = place.join("project");
    let results = project.join("results/eta");
    std::fs::create_dir_all(&results).unwrap();
    std::fs::create_dir_all(project.join(".codes")).unwrap();
    let err = kratos_error(&binary, &results);
    assert!(
        err.contains(&format!(
            "no {} (the codes' folder found in the working directory or above it",
            python(&project.join(".codes"))
        )),
        "{err}"
    );
}

/// A Kratos environment copied from another machine links to a Python that is not here: the
/// error says so and how to make it again, instead of a missing file.
#[test]
fn a_kratos_environment_made_on_another_machine_is_named_as_such() {
    let project = TempDir::new().unwrap();
    let project = project.path().canonicalize().unwrap();
    let bin = project.join(".codes/kratos/bin");
    std::fs::create_dir_all(&bin).unwrap();
    // As `python3 -m venv` makes them: python -> python3 -> the Python that made it.
    let gone = PathBuf::from("/nonexistent/build-machine/.pyenv/versions/3.11.7/bin/python3");
    std::os::unix::fs::symlink(&gone, bin.join("python3")).unwrap();
    std::os::unix::fs::symlink("python3", bin.join("python")).unwrap();
    let err = kratos_error(Path::new(env!("CARGO_BIN_EXE_millimpact")), &project);
    assert!(
        err.starts_with(&format!(
            "error: kratos: {} links to {}, which is not on this machine",
            bin.join("python").display(),
            gone.display()
        )),
        "{err}"
    );
    assert!(
        err.contains("make it again on this machine with bash scripts/install-dem-codes.sh"),
        "{err}"
    );
    assert!(err.contains("MILLIMPACT_KRATOS_BINARY"), "{err}");
}
