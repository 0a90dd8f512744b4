//! `millimpact mill` without a code: the deck as it is switched and instrumented, the refusals
//! (each one line, exit 2, before anything runs), and the report of two runs recorded by
//! `millimpact mill examples/mill/in.mill --time 0.05 --spectra-time 0.0003 --contact-every 10
//! --keep DIR` (in `tests/data/mill/`), in every format.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use std::path::{Path, PathBuf};

use common::mill::{EXAMPLE, recorded, recorded_options, small_plan};
use common::{codes_hidden, millimpact, root};
use millimpact::analysis::mill::{Verdict, report_from_folders};
use millimpact::codes::liggghts::mill::{MillDeck, MillLaw, MillPlan};
use millimpact::output::{Format, export};
use statrs::distribution::{ContinuousCDF, StudentsT};

#[test]
fn the_example_deck_is_read_with_its_drum_rotation_and_cors() {
    let deck = MillDeck::read(Path::new(EXAMPLE)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(deck.law, MillLaw::Hertz);
    assert_eq!(deck.types, 3);
    assert_eq!(deck.settling_steps, 100_000);
    assert_eq!(deck.rotation_steps, 600_000);
    assert_eq!(deck.rotating.len(), 1);
    let drum = &deck.rotating[0];
    assert_eq!(drum.mesh, "drum");
    assert_eq!(drum.axis, [0.0, 1.0, 0.0]);
    assert!((drum.angular_velocity - 2.0 * std::f64::consts::PI / 0.682).abs() < 1e-12);
    assert_eq!(deck.recorded_wall_meshes, ["drum"]);
    assert_eq!(deck.restitution[0], 0.5);
    assert_eq!(deck.restitution[8], 0.45);
    assert_eq!(deck.rotation_from.line, 63);
}

#[test]
fn the_switched_deck_runs_model_paper_at_each_pairs_eta_and_keeps_tangential_and_rolling() {
    let deck = MillDeck::read(Path::new(EXAMPLE)).unwrap();
    let text = deck.render(MillLaw::Paper, &small_plan());
    let lines: Vec<&str> = text.lines().collect();
    let loss = lines
        .iter()
        .find(|l| l.contains("property/global lossCoefficient"))
        .expect("a lossCoefficient table");
    let values: Vec<f64> = loss
        .split_whitespace()
        .skip(7)
        .map(|w| w.parse().unwrap())
        .collect();
    assert_eq!(values.len(), 9);
    for (eta, e) in values.iter().zip(&deck.restitution) {
        // The law's own COR of η is the pair's COR.
        assert!(
            (((1.0 - eta) / (1.0 + eta)).sqrt() - e).abs() < 1e-15,
            "{eta} {e}"
        );
    }
    assert!(lines.contains(&"pair_style gran model paper tangential history rolling_friction cdt"));
    assert!(lines.iter().any(|l| l.starts_with(
        "fix walls all wall/gran model paper tangential history rolling_friction cdt mesh"
    )));
    assert!(!text.contains("model hertz"));
    let mesh = lines.iter().find(|l| l.starts_with("fix drum")).unwrap();
    assert!(
        mesh.contains("mesh/surface/stress") && mesh.ends_with("reference_point 0e0 0e0 0e0"),
        "{mesh}"
    );
    assert!(
        mesh.contains(
            &root()
                .join("examples/mill/meshes/drum.stl")
                .display()
                .to_string()
        ),
        "{mesh}"
    );
    // The rotation cut to 1000 steps, the last 200 with the contacts recorded.
    let runs: Vec<&&str> = lines.iter().filter(|l| l.starts_with("run")).collect();
    assert_eq!(runs.len(), 3, "{runs:?}");
    assert_eq!(runs[1].trim(), "run 800");
    assert_eq!(runs[2].trim(), "run 200");
    // As written, nothing of the contact lines changes.
    let written = deck.render(MillLaw::Hertz, &small_plan());
    assert!(
        written
            .contains("pair_style      gran model hertz tangential history rolling_friction cdt")
    );
    assert!(!written.contains("lossCoefficient"));
}

#[test]
fn a_second_seed_replaces_every_insertion_seed() {
    let deck = MillDeck::read(Path::new(EXAMPLE)).unwrap();
    let first = deck.render(MillLaw::Hertz, &small_plan());
    let second = deck.render(
        MillLaw::Hertz,
        &MillPlan {
            seed: 1,
            ..small_plan()
        },
    );
    for seed in ["15485863", "15485867", "32452843", "32452867"] {
        assert!(first.contains(seed));
        assert!(!second.contains(seed), "{seed} kept");
    }
}

/// A copy of the example in a fresh folder, `edit` applied to its deck.
fn edited(edit: impl Fn(String) -> String) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("meshes")).unwrap();
    std::fs::copy(
        root().join("examples/mill/meshes/drum.stl"),
        dir.path().join("meshes/drum.stl"),
    )
    .unwrap();
    let text = std::fs::read_to_string(root().join(EXAMPLE)).unwrap();
    let path = dir.path().join("in.mill");
    std::fs::write(&path, edit(text)).unwrap();
    (dir, path)
}

/// Run `mill` with no code findable; require exit 2, nothing on stdout and one line on
/// stderr holding every piece of `expected`.
fn refused(args: &[&str], expected: &[&str]) {
    let output = millimpact()
        .arg("mill")
        .args(args)
        .envs(codes_hidden())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(output.stdout.is_empty());
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    for piece in expected {
        assert!(stderr.contains(piece), "`{piece}` not in {stderr}");
    }
}

#[test]
fn a_deck_without_a_rotating_mesh_is_refused() {
    let (_dir, path) = edited(|t| t.replace("fix             turn all move/mesh", "# fix turn"));
    refused(
        &[path.to_str().unwrap()],
        &[
            path.to_str().unwrap(),
            "no rotating mesh",
            "move/mesh mesh MESH rotate",
        ],
    );
}

#[test]
fn a_missing_mesh_file_is_refused() {
    let (_dir, path) = edited(|t| t.replace("meshes/drum.stl", "meshes/shell.stl"));
    refused(
        &[path.to_str().unwrap()],
        &[
            &format!("{}:42", path.display()),
            "mesh file `meshes/shell.stl` does not exist",
        ],
    );
}

#[test]
fn a_law_the_switch_cannot_express_is_refused() {
    let (_dir, path) = edited(|t| {
        t.replace(
            "model hertz tangential history rolling_friction cdt",
            "model hertz tangential no_history rolling_friction cdt",
        )
    });
    refused(
        &[path.to_str().unwrap()],
        &[
            &format!("{}:34", path.display()),
            "tangential no_history with rolling_friction cdt",
            "liggghts-paper is not built",
        ],
    );
    let (_dir, path) = edited(|t| {
        t.replace(
            "rolling_friction cdt\npair_coeff",
            "rolling_friction cdt limitForce on\npair_coeff",
        )
    });
    refused(
        &[path.to_str().unwrap()],
        &[&format!("{}:34", path.display()), "limitForce on"],
    );
}

#[test]
fn a_rotation_time_beyond_the_decks_is_refused() {
    refused(
        &[EXAMPLE, "--time", "2"],
        &[
            EXAMPLE,
            "--time = 2",
            "at most the deck's own 0.9 s",
            "in.mill:63",
        ],
    );
    refused(
        &[EXAMPLE, "--code", "yade"],
        &["--code = yade", "liggghts or liggghts-paper"],
    );
    refused(&[EXAMPLE, "--seeds", "17"], &["--seeds = 17", "1 to 16"]);
}

#[test]
fn the_recorded_runs_give_power_energy_and_every_pairs_spectrum() {
    let report = recorded();
    let power = &report.quantities[0];
    assert_eq!(power.quantity, "power draw");
    assert!(power.written.mean > 0.0 && power.switched.mean > 0.0);
    // One seed: five blocks per law, four degrees of freedom each, and nothing called resolved
    // (a difference beyond Student's t is a hint to run more seeds).
    for q in &report.quantities {
        if q.unit == "1/s" {
            continue;
        }
        assert_eq!(q.written.degrees_of_freedom, Some(4.0), "{q:?}");
        let df = q.difference.degrees_of_freedom.unwrap();
        assert!((4.0..=8.0).contains(&df), "{q:?}");
        let t = StudentsT::new(0.0, 1.0, df).unwrap().inverse_cdf(0.975);
        let beyond = q.difference.mean.abs() > t * q.difference.standard_error;
        let expected = if beyond {
            Verdict::TooFewSeeds
        } else {
            Verdict::NotResolved
        };
        assert_eq!(q.verdict, expected, "{q:?}");
        assert!(q.written.lag1_autocorrelation.is_some(), "{q:?}");
    }
    for q in &report.quantities {
        assert!(
            q.written.mean.is_finite() && q.switched.standard_error.is_finite(),
            "{q:?}"
        );
    }
    // The recorded window is 0.3 ms: every pair collides in it under one law or the other
    // (the live test asks each law for every pair over the example's own window).
    for pair in ["1-1", "1-2", "2-2", "1-wall", "2-wall"] {
        let total: f64 = report
            .spectra
            .iter()
            .filter(|s| s.pair == pair && s.spectrum == "impact_energy")
            .map(|s| s.written.mean + s.switched.mean)
            .sum();
        assert!(total > 0.0, "no {pair} collisions");
    }
}

#[test]
fn mill_snapshots_in_every_format() {
    let report = recorded();
    for format in [Format::Table, Format::Json, Format::Csv, Format::Markdown] {
        let text = export(&report, format).unwrap();
        insta::assert_snapshot!(format!("mill_example_{format:?}").to_lowercase(), text);
    }
}

#[test]
fn a_paper_deck_is_switched_to_hertz_at_the_cor_its_eta_gives() {
    let (_dir, path) = edited(|t| {
        t.replace("model hertz", "model paper").replace(
            "coefficientRestitution peratomtypepair 3 &\n                0.50 0.55 0.45 &\n                0.55 0.60 0.45 &\n                0.45 0.45 0.45",
            "lossCoefficient peratomtypepair 3 0.6 0.6 0.6 0.6 0.6 0.6 0.6 0.6 0.3",
        )
    });
    let deck = MillDeck::read(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(deck.law, MillLaw::Paper);
    assert_eq!(deck.restitution[0], 0.5);
    assert!((deck.restitution[8] - (0.7_f64 / 1.3).sqrt()).abs() < 1e-15);
    let text = deck.render(MillLaw::Hertz, &small_plan());
    let cor = text
        .lines()
        .find(|l| l.contains("property/global coefficientRestitution"))
        .expect("a coefficientRestitution table");
    assert!(
        cor.ends_with(&format!("5e-1 {:e}", (0.7_f64 / 1.3).sqrt())),
        "{cor}"
    );
    assert!(text.contains("pair_style gran model hertz tangential history rolling_friction cdt"));
    assert!(!text.contains("model paper"));
}

/// A run whose positions dump loses a particle on the way (a deck with `thermo_modify lost
/// ignore`) stops the comparison, naming how many of how many and the step.
#[test]
fn a_run_that_loses_particles_stops_the_comparison() {
    let deck = MillDeck::read(Path::new(EXAMPLE)).unwrap();
    let data = root().join("tests/data/mill");
    let copy = tempfile::tempdir().unwrap();
    for law in ["hertz-seed0", "paper-seed0"] {
        let to = copy.path().join(law);
        std::fs::create_dir(&to).unwrap();
        for entry in std::fs::read_dir(data.join(law)).unwrap() {
            let entry = entry.unwrap();
            std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
        }
    }
    // The last frame of the paper run's positions with its last particle gone.
    let positions = copy.path().join("paper-seed0/millimpact_positions.txt");
    let text = std::fs::read_to_string(&positions).unwrap();
    let last = text.rfind("ITEM: TIMESTEP").unwrap();
    let step: &str = text[last..].lines().nth(1).unwrap();
    let mut frame: Vec<&str> = text[last..].lines().collect();
    assert_eq!(frame[3], "100");
    frame[3] = "99";
    frame.pop();
    std::fs::write(
        &positions,
        format!("{}{}\n", &text[..last], frame.join("\n")),
    )
    .unwrap();
    let error = report_from_folders(
        &deck,
        &recorded_options(),
        &[
            (
                MillLaw::Hertz,
                0,
                "liggghts".into(),
                copy.path().join("hertz-seed0"),
            ),
            (
                MillLaw::Paper,
                0,
                "liggghts-paper".into(),
                copy.path().join("paper-seed0"),
            ),
        ],
    )
    .unwrap_err();
    let text = error.to_string();
    assert!(
        matches!(
            error,
            millimpact::analysis::mill::MillError::LostAtoms {
                had: 100,
                has: 99,
                law: MillLaw::Paper,
                ..
            }
        ),
        "{text}"
    );
    assert!(
        text.contains(&format!("lost 1 of its 100 particles by step {step}")),
        "{text}"
    );
    assert!(
        !millimpact::error::Blame::is_user_error(&error),
        "a run-time fault: exit 1"
    );
}
