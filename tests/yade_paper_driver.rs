//! YADE with the paper's law added by a Python hook (`yade-paper`, src/codes/yade/paper.rs):
//! its script, its law and what it refuses, a recorded run read and stepped (no YADE needed);
//! and live runs of the Debian YADE: the run against the harness's stepping of the law as
//! YADE's leap-frog steps it, the realised COR against `sqrt((1−η)/(1+η))` within the predicted
//! step error, a held-out impact through `reference`, and a ball resting under gravity with the
//! hook a user puts in their own script (the book's lines, run as they are printed).
//!
//! The live tests FAIL (not skip) when YADE is not installed.

use std::process::Command;

use millimpact::codes::batch::run_batch;
use millimpact::codes::yade::paper::{YadePaper, code_frame};
use millimpact::codes::yade::{Yade, parse_trajectory};
use millimpact::codes::{CodeDriver, CodeSetup, RunOptions, prepare_with};
use millimpact::model::case::Case;
use millimpact::model::exact;
use millimpact::model::law::CodeLaw;
use millimpact::model::trajectory::{TrajectoryMetrics, trajectory_metrics};
use millimpact::solve::dashpot::{StepScheme, own_law_metrics};

mod common;

use common::paper_build::{
    ETAS, SCENES, assert_cor_within_the_step_band, assert_refuses_eta_outside_its_range,
    assert_run_is_the_law_stepped, clamp_refused_in_one_line,
};
use common::{millimpact, root, shipped};

/// The book's page with the lines a YADE user puts in their own script.
const CHAPTER: &str = "docs/src/paper-law-in-dem.md";

/// The setup of a shipped case at η, as `reference` makes it, at `per_contact` steps per
/// elastic contact time (the default 1000 without).
fn setup_at(scene: &str, eta: f64, per_contact: Option<u32>) -> CodeSetup {
    let case = shipped(scene).with_loss_coefficient(eta);
    prepare_with(&YadePaper, &case, per_contact, None, false, None).unwrap()
}

fn setup(scene: &str, eta: f64) -> CodeSetup {
    setup_at(scene, eta, None)
}

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

// ---------------------------------------------------------------------------------------------
// The script, the law, the refusals, a recorded run (no YADE needed).

/// The script gives the hook the case's law in exact numbers (η as the case gives it, not from
/// the COR), has no collider and no contact law of YADE's, and places the hook between
/// `ForceResetter` and an undamped `NewtonIntegrator`.
#[test]
fn the_script_carries_the_law_exactly_and_only_the_hooks_force() {
    for scene in SCENES {
        let s = setup(scene, 0.95);
        let input = YadePaper.render(&s).unwrap();
        assert_eq!(input.args, ["-j1", "-n", "-x", "paper.py"]);
        let text = &input.text;
        let law = YadePaper::paper_law(&s);
        for (key, value) in [
            ("stiffness", law.stiffness),
            ("exponent", law.exponent),
            ("pair_mass", law.mass),
            ("timestep", s.timestep),
        ] {
            assert!(
                text.contains(&format!("\"{key}\": {value:e}")),
                "{scene}: {key}"
            );
        }
        assert!(text.contains("\"loss_coefficient\": 9.5e-1"), "{scene}");
        assert!(text.contains(&format!("\"scene\": \"{scene}\"")), "{scene}");
        assert!(text.contains(&format!("\"steps\": {}", s.steps)), "{scene}");
        for absent in ["Collider(", "InteractionLoop(", "Law2_", "Ip2_"] {
            assert!(!text.contains(absent), "{scene}: {absent}");
        }
        let engines: Vec<&str> = text
            .lines()
            .map(str::trim)
            .filter(|l| {
                ["ForceResetter(", "PyRunner(", "NewtonIntegrator("]
                    .iter()
                    .any(|k| l.starts_with(k))
            })
            .collect();
        assert_eq!(
            engines,
            [
                "ForceResetter(),",
                "PyRunner(iterPeriod=1, initRun=True, command=\"hook()\", updateGlobals=False),",
                "NewtonIntegrator(damping=0.0, gravity=(0.0, 0.0, 0.0)),",
            ],
            "{scene}"
        );
        assert!(text.contains("FILES = [[\"trajectory.csv\"]]"));
    }
}

/// A rigid plate is the plane with the ball's own `E/(1−ν²)`, an elastic one mixes its own in:
/// the hook's `C` is the case's, bit for bit, so the model difference is zero.
#[test]
fn its_law_is_the_cases_paper_law_exactly() {
    for scene in SCENES {
        let s = setup(scene, 0.7);
        let case = shipped(scene).with_loss_coefficient(0.7).law();
        let CodeLaw::Paper(law) = YadePaper.law(&s) else {
            panic!("{scene}: the paper's law")
        };
        assert_eq!(law, case, "{scene}");
        let own = own_law_metrics(&CodeLaw::Paper(law), s.impact_velocity, 1e-13).unwrap();
        assert_eq!(own.cor.to_bits(), exact::restitution(0.7).to_bits());
        assert_eq!(YadePaper.expected_restitution(&s), None);
        assert_eq!(YadePaper.step_scheme(), StepScheme::LeapFrog);
        assert!(YadePaper.takes_loss_coefficient());
    }
    let mut rigid = shipped("ball_plate");
    rigid.scene = match rigid.scene {
        millimpact::model::scene::Scene::BallPlate { ball, .. } => {
            millimpact::model::scene::Scene::BallPlate {
                ball,
                plate: millimpact::model::scene::Plate::Rigid,
            }
        }
        other => other,
    };
    let s = prepare_with(&YadePaper, &rigid, None, None, false, None).unwrap();
    let e_star = 2.0e11 / (1.0 - 0.3 * 0.3);
    assert!(
        relative(
            YadePaper::paper_law(&s).stiffness,
            4.0 / 3.0 * e_star * 0.02f64.sqrt()
        ) < 1e-15
    );
}

/// The frame is YADE's coordinates mirrored: sphere 1 at `−r1` below the plane (height `r1`),
/// or at the origin with sphere 2 at `r1 + r2`; touching, with the script's masses.
#[test]
fn the_frame_is_the_scripts_start() {
    let plate = setup("ball_plate", 0.35);
    let f = code_frame(&plate);
    let bits = |x: f64| x.to_bits();
    assert_eq!(bits(f.reach), bits(0.02));
    assert_eq!(bits(f.upper.height), bits(0.02));
    assert_eq!(bits(f.upper.velocity), bits(-2.0));
    assert_eq!(bits(f.upper.mass), bits(plate.sphere.mass));
    assert!(f.lower.is_none());
    let pair = setup("ball_ball", 0.35);
    let f = code_frame(&pair);
    let lower = f.lower.unwrap();
    // Touching, and approaching at the impact speed, both exactly.
    assert_eq!(bits(f.reach - (f.upper.height - lower.height)), bits(0.0));
    assert_eq!(bits(lower.velocity - f.upper.velocity), bits(2.0));
    assert_eq!(YadePaper.frame(&pair), Some(f));
}

/// What the hook cannot run is refused before YADE starts: η outside [0, 1) (and NaN), a clamp.
#[test]
fn the_driver_refuses_eta_out_of_range_and_a_clamp() {
    let good = setup("ball_plate", 0.35);
    assert_refuses_eta_outside_its_range(&YadePaper, &good);
    let clamped = CodeSetup {
        clamp_attractive: true,
        ..good
    };
    let err = YadePaper.render(&clamped).unwrap_err().to_string();
    assert!(err.contains("never attracts"), "{err}");
    clamp_refused_in_one_line("yade-paper");
}

/// A batch holds every impact of one time step in one scene (one group), a new group at each
/// change of step, each impact writing its own file.
#[test]
fn a_batch_groups_impacts_by_time_step() {
    let runner = YadePaper.batch().unwrap();
    let mut setups: Vec<CodeSetup> = SCENES
        .iter()
        .flat_map(|scene| [0.0, 0.7].map(|eta| setup_at(scene, eta, Some(200))))
        .collect();
    let mut other = setups[0].clone();
    other.timestep *= 0.5;
    setups.push(other);
    let text = runner.render_batch(&setups).unwrap().text;
    // Each scene's contact time sets its step: three groups of two, and the halved step a fourth.
    assert!(
        text.contains("GROUPS = [[0, 1], [2, 3], [4, 5], [6]]"),
        "{text}"
    );
    assert!(text.contains(
        "FILES = [[\"trajectory-1.csv\", \"trajectory-2.csv\"], [\"trajectory-3.csv\", \"trajectory-4.csv\"], [\"trajectory-5.csv\", \"trajectory-6.csv\"], [\"trajectory-7.csv\"]]"
    ));
    // A group may hold several scenes: only the step must be one.
    let mixed = [
        setups[0].clone(),
        CodeSetup {
            timestep: setups[0].timestep,
            ..setups[4].clone()
        },
    ];
    let text_mixed = runner.render_batch(&mixed).unwrap().text;
    assert!(text_mixed.contains("GROUPS = [[0, 1]]"), "{text_mixed}");
    assert_eq!(text.matches("{\"scene\": ").count(), setups.len());
    assert!(runner.render_batch(&[]).is_err());
}

/// The recorded run (tests/data/yade-paper: ball_plate, η = 0.35, 200 steps per contact) is
/// what today's driver renders, and its rows are the law stepped in YADE's coordinates: the
/// same COR, peak overlap and peak force to the last bit, every overlap within 1e-12 of its
/// stepped row.
#[test]
fn the_recorded_run_is_the_law_stepped_as_yade_steps_it() {
    let data = root().join("tests/data/yade-paper");
    let s = setup_at("ball_plate", 0.35, Some(200));
    let script = std::fs::read_to_string(data.join("paper.py")).unwrap();
    assert_eq!(YadePaper.render(&s).unwrap().text, script);
    let log = std::fs::read_to_string(data.join("log.txt")).unwrap();
    let run = YadePaper.parse(&s, &data, &log).unwrap();
    assert_eq!(run.version.as_deref(), Some("2023.02a"));
    assert!(run.loop_time.is_some_and(|t| t > 0.0));
    let t = &run.trajectory;
    assert_eq!(t.overlap[0].to_bits(), 0f64.to_bits());
    let law = YadePaper.law(&s);
    let ours = YadePaper
        .stepping(&s)
        .trajectory(&law, s.impact_velocity, s.timestep, s.steps, 0.0);
    assert_eq!(ours.overlap.len(), t.overlap.len());
    for (k, (a, b)) in t.overlap.iter().zip(&ours.overlap).enumerate() {
        assert!((a - b).abs() <= 1e-12 * 7.4e-5, "row {k}: {a:e} vs {b:e}");
    }
    let (code, stepped) = (
        trajectory_metrics(t).unwrap(),
        trajectory_metrics(&ours).unwrap(),
    );
    assert_eq!(code.cor.to_bits(), stepped.cor.to_bits());
    assert_eq!(
        code.peak_deformation.to_bits(),
        stepped.peak_deformation.to_bits()
    );
    assert_eq!(code.peak_force.to_bits(), stepped.peak_force.to_bits());
    // The parse is the stock YADE driver's reader.
    let text = std::fs::read_to_string(data.join("trajectory.csv")).unwrap();
    assert_eq!(&parse_trajectory(&text).unwrap(), t);
    assert_eq!(Yade.parse(&s, &data, &log).unwrap(), run);
}

/// The book's `paper_force` is the driver's, line for line: the lines a user copies are the
/// ones the harness runs.
#[test]
fn the_books_hook_has_the_drivers_force() {
    let function = |text: &str| -> String {
        let start = text.find("def paper_force(").expect("a paper_force");
        let rest = &text[start..];
        let end = rest.find("\n\n").unwrap_or(rest.len());
        rest[..end].to_string()
    };
    let driver = std::fs::read_to_string(root().join("src/codes/yade/paper.py")).unwrap();
    let book = hook_lines();
    assert_eq!(function(&book), function(&driver));
}

/// The hook a YADE user puts in their own script, as the book prints it (the fenced block after
/// the marker line).
fn hook_lines() -> String {
    let page = std::fs::read_to_string(root().join(CHAPTER)).unwrap();
    let marker = "<!-- yade-paper hook: run by tests/yade_paper_driver.rs -->";
    let at = page.find(marker).expect("the hook's marker in the chapter");
    let rest = &page[at + marker.len()..];
    let open = rest.find("```python\n").expect("a python block") + "```python\n".len();
    let close = rest[open..].find("```").expect("its end");
    rest[open..open + close].to_string()
}

// ---------------------------------------------------------------------------------------------
// Live runs of YADE.

fn require_yade() {
    if let Err(e) = YadePaper.locate() {
        panic!(
            "YADE is not installed ({e}): bash scripts/install-dem-codes.sh; this live test fails rather than skips"
        );
    }
}

/// Each setup run, in one batch (each impact of a batch is its single run to the last bit:
/// tests/batches.rs), as figures.
fn runs(setups: &[CodeSetup]) -> Vec<TrajectoryMetrics> {
    let batch = run_batch(&YadePaper, setups, &RunOptions::default()).unwrap();
    batch
        .runs
        .into_iter()
        .zip(setups)
        .map(|(run, s)| {
            let run =
                run.unwrap_or_else(|e| panic!("{} η={:?}: {e}", s.case_name, s.loss_coefficient));
            assert_eq!(run.version.as_deref(), Some("2023.02a"));
            trajectory_metrics(&run.trajectory).unwrap()
        })
        .collect()
}

/// The run and the harness's stepping of the paper's law as YADE steps it (leap-frog in YADE's
/// coordinates, the branch from the half-step velocity within the one-step band) agree to
/// 1e-12 in COR, peak overlap, peak force and contact time: three scenes, η from 0 to 0.95, and
/// 200, 1000 and 4000 steps per contact.
#[test]
#[ignore = "live: runs YADE (bash scripts/test.sh)"]
fn live_run_equals_the_rust_stepping() {
    require_yade();
    let mut setups = Vec::new();
    for scene in SCENES {
        for eta in ETAS {
            setups.push(setup(scene, eta));
        }
        for per_contact in [200, 4000] {
            setups.push(setup_at(scene, 0.7, Some(per_contact)));
        }
    }
    for (s, code) in setups.iter().zip(runs(&setups)) {
        let label = format!(
            "{} η={:?} {} steps",
            s.case_name, s.loss_coefficient, s.steps
        );
        assert_run_is_the_law_stepped(&YadePaper, s, &code, &label);
    }
}

/// The realised COR is `sqrt((1−η)/(1+η))` within the step error predicted for the step: it
/// lies in the band the law stepped over 32 start phases spans, and no point of that band is
/// further from the closed form than [`paper_cor_step_error`] (leap-frog moves the bodies as
/// velocity Verlet does, with the same forces: the same bound).
#[test]
#[ignore = "live: runs YADE (bash scripts/test.sh)"]
fn live_cor_is_the_closed_form_within_the_predicted_step_error() {
    require_yade();
    let setups: Vec<CodeSetup> = SCENES
        .iter()
        .flat_map(|scene| ETAS.map(|eta| setup(scene, eta)))
        .collect();
    for (s, code) in setups.iter().zip(runs(&setups)) {
        let eta = s.loss_coefficient.unwrap();
        let label = format!("{} η={eta}", s.case_name);
        assert_cor_within_the_step_band(&YadePaper, s, eta, code.cor, &label);
    }
}

/// `reference --code yade-paper` on an impact no stored run or test above uses (a 6 mm glass
/// ball on an aluminium plate at 3.7 m/s, η = 0.6) at 2000 steps per contact: the COR within
/// 5e-4 of the closed form, the run within 1e-9 of the law stepped, no model difference.
#[test]
#[ignore = "live: runs YADE (bash scripts/test.sh)"]
fn live_reference_on_a_held_out_impact() {
    require_yade();
    let dir = tempfile::TempDir::new().unwrap();
    let case = dir.path().join("glass_on_aluminium.toml");
    std::fs::write(
        &case,
        "scene = \"ball_plate\"\nimpact_velocity = 3.7\nloss_coefficient = 0.6\n\n\
         [ball]\nradius = 0.006\ndensity = 2500.0\nyoungs_modulus = 6.3e10\npoisson_ratio = 0.22\n\n\
         [plate]\nrigid = false\nyoungs_modulus = 7.0e10\npoisson_ratio = 0.33\n",
    )
    .unwrap();
    let out = millimpact()
        .args(["reference", "--code", "yade-paper"])
        .arg(&case)
        .args(["--steps-per-contact", "2000", "--format", "json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let r: millimpact::ReferenceRecord = serde_json::from_slice(&out.stdout).unwrap();
    let e = exact::restitution(0.6);
    assert!(
        (r.figures.cor - e).abs() <= 5e-4,
        "{} vs {e}",
        r.figures.cor
    );
    assert!((r.figures.cor - r.law_at_step.cor).abs() <= 1e-9);
    assert!(relative(r.figures.peak_deformation, r.law_at_step.peak_deformation) <= 1e-9);
    let a = r.attribution();
    assert_eq!(a.model.cor.to_bits(), 0f64.to_bits());
    assert!(a.integration.cor.abs() > 1e-10, "a real step error: {a:?}");
    let held_out = Case::load(&case).unwrap();
    assert_eq!(r.paper_exact.cor.to_bits(), e.to_bits());
    assert_eq!(r.setup.loss_coefficient, Some(held_out.loss_coefficient));
}

/// A script as a YADE user writes it: a steel ball dropped onto the plane z = 0 from touch
/// under gravity, with the book's hook (η = 0.35); after it settles, the hook's force equals
/// the weight within 1e-3 at every step. The same script with a plain sign(ẏ) instead of the
/// one-step band alternates by more than 0.3 m g from step to step: the test tells them apart.
#[test]
#[ignore = "live: runs YADE (bash scripts/test.sh)"]
fn live_a_resting_ball_carries_its_weight_without_alternating() {
    require_yade();
    let hook = hook_lines();
    let scene = "
from math import sqrt
R, RHO, E, NU = 0.02, 7800.0, 2.0e11, 0.3
E_STAR = 1.0 / ((1.0 - NU**2) / E + (1.0 - NU**2) / E)
ball = O.bodies.append(sphere((0.0, 0.0, R), R, material=FrictMat(young=E, poisson=NU, density=RHO)))
O.bodies[ball].state.blockedDOFs = 'XYZ'
PAPER_CONTACTS = [(ball, 4.0 / 3.0 * E_STAR * sqrt(R), 1.5, 0.35)]
O.engines = [
    ForceResetter(),
    PyRunner(iterPeriod=1, command='paper_hook()'),
    NewtonIntegrator(damping=0.0, gravity=(0.0, 0.0, -9.81)),
]
O.dt = 1e-6
";
    let plain = "
def paper_force(overlap, rate, stiffness, exponent, eta, mass, dt):
    if overlap <= 0.0:
        return 0.0
    return stiffness * overlap ** exponent * (1.0 + eta * ((rate > 0) - (rate < 0)))
";
    let record = "
forces = []
for _ in range(40000):
    O.step()
    forces.append(O.forces.f(ball)[2])
weight = O.bodies[ball].state.mass * 9.81
settled = forces[30000:]
print('MILLIMPACT weight=%r low=%r high=%r swing=%r' % (weight, min(settled), max(settled), max(abs(a - b) for a, b in zip(settled, settled[1:]))))
";
    let run = |extra: &str| -> [f64; 4] {
        let dir = tempfile::TempDir::new().unwrap();
        let script = dir.path().join("resting.py");
        std::fs::write(&script, format!("{hook}\n{scene}\n{extra}\n{record}")).unwrap();
        let out = Command::new("yade")
            .args(["-j1", "-n", "-x"])
            .arg(&script)
            .current_dir(dir.path())
            .env("TMPDIR", dir.path())
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{text}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let line = text
            .lines()
            .find_map(|l| l.trim().strip_prefix("MILLIMPACT "))
            .unwrap_or_else(|| panic!("no result line: {text}"));
        let values: Vec<f64> = line
            .split_whitespace()
            .map(|f| f.split_once('=').unwrap().1.parse().unwrap())
            .collect();
        [values[0], values[1], values[2], values[3]]
    };
    let [weight, low, high, swing] = run("");
    eprintln!(
        "with the band: weight {weight:e} N, force in [{low:e}, {high:e}] N, step to step {swing:e} N"
    );
    assert!(
        (low - weight).abs() <= 1e-3 * weight && (high - weight).abs() <= 1e-3 * weight,
        "resting force in [{low}, {high}] N against the weight {weight} N"
    );
    assert!(swing <= 1e-3 * weight, "step to step {swing} N");
    let [weight, low, high, swing] = run(plain);
    eprintln!(
        "plain sign: weight {weight:e} N, force in [{low:e}, {high:e}] N, step to step {swing:e} N"
    );
    assert!(
        swing > 0.3 * weight,
        "a plain sign should alternate: step to step {swing} N, weight {weight} N"
    );
}
