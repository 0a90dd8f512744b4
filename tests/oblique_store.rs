//! The stored oblique runs (`reference/oblique/`) as `verify` checks them: every build that
//! renders a ball-on-plate oblique case has a run of it, each run's motion meets Coulomb's
//! closed form taken again now, and a changed motion or a missing run is found. No DEM code
//! needed.

mod common;

use std::path::Path;

use serde_json::Value;

use common::{millimpact, root};

/// A copy of the oblique cases and of the oblique store in a fresh folder: `(cases, reference)`.
fn copies(dir: &Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let cases = dir.join("cases");
    let oblique = cases.join("oblique");
    std::fs::create_dir_all(&oblique).unwrap();
    // verify reads a folder of cases; one that is not canonical asks nothing of the
    // canonical store.
    std::fs::copy(common::case_path("rod_end"), cases.join("a_rod.toml")).unwrap();
    for entry in std::fs::read_dir(root().join("cases/oblique")).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, oblique.join(path.file_name().unwrap())).unwrap();
    }
    let reference = dir.join("reference");
    for entry in std::fs::read_dir(root().join("reference/oblique")).unwrap() {
        let code = entry.unwrap().path();
        let to = reference.join("oblique").join(code.file_name().unwrap());
        std::fs::create_dir_all(&to).unwrap();
        for file in std::fs::read_dir(&code).unwrap() {
            let file = file.unwrap().path();
            std::fs::copy(&file, to.join(file.file_name().unwrap())).unwrap();
        }
    }
    (cases, reference)
}

fn verify(cases: &Path, reference: &Path) -> (Option<i32>, Vec<Value>) {
    let out = millimpact()
        .arg("verify")
        .arg("--cases")
        .arg(cases)
        .arg("--reference")
        .arg(reference)
        .args(["--format", "json"])
        .output()
        .unwrap();
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    (
        out.status.code(),
        report["rows"].as_array().unwrap().clone(),
    )
}

/// The shipped store passes, with a tangential row per stored run; the builds that run the
/// held-out cases are every build but the two that refuse oblique impacts.
#[test]
fn the_shipped_oblique_store_passes_and_covers_the_builds() {
    let dir = tempfile::tempdir().unwrap();
    let (cases, reference) = copies(dir.path());
    let (code, rows) = verify(&cases, &reference);
    let failing: Vec<&Value> = rows.iter().filter(|r| r["pass"] == false).collect();
    assert_eq!(code, Some(0), "{failing:?}");
    for case in common::oblique::HELD_OUT {
        let mut builds: Vec<&str> = rows
            .iter()
            .filter(|r| r["case"] == case && r["check"] == "tangential")
            .map(|r| r["source"].as_str().unwrap())
            .collect();
        builds.sort_unstable();
        let mut expected: Vec<&str> = millimpact::codes::CodeName::ALL
            .iter()
            .map(|c| c.name())
            .filter(|n| !["yade-paper", "kratos-paper"].contains(n))
            .collect();
        expected.sort_unstable();
        assert_eq!(builds, expected, "{case}");
    }
}

/// A stored motion moved by 2 % of the impact's change, and a run taken away, each fail
/// `verify` (exit 1) with a row that names them.
#[test]
fn a_changed_motion_and_a_missing_run_are_found() {
    let dir = tempfile::tempdir().unwrap();
    let (cases, reference) = copies(dir.path());
    let path = reference.join("oblique/lammps/ball_plate_sliding.json");
    let mut file: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let t = &mut file["runs"][0]["tangential"];
    let (start, out) = (
        t["tangential_velocity"].as_f64().unwrap(),
        t["tangential_velocity_out"].as_f64().unwrap(),
    );
    t["tangential_velocity_out"] = Value::from(out + 0.02 * (out - start));
    std::fs::write(&path, serde_json::to_string_pretty(&file).unwrap()).unwrap();
    std::fs::remove_file(reference.join("oblique/yade/ball_plate_spin.json")).unwrap();
    let (code, rows) = verify(&cases, &reference);
    assert_eq!(code, Some(1));
    let failing: Vec<&Value> = rows.iter().filter(|r| r["pass"] == false).collect();
    assert_eq!(failing.len(), 2, "{failing:?}");
    let changed = failing
        .iter()
        .find(|r| r["check"] == "tangential")
        .expect("the changed motion's row");
    assert_eq!(changed["source"], "lammps");
    assert!(
        changed["detail"]
            .as_str()
            .unwrap()
            .contains("not the closed form's now"),
        "{changed}"
    );
    let missing = failing
        .iter()
        .find(|r| r["check"] == "store")
        .expect("the missing run's row");
    assert_eq!(missing["source"], "yade");
    assert!(
        missing["detail"]
            .as_str()
            .unwrap()
            .contains("reference --code yade"),
        "{missing}"
    );
}
