//! `millimpact precision`: the documented JSON shape, the SVG, the other formats, and one live
//! DEM code to prove the code path (the codes are installed; a missing binary fails). The
//! observed orders and the sweeps' ranges are the module's own unit tests.

mod common;

use common::millimpact;
use serde_json::Value;

fn run_json(args: &[&str]) -> Value {
    let out = millimpact()
        .args(args)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    serde_json::from_slice(&out).expect("precision --format json prints one JSON document")
}

#[test]
fn json_has_the_documented_shape_and_the_plot_is_an_svg() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("wp.svg");
    let doc = run_json(&[
        "precision",
        "cases/ball_plate.toml",
        "--methods",
        "rk4,rk4-event,dopri5,verlet",
        "--format",
        "json",
        "--repeats",
        "1",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    let points = doc["points"].as_array().unwrap();
    assert!(!points.is_empty());
    for p in points {
        for key in [
            "source",
            "knob",
            "value",
            "cor_error",
            "peak_deformation_error",
            "contact_time_error",
            "rhs_evaluations",
            "time_s",
        ] {
            assert!(p.get(key).is_some(), "point lacks {key}: {p}");
        }
        assert!(p["time_s"].as_f64().unwrap() > 0.0);
        assert!(p["rhs_evaluations"].as_u64().unwrap() > 0);
        let source = p["source"].as_str().unwrap();
        assert!(
            ["rk4", "rk4-event", "dopri5", "verlet"].contains(&source),
            "{source}"
        );
    }
    for method in ["rk4", "rk4-event", "dopri5", "verlet"] {
        assert!(
            points.iter().any(|p| p["source"] == method),
            "no {method} points"
        );
    }
    let orders = doc["orders"].as_object().unwrap();
    for method in ["rk4", "rk4-event", "verlet"] {
        assert!(
            orders[method].as_f64().unwrap().is_finite(),
            "order of {method}"
        );
    }
    let order = orders["rk4-event"].as_f64().unwrap();
    assert!((order - 4.0).abs() <= 0.3, "rk4-event order {order}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("<svg"));
    for label in ["rk4-event", "dopri5", "verlet", "run time"] {
        assert!(text.contains(label), "SVG lacks {label}");
    }
}

#[test]
fn markdown_and_csv_render() {
    for (format, opening) in [
        ("markdown", "| source | knob |"),
        ("csv", "source,knob,value,cor_error"),
    ] {
        let out = millimpact()
            .args([
                "precision",
                "cases/rod_end.toml",
                "--methods",
                "dopri5",
                "--repeats",
                "1",
            ])
            .args(["--format", format])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let text = String::from_utf8(out).unwrap();
        assert!(text.contains(opening), "{format}: {text:.300}");
    }
}

/// The LAMMPS path, live: five time steps, one run each after a warm-up. A missing `lmp`
/// fails the test.
#[test]
#[ignore = "live: runs LAMMPS (bash scripts/test.sh)"]
fn lammps_sweep_runs_live() {
    let doc = run_json(&[
        "precision",
        "cases/ball_plate.toml",
        "--methods",
        "rk4-event",
        "--codes",
        "lammps",
        "--format",
        "json",
        "--repeats",
        "1",
    ]);
    let points = doc["points"].as_array().unwrap();
    let lammps: Vec<&Value> = points.iter().filter(|p| p["source"] == "lammps").collect();
    // The five steps per contact the sweep documents, 20 to 2000.
    let steps: Vec<f64> = lammps
        .iter()
        .map(|p| p["value"].as_f64().unwrap())
        .collect();
    assert_eq!(steps, [20.0, 63.0, 200.0, 632.0, 2000.0]);
    for p in &lammps {
        assert_eq!(p["knob"], "steps_per_contact");
        let cor = p["cor_error"].as_f64().unwrap();
        assert!(
            cor.is_finite() && cor < 0.05,
            "LAMMPS COR error against its own law: {cor}"
        );
        assert!(p["time_s"].as_f64().unwrap() > 0.0);
        assert!(p["loop_time_s"].as_f64().unwrap() > 0.0);
    }
    // Its step error shrinks with its step.
    let first = lammps[0]["contact_time_error"].as_f64().unwrap();
    let last = lammps.last().unwrap()["contact_time_error"]
        .as_f64()
        .unwrap();
    assert!(last < first / 10.0, "{first} -> {last}");
    assert!(doc["targets"]["cost_ratio"].as_f64().unwrap() > 0.0);
}
