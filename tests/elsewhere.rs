//! The commands a user runs from a folder of their own, on a case given by its absolute path:
//! what they draw besides the case (the report's figures, the stored references, the default
//! cases) does not depend on the working folder.

mod common;

use std::path::Path;

use common::{case_path, root};
use tempfile::TempDir;

/// `millimpact` run from `folder`, a folder with no `cases/` or `reference/` of its own, as on
/// a machine without the DEM codes (so that none is probed: `calibrate` and `report` would
/// measure a LAMMPS build they find).
fn millimpact_in(folder: &Path) -> assert_cmd::Command {
    let mut cmd = assert_cmd::Command::cargo_bin("millimpact").unwrap();
    cmd.current_dir(folder).envs(common::codes_hidden());
    cmd
}

/// `millimpact` run from the repository's folder, the codes hidden as in [`millimpact_in`].
fn millimpact_at_root() -> assert_cmd::Command {
    millimpact_in(&root())
}

#[test]
fn report_runs_on_an_absolute_case_path_from_another_folder() {
    let here = TempDir::new().unwrap();
    let out = here.path().join("my-report");
    let output = millimpact_in(here.path())
        .arg("report")
        .arg(case_path("ball_plate"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    let page = std::fs::read_to_string(out.join("index.md")).unwrap();
    // The paper's figures (drawn from the built-in rod and ball cases) and the stored
    // references' comparison are both there.
    assert!(
        out.join("fig2.svg").is_file() || page.contains("Figure 2"),
        "{page}"
    );
    assert!(page.contains("ball_plate"), "{page}");
    let repository = root().join("reference");
    assert!(
        stderr.contains(&repository.display().to_string()),
        "the stored references read from the repository are named: {stderr}"
    );
}

#[test]
fn verify_from_another_folder_checks_the_repository_and_says_so() {
    let here = TempDir::new().unwrap();
    let output = millimpact_in(here.path())
        .args(["verify", "--format", "json"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    for folder in ["cases", "reference"] {
        let path = root().join(folder).display().to_string();
        assert!(stderr.contains(&path), "{folder}: {stderr}");
    }
    let from_root = common::stdout(millimpact_at_root().args(["verify", "--format", "json"]));
    let rows = |text: &str| -> usize {
        serde_json::from_str::<serde_json::Value>(text).unwrap()["rows"]
            .as_array()
            .unwrap()
            .len()
    };
    assert_eq!(
        rows(&String::from_utf8_lossy(&output.stdout)),
        rows(&from_root)
    );
}

#[test]
fn a_reference_folder_given_that_does_not_exist_is_not_replaced() {
    let here = TempDir::new().unwrap();
    let output = millimpact_in(here.path())
        .args(["compare", "--reference", "no-such-folder"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("--reference") && stderr.contains("no-such-folder"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(output.stdout.is_empty());
}

/// The JSON output with the measured run times taken out (they differ from run to run).
fn without_run_times(text: &str) -> serde_json::Value {
    fn strip(value: &mut serde_json::Value) {
        match value {
            serde_json::Value::Object(map) => {
                map.retain(|key, _| !key.ends_with("run_time") && key != "wall_time");
                map.values_mut().for_each(strip);
            }
            serde_json::Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut value: serde_json::Value = serde_json::from_str(text).unwrap();
    strip(&mut value);
    value
}

#[test]
fn compare_and_calibrate_without_a_case_read_the_built_in_cases() {
    let here = TempDir::new().unwrap();
    let elsewhere =
        common::stdout(millimpact_in(here.path()).args(["compare", "--format", "json"]));
    let at_root = common::stdout(millimpact_at_root().args(["compare", "--format", "json"]));
    assert_eq!(without_run_times(&elsewhere), without_run_times(&at_root));
    let elsewhere = common::stdout(millimpact_in(here.path()).args([
        "calibrate",
        "--cor",
        "0.6",
        "--format",
        "json",
    ]));
    let at_root = common::stdout(millimpact_at_root().args([
        "calibrate",
        "--cor",
        "0.6",
        "--format",
        "json",
    ]));
    assert_eq!(without_run_times(&elsewhere), without_run_times(&at_root));
}
