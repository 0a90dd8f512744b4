//! `millimpact precision`: the observed orders, the documented JSON shape, the SVG, and one
//! live DEM code to prove the code path (the codes are installed; a missing binary fails).

mod common;

use common::{millimpact, shipped as case};
use millimpact::analysis::precision::{self, WorkPrecisionPoint};
use millimpact::solve::Method;
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
fn rk4_event_converges_at_order_4_in_contact_time_and_5_in_cor_and_peak() {
    for name in ["ball_plate", "rod_end"] {
        let points: Vec<WorkPrecisionPoint> =
            precision::method_sweep(&case(name), Method::Rk4Event, 1).unwrap();
        let q = precision::observed_orders(&points);
        let time = q.contact_time.unwrap();
        assert!(
            (time - 4.0).abs() <= 0.3,
            "{name}: contact-time order {time}"
        );
        // Superconvergence: COR and peak come from the energy, whose error is O(h^5).
        let cor = q.cor.unwrap();
        let peak = q.peak_deformation.unwrap();
        assert!((cor - 5.0).abs() <= 0.5, "{name}: COR order {cor}");
        assert!((peak - 5.0).abs() <= 0.5, "{name}: peak order {peak}");
    }
}

#[test]
fn paper_rk4_and_verlet_are_first_order_in_contact_time() {
    let c = case("ball_plate");
    for method in [Method::Rk4, Method::Verlet] {
        let points = precision::method_sweep(&c, method, 1).unwrap();
        // The bound on a staircase error: its upper envelope.
        let envelope = precision::envelope_orders(&points).contact_time.unwrap();
        assert!(
            (envelope - 1.0).abs() <= 0.3,
            "{}: contact-time envelope order {envelope}",
            method.name()
        );
    }
}

#[test]
fn log_slope_recovers_a_power_law() {
    let pairs: Vec<(f64, f64)> = (1..8)
        .map(|k| (1.0 / k as f64, 3.0 / (k as f64).powi(4)))
        .collect();
    let slope = precision::log_slope(&pairs).unwrap();
    assert!((slope - 4.0).abs() < 1e-12);
    assert_eq!(precision::log_slope(&pairs[..2]), None);
}

#[test]
fn sweeps_span_the_documented_ranges() {
    let n = precision::steps_per_period_sweep();
    assert_eq!((n[0], *n.last().unwrap()), (8, 20000));
    let r = precision::rtol_sweep();
    assert_eq!((r[0], *r.last().unwrap()), (1e-3, 1e-14));
    let c = precision::code_steps_sweep();
    assert_eq!(c.len(), 5);
    assert!(c[0] >= 15 && *c.last().unwrap() <= 2500);
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
    assert_eq!(lammps.len(), precision::code_steps_sweep().len());
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
