//! `millimpact mill` run for real: the shipped example drum under both laws (liggghts and
//! liggghts-paper at once), and a deck that fails at run time (exit 1, the code's own `ERROR`
//! line, its log kept).

mod common;

use common::{millimpact, root};

/// `examples/mill/stored-run.json`, from which the book's figures and table of the example are
/// drawn, is what the example gives now: every figure the same (LIGGGHTS on one process repeats
/// itself bit for bit), the wall times apart. `UPDATE_BOOK=1` stores this run instead.
fn the_run_is_the_stored_one(report: &serde_json::Value) {
    let path = root().join("examples/mill/stored-run.json");
    let mut fresh = report.clone();
    if std::env::var_os("UPDATE_BOOK").is_some() {
        std::fs::write(&path, serde_json::to_string_pretty(report).unwrap() + "\n").unwrap();
    }
    let mut stored: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    for json in [&mut fresh, &mut stored] {
        for run in json["runs"].as_array_mut().unwrap() {
            run["wall_time"] = serde_json::Value::Null;
        }
    }
    for key in ["quantities", "power_balance", "spectra", "runs"] {
        assert_eq!(
            fresh[key], stored[key],
            "{key}: the example's run differs from examples/mill/stored-run.json (rerun with UPDATE_BOOK=1 if the change is meant, and redraw the book's figures)"
        );
    }
    assert_eq!(fresh, stored);
}

#[test]
#[ignore = "live: runs liggghts and liggghts-paper on examples/mill/in.mill (about a minute of CPU each)"]
fn live_the_example_mill_runs_both_laws() {
    let keep = tempfile::tempdir().unwrap();
    let output = millimpact()
        .args([
            "mill",
            "examples/mill/in.mill",
            "--format",
            "json",
            "--keep",
        ])
        .arg(keep.path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    the_run_is_the_stored_one(&report);
    let quantities = report["quantities"].as_array().unwrap();
    let power = &quantities[0];
    assert_eq!(power["quantity"], "power draw");
    for law in ["written", "switched"] {
        let mean = power[law]["mean"].as_f64().unwrap();
        assert!(mean > 0.0, "{law} power {mean}");
    }
    // One seed is too few to call anything resolved: a difference beyond Student's t at its
    // degrees of freedom (five blocks per law) only says to run more seeds.
    for q in quantities {
        assert_ne!(q["verdict"], "resolved", "{q}");
    }
    let df = power["difference"]["degrees_of_freedom"].as_f64().unwrap();
    assert!((4.0..=8.0).contains(&df), "{df}");
    for q in quantities {
        for law in ["written", "switched", "difference"] {
            for field in ["mean", "standard_error"] {
                assert!(q[law][field].as_f64().unwrap().is_finite(), "{q}");
            }
        }
    }
    let spectra = report["spectra"].as_array().unwrap();
    for pair in ["1-1", "1-2", "2-2", "1-wall", "2-wall"] {
        for law in ["written", "switched"] {
            let total: f64 = spectra
                .iter()
                .filter(|s| s["pair"] == pair && s["spectrum"] == "impact_energy")
                .map(|s| s[law]["mean"].as_f64().unwrap())
                .sum();
            assert!(total > 0.0, "no {pair} collisions under the {law} law");
        }
    }
    // The switched run really ran model paper in liggghts-paper, the written one model hertz.
    let runs = report["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    assert_eq!(runs[1]["law"], "paper");
    assert_eq!(runs[1]["code"], "liggghts-paper");
    let folders: Vec<_> = std::fs::read_dir(keep.path())
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let folder = |law: &str| {
        folders
            .iter()
            .find(|f| f.file_name().unwrap().to_string_lossy().starts_with(law))
            .unwrap_or_else(|| panic!("no {law} run folder in {folders:?}"))
            .clone()
    };
    let paper = std::fs::read_to_string(folder("paper").join("in.mill")).unwrap();
    assert!(paper.contains("pair_style gran model paper tangential history rolling_friction cdt"));
    assert!(paper.contains("wall/gran model paper"));
    assert!(!paper.contains("model hertz"));
    let log = std::fs::read_to_string(folder("paper").join("log.txt")).unwrap();
    assert!(!log.contains("ERROR"), "{log}");
    let hertz = std::fs::read_to_string(folder("hertz").join("in.mill")).unwrap();
    assert!(hertz.contains("model hertz") && !hertz.contains("model paper"));
}

#[test]
#[ignore = "live: runs liggghts on a deck that stops at its insertion"]
fn live_a_run_that_fails_exits_1_with_the_codes_error_line_and_its_log() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("meshes")).unwrap();
    std::fs::copy(
        root().join("examples/mill/meshes/drum.stl"),
        dir.path().join("meshes/drum.stl"),
    )
    .unwrap();
    let text = std::fs::read_to_string(root().join("examples/mill/in.mill"))
        .unwrap()
        .replace(
            "particles_in_region 100 region charge",
            "particles_in_region 100 region nowhere",
        );
    let deck = dir.path().join("in.mill");
    std::fs::write(&deck, text).unwrap();
    let output = millimpact()
        .arg("mill")
        .arg(&deck)
        .args(["--time", "0.01"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(output.stdout.is_empty());
    assert!(stderr.contains("saying `ERROR"), "{stderr}");
    let log = stderr
        .split("log kept in ")
        .nth(1)
        .map(|rest| {
            rest.split_whitespace()
                .next()
                .unwrap()
                .trim_end_matches(':')
        })
        .unwrap_or_else(|| panic!("no kept log in {stderr}"));
    assert!(std::path::Path::new(log).is_file(), "{log}");
    std::fs::remove_dir_all(std::path::Path::new(log).parent().unwrap()).unwrap();
}

#[test]
#[ignore = "live: runs python3 on the example's mesh script"]
fn live_the_shipped_drum_mesh_is_what_its_script_writes() {
    let status = std::process::Command::new("python3")
        .arg(root().join("examples/mill/make_meshes.py"))
        .arg("--check")
        .status()
        .unwrap();
    assert!(status.success());
}

/// `report --mill` from a folder outside the repository, on an absolute deck path, as a user
/// runs it: the part's figures and data are written, and its JSON is `mill`'s.
#[test]
#[ignore = "live: runs liggghts and liggghts-paper on examples/mill/in.mill for 0.3 s of rotation"]
fn live_report_mill_writes_the_mills_part_from_another_folder() {
    let elsewhere = tempfile::tempdir().unwrap();
    let deck = root().join("examples/mill/in.mill");
    let output = millimpact()
        .current_dir(elsewhere.path())
        .args(["report"])
        .arg(root().join("cases/ball_plate.toml"))
        .arg("--mill")
        .arg(&deck)
        .args(["--mill-time", "0.3", "--out", "report"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let out = elsewhere.path().join("report");
    for name in [
        "mill-1-power.svg",
        "mill-1-power.csv",
        "mill-1-impact-energy.svg",
        "mill-1-peak-force.svg",
        "mill-1-charge.svg",
        "mill-1-figures.csv",
        "mill-1-spectra.csv",
        "mill-1-runs.csv",
        "mill-1.csv",
    ] {
        assert!(out.join(name).is_file(), "{name} not written");
    }
    let mill: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("mill-1.json")).unwrap()).unwrap();
    assert_eq!(
        mill["reproduce"],
        format!("millimpact mill {} --time 0.3", deck.display())
    );
    let runs = mill["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    for run in runs {
        // Both routes to the power through the whole rotation, and the charge's 100 balls.
        let trace = run["trace"].as_array().unwrap();
        assert_eq!(trace.len(), 100);
        assert!(trace.iter().all(|t| t["power"].is_number()), "{run}");
        assert!(
            trace
                .iter()
                .filter(|t| t["weight_power"].is_number())
                .count()
                >= 50,
            "{run}"
        );
        assert_eq!(run["profile"].as_array().unwrap().len(), 100);
    }
    let index = std::fs::read_to_string(out.join("index.md")).unwrap();
    assert!(index.contains("Your mill:"), "no mill part in index.md");
    assert!(index.contains("mill-1-power.svg"));
}

/// `millimpact mill in.mill` from the deck's own folder, as users run it: the mesh files are
/// found from the working folder (the deck's path has no folder part).
#[test]
#[ignore = "live: runs liggghts and liggghts-paper on examples/mill/in.mill for 0.01 s of rotation"]
fn live_a_deck_named_without_its_folder_runs_from_that_folder() {
    let output = millimpact()
        .current_dir(root().join("examples/mill"))
        .args(["mill", "in.mill", "--time", "0.01", "--format", "json"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(report["deck"], "in.mill");
    assert_eq!(report["runs"].as_array().unwrap().len(), 2);
}
