//! Sweep files: rows per point with a status, a failing point that does not stop the sweep,
//! resume after an interruption, shards merged (via GNU parallel), and the bound on live
//! code processes.

use std::collections::BTreeMap;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};

use assert_cmd::Command;
use tempfile::TempDir;

fn millimpact() -> Command {
    let mut cmd = Command::cargo_bin("millimpact").unwrap();
    cmd.current_dir(env!("CARGO_MANIFEST_DIR"));
    cmd.env_remove("CI");
    cmd
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A sweep file over η and radius by two methods, with one invalid η.
fn grid_file(dir: &Path) -> PathBuf {
    let path = dir.join("grid.toml");
    std::fs::write(
        &path,
        format!(
            "base = \"{}\"\n[axes]\nloss_coefficient = [0.0, 0.2, 0.35, 1.5, 0.6]\n\"ball.radius\" = [0.01, 0.03]\nmethod = [\"rk4-event\", \"dopri5\"]\nsteps_per_period = [200, 800]\n",
            root().join("cases/ball_plate.toml").display()
        ),
    )
    .unwrap();
    path
}

/// Rows of a CSV output keyed by their parameters (the columns up to `case`), each row's
/// cells by column, the timing columns left out.
fn rows_by_parameters(path: &Path) -> BTreeMap<Vec<String>, BTreeMap<String, String>> {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let headers: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let key_end = headers.iter().position(|h| h == "case").unwrap();
    let mut out = BTreeMap::new();
    for record in reader.records() {
        let record = record.unwrap();
        let cells: Vec<String> = record.iter().map(String::from).collect();
        let key = cells[2..key_end].to_vec();
        let figures = headers
            .iter()
            .zip(&cells)
            .filter(|(h, _)| !["wall_time", "loop_time", "whole_wall_time"].contains(&h.as_str()))
            .map(|(h, c)| (h.clone(), c.clone()))
            .collect();
        assert!(out.insert(key, figures).is_none(), "a point appears once");
    }
    out
}

fn run_sweep(file: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    millimpact()
        .arg("sweep")
        .arg(file)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn every_point_is_a_row_and_a_failing_point_does_not_stop_the_sweep() {
    let dir = TempDir::new().unwrap();
    let file = grid_file(dir.path());
    let out = dir.path().join("all.csv");
    let result = run_sweep(&file, &out, &[]);
    // Failed points make the sweep fail, once every point has its row.
    assert_eq!(result.status.code(), Some(1), "{result:?}");
    let rows = rows_by_parameters(&out);
    // 5 η × 2 radii × (rk4-event at 2 resolutions + dopri5).
    assert_eq!(rows.len(), 5 * 2 * 3);
    let failed: Vec<_> = rows.values().filter(|r| r["status"] != "ok").collect();
    assert_eq!(failed.len(), 2 * 3, "the η = 1.5 points");
    for r in &failed {
        assert_eq!(r["loss_coefficient"], "1.5");
        assert!(
            r["status"].contains("loss_coefficient = 1.5: must be in [0, 1)"),
            "{}",
            r["status"]
        );
    }
    for r in rows.values().filter(|r| r["status"] == "ok") {
        let error: f64 = r["cor_error"].parse().unwrap();
        assert!(error.abs() < 1e-3, "{r:?}");
        assert_eq!(r["eta"], r["loss_coefficient"]);
    }
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("6 of 30 points failed"), "{stderr}");
}

/// The lines `summary` lists after `lines ` (up to `;`), as numbers.
fn listed_lines(summary: &str) -> Vec<usize> {
    let at = summary.find(", line").expect("the summary lists lines") + 6;
    let rest = summary[at..].trim_start_matches('s').trim_start();
    rest[..rest.find(';').unwrap()]
        .split(", ")
        .map(|n| n.parse().unwrap())
        .collect()
}

#[test]
fn failed_points_exit_1_saying_how_many_and_on_which_lines_unless_failures_are_allowed() {
    let dir = TempDir::new().unwrap();
    let file = grid_file(dir.path());
    for format in ["csv", "jsonl"] {
        let out = dir.path().join(format!("failing.{format}"));
        let result = run_sweep(&file, &out, &["--format", format, "--jobs", "2"]);
        assert_eq!(result.status.code(), Some(1), "{result:?}");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
        let line = stderr.trim_end();
        assert!(
            line.starts_with(&format!(
                "error: 6 of 30 points failed; their errors are in the status column of {}, lines ",
                out.display()
            )),
            "{line}"
        );
        assert!(
            line.contains("loss_coefficient = 1.5: must be in [0, 1)"),
            "the first error is quoted: {line}"
        );
        assert!(
            line.ends_with("--resume retries them, --allow-failures exits 0"),
            "{line}"
        );
        // The lines named are exactly the failed rows' lines.
        let text = std::fs::read_to_string(&out).unwrap();
        let failed: Vec<usize> = text
            .lines()
            .enumerate()
            .filter(|(_, l)| l.contains("must be in [0, 1)"))
            .map(|(i, _)| i + 1)
            .collect();
        assert_eq!(listed_lines(line), failed, "{line}");
        let first = failed[0];
        assert!(line.contains(&format!("the first (line {first}, point ")));

        // To standard output, the lines are the output's own.
        let piped = millimpact()
            .args(["sweep", "--format", format, "--jobs", "1"])
            .arg(&file)
            .output()
            .unwrap();
        assert_eq!(piped.status.code(), Some(1));
        let stdout = String::from_utf8(piped.stdout).unwrap();
        let stderr = String::from_utf8_lossy(&piped.stderr);
        assert!(stderr.contains("of standard output, lines "), "{stderr}");
        assert!(stderr.contains("--out FILE keeps the rows"), "{stderr}");
        let on_stdout: Vec<usize> = stdout
            .lines()
            .enumerate()
            .filter(|(_, l)| l.contains("must be in [0, 1)"))
            .map(|(i, _)| i + 1)
            .collect();
        assert_eq!(listed_lines(&stderr), on_stdout);

        // --allow-failures: the same rows, the same count as a warning, exit 0.
        let allowed_out = dir.path().join(format!("allowed.{format}"));
        let allowed = run_sweep(
            &file,
            &allowed_out,
            &["--format", format, "--allow-failures"],
        );
        assert_eq!(allowed.status.code(), Some(0), "{allowed:?}");
        let stderr = String::from_utf8_lossy(&allowed.stderr);
        assert!(
            stderr.starts_with(
                "warning: 6 of 30 points failed; their errors are in the status column of "
            ),
            "{stderr}"
        );
    }
}

/// Rewrite the rows of `points` in the output `path` as failed with `error`, their figures
/// emptied, as a code killed under them would have left them.
fn fail_rows(path: &Path, points: &[usize], error: &str) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut out = String::new();
    if text.starts_with('{') {
        for line in text.lines() {
            let mut row: serde_json::Map<String, serde_json::Value> =
                serde_json::from_str(line).unwrap();
            if points.contains(&usize::try_from(row["point"].as_u64().unwrap()).unwrap()) {
                for figure in [
                    "case",
                    "cor",
                    "cor_target",
                    "cor_error",
                    "steps",
                    "wall_time",
                ] {
                    row.insert(figure.into(), serde_json::Value::Null);
                }
                row.insert("status".into(), error.into());
            }
            out += &serde_json::to_string(&row).unwrap();
            out.push('\n');
        }
    } else {
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let headers = reader.headers().unwrap().clone();
        let mut writer = csv::Writer::from_writer(Vec::new());
        writer.write_record(&headers).unwrap();
        let case = headers.iter().position(|h| h == "case").unwrap();
        for record in reader.records() {
            let mut cells: Vec<String> = record.unwrap().iter().map(String::from).collect();
            if points.contains(&cells[1].parse().unwrap()) {
                let n = cells.len();
                for c in &mut cells[case..n - 1] {
                    c.clear();
                }
                cells[n - 1] = error.to_string();
            }
            writer.write_record(&cells).unwrap();
        }
        out = String::from_utf8(writer.into_inner().unwrap()).unwrap();
    }
    std::fs::write(path, out).unwrap();
}

/// The rows of a CSV or JSON-lines output by point, the wall time left out.
fn rows_by_point(path: &Path) -> BTreeMap<u64, BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut out = BTreeMap::new();
    let mut add = |row: BTreeMap<String, String>| {
        let point = row["point"].parse().unwrap();
        assert!(
            out.insert(point, row).is_none(),
            "point {point} appears once"
        );
    };
    if text.starts_with('{') {
        for line in text.lines() {
            let row: serde_json::Map<String, serde_json::Value> =
                serde_json::from_str(line).unwrap();
            add(row
                .into_iter()
                .filter(|(k, _)| k != "wall_time")
                .map(|(k, v)| (k, v.to_string()))
                .collect());
        }
    } else {
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let headers = reader.headers().unwrap().clone();
        for record in reader.records() {
            add(headers
                .iter()
                .zip(record.unwrap().iter())
                .filter(|(h, _)| *h != "wall_time")
                .map(|(h, c)| (h.to_string(), c.to_string()))
                .collect());
        }
    }
    out
}

#[test]
fn resume_runs_failed_and_cut_off_rows_again_and_keeps_the_computed_ones_as_written() {
    let dir = TempDir::new().unwrap();
    let file = root().join("sweeps/grid.toml");
    for format in ["csv", "jsonl"] {
        let whole = dir.path().join(format!("whole.{format}"));
        let done = run_sweep(&file, &whole, &["--format", format, "--jobs", "1"]);
        assert!(done.status.success(), "{done:?}");
        // Points 1 and 4 failed (a code killed under them), and the run was killed while it
        // wrote point 5's row.
        let part = dir.path().join(format!("part.{format}"));
        std::fs::copy(&whole, &part).unwrap();
        fail_rows(&part, &[1, 4], "lammps: killed after the time limit of 1 s");
        let damaged = std::fs::read_to_string(&part).unwrap();
        let cut = damaged.trim_end().len() - 30;
        std::fs::write(&part, &damaged[..cut]).unwrap();
        let kept_lines: Vec<&str> = damaged
            .lines()
            .filter(|l| !l.contains("killed after"))
            .collect();
        let kept_lines = &kept_lines[..kept_lines.len() - 1];

        let resumed = run_sweep(&file, &part, &["--resume", "--format", format]);
        assert!(resumed.status.success(), "{resumed:?}");
        let stderr = String::from_utf8_lossy(&resumed.stderr);
        assert!(
            stderr.contains(&format!(
                "resuming {}: {} rows kept; run again: 2 failed points, the point of the last row, cut off mid-line",
                part.display(),
                kept_lines.len() - usize::from(format == "csv")
            )),
            "{stderr}"
        );
        // Each point once, with its latest outcome: the failed and cut-off ones computed now.
        assert_eq!(rows_by_point(&part), rows_by_point(&whole));
        let text = std::fs::read_to_string(&part).unwrap();
        assert!(!text.contains("killed after"));
        // The rows kept are the lines as they were written, first and in their order (their
        // wall times too); the points run again come after them.
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(&lines[..kept_lines.len()], kept_lines);
        assert_eq!(lines.len(), whole_lines(&whole));
        // The file was swapped in whole: no temporary file is left beside it.
        let names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with('.'))
            .collect();
        assert!(names.is_empty(), "{names:?}");
        // A complete, all-ok output is left as it is.
        let before = std::fs::read(&part).unwrap();
        let again = run_sweep(&file, &part, &["--resume"]);
        assert!(again.status.success(), "{again:?}");
        assert!(again.stderr.is_empty(), "{again:?}");
        assert_eq!(std::fs::read(&part).unwrap(), before);
    }
}

fn whole_lines(path: &Path) -> usize {
    std::fs::read_to_string(path).unwrap().lines().count()
}

/// The code points of a sweep fail while their binary is missing (no process starts: the
/// override names no file); resumed, they fail again and their rows carry the latest error,
/// each point once, while the points computed by our methods are kept.
#[test]
fn points_that_fail_again_on_resume_keep_only_their_latest_error() {
    let dir = TempDir::new().unwrap();
    let file = dir.path().join("mixed.toml");
    std::fs::write(
        &file,
        format!(
            "base = \"{}\"\n[axes]\nloss_coefficient = [0.1, 0.35, 0.6]\nmethod = [\"rk4-event\"]\ncode = [\"lammps\"]\n",
            root().join("cases/ball_plate.toml").display()
        ),
    )
    .unwrap();
    for format in ["csv", "jsonl"] {
        let out = dir.path().join(format!("mixed.{format}"));
        let first = millimpact()
            .env(
                "MILLIMPACT_LAMMPS_BINARY",
                dir.path().join("first-missing-lmp"),
            )
            .args(["sweep", "--format", format])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(first.status.code(), Some(1), "{first:?}");
        assert!(String::from_utf8_lossy(&first.stderr).contains("3 of 6 points failed"));
        let computed = rows_by_point(&out);
        let second = millimpact()
            .env(
                "MILLIMPACT_LAMMPS_BINARY",
                dir.path().join("second-missing-lmp"),
            )
            .args(["sweep", "--resume"])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(second.status.code(), Some(1), "{second:?}");
        let stderr = String::from_utf8_lossy(&second.stderr);
        assert!(stderr.contains("run again: 3 failed points"), "{stderr}");
        assert!(stderr.contains("3 of 6 points failed"), "{stderr}");
        let rows = rows_by_point(&out);
        assert_eq!(rows.len(), 6);
        for (point, row) in &rows {
            if row["code"].contains("lammps") {
                assert!(row["status"].contains("second-missing-lmp"), "{row:?}");
            } else {
                assert_eq!(row, &computed[point], "a computed point is kept");
            }
        }
        // The errors named are on the lines after the kept rows.
        let header = usize::from(format == "csv");
        assert_eq!(
            listed_lines(&stderr),
            vec![header + 4, header + 5, header + 6],
            "{stderr}"
        );
    }
}

#[test]
fn shards_resumed_after_failures_merge_into_the_unsharded_sweep() {
    let dir = TempDir::new().unwrap();
    let file = root().join("sweeps/grid.toml");
    let whole = dir.path().join("whole.csv");
    assert!(run_sweep(&file, &whole, &[]).status.success());
    let shards: Vec<PathBuf> = (1..=2)
        .map(|k| dir.path().join(format!("shard{k}.csv")))
        .collect();
    for (k, shard) in shards.iter().enumerate() {
        let ran = run_sweep(&file, shard, &["--shard", &format!("{}/2", k + 1)]);
        assert!(ran.status.success(), "{ran:?}");
    }
    // Points 0 and 2 of shard 1 failed; the merge of it as it is says where.
    fail_rows(&shards[0], &[0, 2], "yade: exited with exit status: 9");
    let merged = dir.path().join("merged.csv");
    let merge = |shards: &[&PathBuf]| {
        millimpact()
            .arg("merge")
            .arg(&merged)
            .args(shards)
            .output()
            .unwrap()
    };
    let result = merge(&[&shards[0], &shards[1]]);
    assert!(result.status.success(), "{result:?}");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.starts_with(&format!(
            "warning: 2 of 6 points failed; their errors are in the status column of {}, lines 2, 4;",
            merged.display()
        )),
        "{stderr}"
    );
    // Resumed, shard 1 computes them again (its rows no longer in grid order); the merge
    // puts every point once in grid order, as the unsharded sweep has them.
    let resumed = run_sweep(&file, &shards[0], &["--shard", "1/2", "--resume"]);
    assert!(resumed.status.success(), "{resumed:?}");
    let result = merge(&[&shards[0], &shards[1]]);
    assert!(
        result.status.success() && result.stderr.is_empty(),
        "{result:?}"
    );
    assert_eq!(rows_by_point(&merged), rows_by_point(&whole));
    let points: Vec<u64> = rows_by_point(&merged).into_keys().collect();
    assert_eq!(points, (0..6).collect::<Vec<_>>());
    // A point given twice, failed in one file and computed in another, is kept computed,
    // whichever comes first.
    let stale = dir.path().join("stale.csv");
    std::fs::copy(&shards[1], &stale).unwrap();
    fail_rows(&stale, &[1, 3], "lammps: exited with exit status: 1");
    for order in [[&stale, &shards[1]], [&shards[1], &stale]] {
        let result = merge(&[order[0], order[1], &shards[0]]);
        assert!(
            result.status.success() && result.stderr.is_empty(),
            "{result:?}"
        );
        assert_eq!(rows_by_point(&merged), rows_by_point(&whole));
    }
}

#[test]
fn an_interrupted_sweep_resumed_equals_the_uninterrupted_one() {
    let dir = TempDir::new().unwrap();
    let file = grid_file(dir.path());
    for format in ["csv", "jsonl"] {
        let full = dir.path().join(format!("full.{format}"));
        assert_eq!(
            run_sweep(&file, &full, &["--format", format]).status.code(),
            Some(1),
            "the η = 1.5 points fail"
        );
        let text = std::fs::read_to_string(&full).unwrap();
        // Interrupted after 7 rows, the 8th cut mid-line.
        let lines: Vec<&str> = text.lines().collect();
        let head = if format == "csv" { 8 } else { 7 };
        let cut = lines[..head].join("\n") + "\n" + &lines[head][..20];
        let part = dir.path().join(format!("part.{format}"));
        std::fs::write(&part, cut).unwrap();
        // Without --resume the existing output is not overwritten.
        let refused = run_sweep(&file, &part, &[]);
        assert_eq!(refused.status.code(), Some(2));
        let resumed = run_sweep(&file, &part, &["--resume", "--allow-failures"]);
        assert!(resumed.status.success(), "{resumed:?}");
        let resumed_text = std::fs::read_to_string(&part).unwrap();
        assert_eq!(resumed_text.lines().count(), text.lines().count());
        if format == "csv" {
            assert_eq!(rows_by_parameters(&part), rows_by_parameters(&full));
        } else {
            let set = |t: &str| {
                let mut v: Vec<serde_json::Value> = t
                    .lines()
                    .map(|l| {
                        let mut v: serde_json::Value = serde_json::from_str(l).unwrap();
                        v.as_object_mut().unwrap().remove("wall_time");
                        v
                    })
                    .collect();
                v.sort_by_key(|v| v["point"].as_u64());
                v
            };
            assert_eq!(set(&resumed_text), set(&text));
        }
        // Resuming a complete output runs only its failed points again, each still once.
        assert!(
            run_sweep(&file, &part, &["--resume", "--allow-failures"])
                .status
                .success()
        );
        assert_eq!(
            std::fs::read_to_string(&part).unwrap().lines().count(),
            text.lines().count()
        );
    }
}

#[test]
fn resume_refuses_the_output_of_another_sweep() {
    let dir = TempDir::new().unwrap();
    let file = grid_file(dir.path());
    let out = dir.path().join("out.csv");
    assert!(
        run_sweep(&file, &out, &["--allow-failures"])
            .status
            .success()
    );
    let other = dir.path().join("other.toml");
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replace("0.35", "0.36");
    std::fs::write(&other, text).unwrap();
    let refused = run_sweep(&other, &out, &["--resume"]);
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("not of this sweep"), "{stderr}");
}

#[test]
#[ignore = "live: needs GNU parallel (bash scripts/test.sh)"]
fn three_shards_run_by_gnu_parallel_merge_into_the_unsharded_sweep() {
    require("parallel", "GNU parallel (Debian package `parallel`)");
    let dir = TempDir::new().unwrap();
    let file = grid_file(dir.path());
    let whole = dir.path().join("whole.csv");
    assert!(
        run_sweep(&file, &whole, &["--allow-failures"])
            .status
            .success()
    );
    let bin = assert_cmd::cargo::cargo_bin("millimpact");
    let status = std::process::Command::new("parallel")
        .current_dir(dir.path())
        .args(["--will-cite", "--halt", "now,fail=1"])
        .arg(format!(
            "{} sweep {} --shard {{}}/3 --allow-failures --out shard{{}}.csv",
            bin.display(),
            file.display()
        ))
        .args([":::", "1", "2", "3"])
        .status()
        .unwrap();
    assert!(status.success());
    let merged = dir.path().join("merged.csv");
    let shards: Vec<PathBuf> = (1..=3)
        .map(|k| dir.path().join(format!("shard{k}.csv")))
        .collect();
    for s in &shards {
        let n = rows_by_parameters(s).len();
        assert!(n == 10, "each shard holds a third: {n}");
    }
    millimpact()
        .arg("merge")
        .arg(&merged)
        .args(&shards)
        .assert()
        .success();
    assert_eq!(rows_by_parameters(&merged), rows_by_parameters(&whole));
    // The merged rows are in grid order.
    let points: Vec<usize> = csv::Reader::from_path(&merged)
        .unwrap()
        .records()
        .map(|r| r.unwrap()[1].parse().unwrap())
        .collect();
    assert_eq!(points, (0..30).collect::<Vec<_>>());
    // A shard of another sweep is refused.
    let other = dir.path().join("other.toml");
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replace("0.35", "0.36");
    std::fs::write(&other, text).unwrap();
    let foreign = dir.path().join("foreign.csv");
    assert!(
        run_sweep(&other, &foreign, &["--shard", "3/3", "--allow-failures"])
            .status
            .success()
    );
    let refused = millimpact()
        .arg("merge")
        .arg(dir.path().join("bad.csv"))
        .arg(&shards[0])
        .arg(&shards[1])
        .arg(&foreign)
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("different sweeps"));
    assert!(!dir.path().join("bad.csv").exists(), "no partial output");
}

fn which(binary: &str) -> Option<PathBuf> {
    std::env::split_paths(&std::env::var_os("PATH")?)
        .map(|d| d.join(binary))
        .find(|p| p.is_file())
}

/// Fail the (live) test, saying what is missing, when `binary` is not on PATH: a live test
/// that cannot run fails, it does not pass as skipped.
#[track_caller]
fn require(binary: &str, what: &str) {
    assert!(
        which(binary).is_some(),
        "`{binary}` is not on PATH: this live test needs {what}; bash scripts/test.sh installs it"
    );
}

#[test]
fn jobs_bounds_the_number_of_live_code_processes() {
    let dir = TempDir::new().unwrap();
    let bin = dir.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    let state = dir.path().join("state");
    std::fs::create_dir(&state).unwrap();
    std::fs::write(state.join("live"), "0").unwrap();
    std::fs::write(state.join("max"), "0").unwrap();
    // A fake LAMMPS that counts live instances under a lock, stays a while, and crashes.
    let script = format!(
        r#"#!/bin/sh
d={d}
(flock 9; n=$(($(cat $d/live) + 1)); echo $n > $d/live; [ $n -gt $(cat $d/max) ] && echo $n > $d/max) 9>$d/lock
sleep 0.4
(flock 9; echo $(($(cat $d/live) - 1)) > $d/live) 9>$d/lock
echo "fake lmp crashed"
exit 3
"#,
        d = state.display()
    );
    let lmp = bin.join("lmp");
    std::fs::write(&lmp, script).unwrap();
    std::fs::set_permissions(&lmp, std::fs::Permissions::from_mode(0o755)).unwrap();
    let file = dir.path().join("codes.toml");
    std::fs::write(
        &file,
        format!(
            "base = \"{}\"\n[axes]\nloss_coefficient = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]\ncode = [\"lammps\"]\nsteps_per_contact = [50]\n",
            root().join("cases/ball_plate.toml").display()
        ),
    )
    .unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    for jobs in [1usize, 3] {
        std::fs::write(state.join("max"), "0").unwrap();
        let out = dir.path().join(format!("jobs{jobs}.csv"));
        let result = millimpact()
            .env("PATH", &path)
            .env("TMPDIR", dir.path())
            .args(["sweep", "--batch", "1", "--jobs", &jobs.to_string()])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(
            result.status.code(),
            Some(1),
            "every point crashed: {result:?}"
        );
        assert!(
            String::from_utf8_lossy(&result.stderr).contains("7 of 7 points failed"),
            "{result:?}"
        );
        let most: usize = std::fs::read_to_string(state.join("max"))
            .unwrap()
            .trim()
            .parse()
            .unwrap();
        assert!(most <= jobs, "{most} live processes with --jobs {jobs}");
        if jobs > 1 {
            assert!(most > 1, "the pool ran processes side by side ({most})");
        }
        // Every point crashed, each is a row naming the crash and its kept log.
        let rows = rows_by_parameters(&out);
        assert_eq!(rows.len(), 7);
        for r in rows.values() {
            assert!(
                r["status"].contains("lammps: exited with"),
                "{}",
                r["status"]
            );
            let log = &r["status"][r["status"].find("log kept in ").unwrap() + 12..];
            assert!(
                std::fs::read_to_string(log.trim())
                    .unwrap()
                    .contains("fake lmp crashed")
            );
        }
    }
}

#[test]
fn invalid_sweep_files_are_one_line_naming_file_key_value_and_what_is_allowed() {
    let dir = TempDir::new().unwrap();
    let base = root().join("cases/ball_plate.toml");
    let cases = [
        (
            "[axes]\n\"ball.colour\" = [1]\n",
            "axes.ball.colour",
            "unknown axis",
        ),
        (
            "[axes]\nmethod = [\"rk45\"]\n",
            "axes.method",
            "allowed: rk4",
        ),
        (
            "[axes]\nloss_coefficient = 0.3\n",
            "axes.loss_coefficient",
            "a list of values",
        ),
        (
            "[axes]\nloss_coefficient = { start = 0.5, stop = 0.1, step = 0.1 }\n",
            "axes.loss_coefficient",
            "start <= stop",
        ),
        (
            "[axes]\nsteps_per_contact = [100]\n",
            "axes.steps_per_contact",
            "codes",
        ),
        ("colour = 3\n[axes]\n", "colour", "unknown key"),
    ];
    for (body, key, allowed) in cases {
        let file = dir.path().join("bad.toml");
        std::fs::write(&file, format!("base = \"{}\"\n{body}", base.display())).unwrap();
        let out = dir.path().join("never.csv");
        let result = run_sweep(&file, &out, &[]);
        assert_eq!(result.status.code(), Some(2), "{body}");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(&file.display().to_string()), "{stderr}");
        assert!(stderr.contains(&format!("{key} = ")), "{key}: {stderr}");
        assert!(stderr.contains(allowed), "{allowed}: {stderr}");
        assert!(!out.exists(), "no partial output");
    }
}

/// Stops the single-node cluster however the test ends.
struct Cluster(PathBuf);

impl Drop for Cluster {
    fn drop(&mut self) {
        let _ = std::process::Command::new("bash")
            .arg(root().join("scripts/slurm/local-cluster.sh"))
            .arg("stop")
            .arg(&self.0)
            .status();
    }
}

#[test]
#[ignore = "live: needs Slurm and munge (bash scripts/test.sh)"]
fn a_slurm_job_array_of_three_shards_merges_into_the_unsharded_sweep() {
    require("slurmctld", "Slurm (Debian package `slurm-wlm`)");
    require("munged", "munge (Debian package `munge`)");
    let dir = TempDir::new().unwrap();
    let cluster_dir = dir.path().join("cluster");
    let started = std::process::Command::new("bash")
        .arg(root().join("scripts/slurm/local-cluster.sh"))
        .arg("start")
        .arg(&cluster_dir)
        .output()
        .unwrap();
    let _cluster = Cluster(cluster_dir.clone());
    assert!(
        started.status.success(),
        "the single-node Slurm of scripts/slurm/local-cluster.sh did not start ({}): {}{}",
        started.status,
        String::from_utf8_lossy(&started.stdout),
        String::from_utf8_lossy(&started.stderr)
    );
    let conf = cluster_dir.join("slurm.conf");
    let file = grid_file(dir.path());
    let whole = dir.path().join("whole.csv");
    assert!(
        run_sweep(&file, &whole, &["--allow-failures"])
            .status
            .success()
    );
    let outdir = dir.path().join("slurm-out");
    let submitted = std::process::Command::new("bash")
        .arg(root().join("scripts/slurm/sweep.sbatch"))
        .arg(&file)
        .arg(&outdir)
        .arg("3")
        // The grid's η = 1.5 points fail in every shard; the merge runs all the same.
        .arg("--allow-failures")
        .env("SLURM_CONF", &conf)
        .env("MILLIMPACT", assert_cmd::cargo::cargo_bin("millimpact"))
        .output()
        .unwrap();
    assert!(submitted.status.success(), "{submitted:?}");
    let merged = outdir.join("sweep.csv");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while !merged.exists() && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(200));
    }
    // The merge job writes its output atomically: once it exists it is whole.
    assert!(
        merged.exists(),
        "the merge job did not finish; logs in {}",
        outdir.display()
    );
    for k in 1..=3 {
        assert_eq!(
            rows_by_parameters(&outdir.join(format!("shard-{k}.csv"))).len(),
            10
        );
    }
    assert_eq!(rows_by_parameters(&merged), rows_by_parameters(&whole));
}

#[test]
#[ignore = "live: runs LAMMPS (bash scripts/test.sh)"]
fn every_impact_of_a_lammps_batch_gives_the_figures_of_its_single_run() {
    batch_equals_single_runs("lammps", "lmp");
}

#[test]
#[ignore = "live: runs LIGGGHTS (bash scripts/test.sh)"]
fn every_impact_of_a_liggghts_batch_gives_the_figures_of_its_single_run() {
    batch_equals_single_runs("liggghts", "liggghts");
}

#[test]
#[ignore = "live: runs YADE (bash scripts/test.sh)"]
fn every_impact_of_a_yade_batch_gives_the_figures_of_its_single_run() {
    batch_equals_single_runs("yade", "yade");
}

#[test]
#[ignore = "live: runs LAMMPS 2025 (bash scripts/test.sh)"]
fn every_impact_of_a_lammps_2025_batch_gives_the_figures_of_its_single_run() {
    batch_equals_single_runs("lammps-2025", "");
}

#[test]
#[ignore = "live: runs Kratos (bash scripts/test.sh)"]
fn every_impact_of_a_kratos_batch_gives_the_figures_of_its_single_run() {
    batch_equals_single_runs("kratos", "");
}

/// A sweep's rows from batches and from single runs: the same figures, cell for cell (the
/// trajectories are the same to the bit: tests/batches.rs), but the batch size and the times.
/// `binary`: the code's program on PATH, or empty for a build under the codes' folder (whose
/// absence the sweep's own error reports).
fn batch_equals_single_runs(code: &str, binary: &str) {
    if !binary.is_empty() {
        require(binary, &format!("the DEM code {code}"));
    }
    let dir = TempDir::new().unwrap();
    let file = dir.path().join("batch.toml");
    std::fs::write(
        &file,
        format!(
            "base = \"{}\"\n[axes]\nloss_coefficient = [0.0, 0.1, 0.35, 0.5, 0.7, 0.9]\ncode = [\"{code}\"]\nsteps_per_contact = [200]\n",
            root().join("cases/ball_plate.toml").display()
        ),
    )
    .unwrap();
    let single = dir.path().join("single.csv");
    let batched = dir.path().join("batched.csv");
    let ran = |out: &Path, batch: &str| {
        let result = millimpact()
            .env("TMPDIR", dir.path())
            .args(["sweep", "--jobs", "1", "--batch", batch])
            .arg(&file)
            .arg("--out")
            .arg(out)
            .output()
            .unwrap();
        assert!(result.status.success(), "{result:?}");
        assert!(result.stderr.is_empty(), "no fallback: {result:?}");
        rows_by_parameters(out)
    };
    let single = ran(&single, "1");
    let batched = ran(&batched, "6");
    assert_eq!(single.len(), 6);
    for (key, one) in &single {
        let many = &batched[key];
        assert_eq!(one["status"], "ok", "{key:?}");
        assert_eq!(one["batch"], "1");
        assert_eq!(many["batch"], "6", "all six in one process");
        for (column, value) in one {
            if column == "batch" {
                continue;
            }
            assert_eq!(value, &many[column], "{column}: single, batched");
        }
    }
}

#[test]
#[ignore = "live: runs LAMMPS (bash scripts/test.sh)"]
fn ctrl_c_keeps_every_finished_row_and_resume_completes_the_sweep() {
    require("lmp", "LAMMPS (Debian package `lammps`)");
    // One code process at a time, each a fraction of a second: the signal goes once two rows
    // are in, and the fourteen left take seconds, so the sweep is always interrupted (no
    // scheduling delay of the test's own process lets it finish first).
    const ROWS: usize = 16;
    let dir = TempDir::new().unwrap();
    let file = dir.path().join("slow.toml");
    std::fs::write(
        &file,
        format!(
            "base = \"{}\"\n[axes]\nloss_coefficient = {{ start = 0.05, stop = 0.95, count = {ROWS} }}\ncode = [\"lammps\"]\nsteps_per_contact = [100]\n",
            root().join("cases/ball_plate.toml").display()
        ),
    )
    .unwrap();
    let whole = dir.path().join("whole.csv");
    let one_at_a_time = ["--jobs", "1", "--batch", "1"];
    let started = std::time::Instant::now();
    assert!(run_sweep(&file, &whole, &one_at_a_time).status.success());
    let uninterrupted = started.elapsed();
    assert_eq!(rows_by_parameters(&whole).len(), ROWS);
    let part = dir.path().join("part.csv");
    let child = std::process::Command::new(assert_cmd::cargo::cargo_bin("millimpact"))
        .current_dir(root())
        .env_remove("CI")
        .arg("sweep")
        .arg(&file)
        .arg("--out")
        .arg(&part)
        .args(one_at_a_time)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Interrupt as soon as two rows are in.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while std::fs::read_to_string(&part)
        .map(|t| t.lines().count())
        .unwrap_or(0)
        < 3
        && std::time::Instant::now() < deadline
    {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let interrupted = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(interrupted.success());
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let kept = rows_by_parameters(&part);
    assert!(
        !output.status.success(),
        "the sweep finished before the signal ({} rows; the whole sweep took {uninterrupted:?}): {stderr}",
        kept.len()
    );
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("interrupted"), "{stderr}");
    assert!(
        kept.len() >= 2 && kept.len() < ROWS,
        "{} rows kept",
        kept.len()
    );
    assert!(
        kept.values().all(|r| r["status"] == "ok"),
        "only finished rows"
    );
    eprintln!(
        "interrupted after {} of {ROWS} rows (the whole sweep: {uninterrupted:?})",
        kept.len()
    );
    let resumed = run_sweep(&file, &part, &["--resume", "--jobs", "1", "--batch", "1"]);
    assert!(resumed.status.success(), "{resumed:?}");
    assert_eq!(rows_by_parameters(&part), rows_by_parameters(&whole));
}

#[test]
#[ignore = "live: runs LAMMPS (bash scripts/test.sh)"]
fn a_sweep_whose_code_fails_its_first_launch_exits_1_and_resume_completes_it() {
    require("lmp", "LAMMPS (Debian package `lammps`)");
    let dir = TempDir::new().unwrap();
    let file = dir.path().join("codes.toml");
    std::fs::write(
        &file,
        format!(
            "base = \"{}\"\n[axes]\nloss_coefficient = [0.1, 0.35, 0.6]\nmethod = [\"rk4-event\"]\ncode = [\"lammps\"]\nsteps_per_contact = [100]\n",
            root().join("cases/ball_plate.toml").display()
        ),
    )
    .unwrap();
    // The first launch dies at once (a node out of memory, say), keeping its log.
    let crash = dir.path().join("crashing-lmp");
    std::fs::write(&crash, "#!/bin/sh\necho 'out of memory'\nexit 137\n").unwrap();
    std::fs::set_permissions(&crash, std::fs::Permissions::from_mode(0o755)).unwrap();
    for format in ["csv", "jsonl"] {
        let out = dir.path().join(format!("codes.{format}"));
        let first = millimpact()
            .env("MILLIMPACT_LAMMPS_BINARY", &crash)
            .env("TMPDIR", dir.path())
            .args(["sweep", "--format", format])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(first.status.code(), Some(1), "{first:?}");
        let stderr = String::from_utf8_lossy(&first.stderr);
        assert!(stderr.contains("3 of 6 points failed"), "{stderr}");
        assert!(stderr.contains("log kept in "), "{stderr}");
        let resumed = millimpact()
            .env_remove("MILLIMPACT_LAMMPS_BINARY")
            .env("TMPDIR", dir.path())
            .args(["sweep", "--resume"])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(resumed.status.success(), "{resumed:?}");
        let rows = rows_by_point(&out);
        assert_eq!(rows.len(), 6, "each point once");
        for row in rows.values() {
            assert!(row["status"].contains("ok"), "{row:?}");
        }
        let lammps = rows.values().filter(|r| r["code"].contains("lammps"));
        assert_eq!(lammps.count(), 3);
    }
}

/// A sweep file that asks for a COR tolerance: the method and resolution chosen are named on
/// standard error and in every row's source columns, every row meets the tolerance, and both
/// forms give the same figures; a tolerance beside an explicit method, or out of reach, is one
/// line and exit 2 with nothing written.
#[test]
fn a_tolerance_chooses_the_method_and_every_row_meets_it() {
    let dir = TempDir::new().unwrap();
    let file = dir.path().join("tol.toml");
    let base = root().join("cases/rod_end.toml");
    std::fs::write(
        &file,
        format!(
            "base = \"{}\"\ntolerance = 1e-9\n[axes]\nloss_coefficient = {{ start = 0.0, stop = 0.9999, count = 300 }}\n",
            base.display()
        ),
    )
    .unwrap();
    let out = millimpact()
        .args(["sweep", file.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success());
    let note = String::from_utf8_lossy(&out.stderr);
    let chosen = note
        .split(" steps per period")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .unwrap()
        .to_string();
    assert!(note.contains("COR tolerance 1e-9: rk4-event at"), "{note}");
    let mut reader = csv::Reader::from_reader(out.stdout.as_slice());
    let headers = reader.headers().unwrap().clone();
    let col = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 300);
    for r in &rows {
        assert_eq!(&r[col("method")], "rk4-event");
        assert_eq!(r[col("steps_per_period")], chosen);
        let error: f64 = r[col("cor_error")].parse().unwrap();
        assert!(
            error.abs() <= 1e-9,
            "η = {}: {error}",
            &r[col("loss_coefficient")]
        );
    }
    // The legacy form with --tolerance chooses the same and gives the same COR.
    let legacy = millimpact()
        .args([
            "sweep",
            base.to_str().unwrap(),
            "--loss-coefficient",
            "0:0.5:0.25",
            "--tolerance",
            "1e-9",
        ])
        .output()
        .unwrap();
    assert!(legacy.status.success());
    assert_eq!(
        String::from_utf8_lossy(&legacy.stderr).trim(),
        note.trim(),
        "both forms name the same choice"
    );
    for (bad, says) in [
        (
            "tolerance = 1e-9\n[axes]\nmethod = [\"dopri5\"]\n",
            "not with axes.method",
        ),
        ("tolerance = 1e-16\n", "a relative COR error in"),
        ("tolerance = -1.0\n", "a relative COR error in"),
    ] {
        std::fs::write(&file, format!("base = \"{}\"\n{bad}", base.display())).unwrap();
        let out = millimpact()
            .args(["sweep", file.to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        assert!(out.stdout.is_empty());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("tolerance = ") && err.contains(says), "{err}");
    }
}
