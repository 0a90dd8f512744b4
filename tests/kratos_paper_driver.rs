//! Kratos DEM with the paper's law (`kratos-paper`, the force set through
//! `EXTERNAL_APPLIED_FORCE` before every `SolveSolutionStep`): its script, its law and what it
//! refuses, a recorded run (no Kratos needed), why the velocity-Verlet step bound holds for
//! symplectic Euler, and live runs of the installed Kratos: each run against the harness's
//! stepping of the law, the COR within the predicted step band, a batch against single runs,
//! a held-out case through `reference`, and a ball at rest under gravity.
//!
//! The live tests FAIL (not skip) when Kratos is not installed.

use std::path::Path;

use millimpact::codes::batch::run_batch;
use millimpact::codes::kratos::paper::{KratosPaper, render_script};
use millimpact::codes::kratos::{Kratos, particle_mass};
use millimpact::codes::{
    CodeDriver, CodeError, CodeSetup, LocateError, ParseError, ParsedRun, RenderedInput,
    RunOptions, prepare_with, run_code,
};
use millimpact::model::exact;
use millimpact::model::law::CodeLaw;
use millimpact::model::trajectory::{TrajectoryMetrics, trajectory_metrics};
use millimpact::solve::dashpot::{
    StepScheme, own_law_metrics, paper_cor_step_error, step_trajectory_from,
};

mod common;

use common::paper_build::{
    ETAS, SCENES, assert_cor_within_the_step_band, assert_refuses_eta_outside_its_range,
    assert_run_is_the_law_stepped, clamp_refused_in_one_line,
};
use common::{millimpact, root, shipped};

/// The recorded run: ball_plate at η = 0.35, the default step, 60 steps.
const SAMPLE: &str = "tests/data/kratos-paper";

/// The setup of a shipped case at η, as `reference` makes it (`steps_per_contact` steps per
/// elastic contact time, 1000 by default).
fn setup_at(scene: &str, eta: f64, steps_per_contact: Option<u32>) -> CodeSetup {
    let case = shipped(scene).with_loss_coefficient(eta);
    prepare_with(&KratosPaper, &case, steps_per_contact, None, false, None).unwrap()
}

fn setup(scene: &str, eta: f64) -> CodeSetup {
    setup_at(scene, eta, None)
}

/// The setup the recorded run was made from.
fn sample_setup() -> CodeSetup {
    CodeSetup {
        steps: 60,
        ..setup("ball_plate", 0.35)
    }
}

// ---------------------------------------------------------------------------------------------
// The script, the law, the refusals, the recorded run (no Kratos needed).

/// The recorded run's script is what the driver renders now for its setup, and a script
/// carries each impact's values exactly (η as the case gives it), no gravity, and no wall
/// condition: the plate is the hook's plane.
#[test]
fn the_script_carries_each_impact_and_no_stock_wall() {
    let rendered = KratosPaper.render(&sample_setup()).unwrap();
    assert_eq!(rendered.file_name, "paper.py");
    assert_eq!(rendered.args, ["paper.py"]);
    let recorded = std::fs::read_to_string(root().join(SAMPLE).join("paper.py")).unwrap();
    assert_eq!(rendered.text, recorded);
    for scene in SCENES {
        let s = setup(scene, 0.95);
        let text = KratosPaper.render(&s).unwrap().text;
        let CodeLaw::Paper(law) = KratosPaper.law(&s) else {
            panic!("the paper's law")
        };
        for cell in [
            format!("\"scene\": \"{scene}\""),
            "\"loss_coefficient\": 9.5e-1".to_string(),
            format!("\"stiffness\": {:e}", law.stiffness),
            format!("\"exponent\": {:e}", law.exponent),
            format!("\"timestep\": {:e}", s.timestep),
            format!("\"steps\": {},", s.steps),
        ] {
            assert!(text.contains(&cell), "{scene}: {cell}");
        }
        assert!(text.contains("\nGRAVITY = 0e0\n"), "{scene}");
        // common.py defines add_wall and relation (a stock law); the paper's part never calls
        // the first, and the second only for a linear law of zero stiffness.
        let own = &text[text.find("# ---- End of the shared part.").unwrap()..];
        assert!(!own.contains("add_wall("), "{scene}");
        let relations: Vec<&str> = own.lines().filter(|l| l.contains("relation(")).collect();
        assert!(!relations.is_empty(), "{scene}");
        for line in relations {
            assert!(line.contains("\"rod_end\", 1.0, 0.0)"), "{scene}: {line}");
        }
        assert!(text.contains("KM.EXTERNAL_APPLIED_FORCE"), "{scene}");
    }
}

/// The driver refuses η outside [0, 1) (and NaN), a clamp, before Kratos runs; `--clamp` on
/// the command line is bad input (exit 2).
#[test]
fn the_driver_refuses_eta_out_of_range_and_a_clamp() {
    let good = setup("ball_plate", 0.35);
    assert_refuses_eta_outside_its_range(&KratosPaper, &good);
    let clamped = CodeSetup {
        clamp_attractive: true,
        ..good
    };
    let err = KratosPaper.render(&clamped).unwrap_err().to_string();
    assert!(err.contains("never attracts"), "{err}");
    clamp_refused_in_one_line("kratos-paper");
}

/// Its law is the paper's with Kratos' own masses and the stiffness of Kratos' Hertz law (the
/// plate's own E and ν mixed in), equal to the case's to rounding: no model difference, the
/// closed form to the bit; stepped as leap-frog from touch, with no frame.
#[test]
fn its_law_is_the_papers_law_with_kratos_masses() {
    for scene in SCENES {
        let s = setup(scene, 0.7);
        let CodeLaw::Paper(law) = KratosPaper.law(&s) else {
            panic!("the paper's law")
        };
        let case = shipped(scene).with_loss_coefficient(0.7).law();
        assert!((law.mass / case.mass - 1.0).abs() < 1e-15, "{scene}");
        assert!(
            (law.stiffness / case.stiffness - 1.0).abs() < 1e-15,
            "{scene}"
        );
        assert_eq!(law.exponent.to_bits(), case.exponent.to_bits());
        assert_eq!(law.loss_coefficient.to_bits(), 0.7f64.to_bits());
        let m1 = particle_mass(s.sphere.radius, s.sphere.density);
        let mass = match s.other_sphere.filter(|_| scene == "ball_ball") {
            Some(o) => 1.0 / (1.0 / m1 + 1.0 / particle_mass(o.radius, o.density)),
            None => m1,
        };
        assert_eq!(law.mass.to_bits(), mass.to_bits(), "{scene}");
        if scene != "rod_end" {
            // Kratos' Hertz law's stiffness, the one the stock driver's dashpot law has.
            let stock = Kratos.dashpot_law(&CodeSetup {
                loss_coefficient: None,
                ..s.clone()
            });
            assert_eq!(
                law.stiffness.to_bits(),
                stock.stiffness.to_bits(),
                "{scene}"
            );
        }
        let own = own_law_metrics(&CodeLaw::Paper(law), s.impact_velocity, 1e-13).unwrap();
        assert_eq!(own.cor.to_bits(), exact::restitution(0.7).to_bits());
        assert_eq!(KratosPaper.expected_restitution(&s), None);
        assert_eq!(KratosPaper.step_scheme(), StepScheme::LeapFrog);
        assert!(KratosPaper.frame(&s).is_none());
        assert_eq!(KratosPaper.start_gap(&s).to_bits(), 0f64.to_bits());
    }
}

/// A rigid plate is Kratos' stock rigid wall (E = 1e30, ν = 0): `E*` the ball's `E/(1−ν²)`.
#[test]
fn a_rigid_plate_is_the_ball_alone() {
    let case = shipped("ball_plate_rigid");
    let s = prepare_with(&KratosPaper, &case, None, None, false, None).unwrap();
    let CodeLaw::Paper(law) = KratosPaper.law(&s) else {
        panic!("the paper's law")
    };
    let alone = 4.0 / 3.0 * (2e11 / (1.0 - 0.09)) * 0.02f64.sqrt();
    assert!((law.stiffness / alone - 1.0).abs() < 1e-15, "{law:?}");
}

/// A batch holds any scenes at one time step, each impact's values as its single script's.
#[test]
fn a_batch_lists_each_impact_and_refuses_two_steps() {
    let runner = KratosPaper.batch().unwrap();
    let setups: Vec<CodeSetup> = [0.0, 0.35, 0.7].map(|eta| setup("ball_ball", eta)).to_vec();
    let text = runner.render_batch(&setups).unwrap().text;
    for s in &setups {
        let single = KratosPaper.render(s).unwrap().text;
        let line = single
            .lines()
            .find(|l| l.trim_start().starts_with("{\"scene\""))
            .unwrap();
        assert!(text.contains(line), "{line}");
    }
    assert!(text.starts_with("# millimpact: 3 impacts"));
    let mut finer = setups[1].clone();
    finer.timestep /= 2.0;
    assert!(runner.render_batch(&[setups[0].clone(), finer]).is_err());
    assert!(runner.render_batch(&[]).is_err());
}

/// The recorded run parses: 61 rows (the state before each step and after the last), the
/// hook's force from the row's own state, and the state the run starts from: touching.
// The rows are written with %r: the start is exactly 0 and 2.
#[allow(clippy::float_cmp)]
#[test]
fn parses_the_recorded_run() {
    let dir = root().join(SAMPLE);
    let log = std::fs::read_to_string(dir.join("log.txt")).unwrap();
    let s = sample_setup();
    let run = KratosPaper.parse(&s, &dir, &log).unwrap();
    assert_eq!(run.version.as_deref(), Some("10.4.4"));
    assert!(run.loop_time.is_some_and(|t| t > 0.0 && t < 1.0));
    let t = &run.trajectory;
    assert_eq!(t.time.len(), 61);
    assert_eq!(
        (t.overlap[0], t.approach_velocity[0], t.normal_force[0]),
        (0.0, 2.0, 0.0)
    );
    // The harness's stepping gives the same rows to rounding of the absolute height.
    let law = KratosPaper.law(&s);
    let stepped = step_trajectory_from(&law, 2.0, s.timestep, 60, StepScheme::LeapFrog, 0.0);
    for k in 1..=60 {
        let f = stepped.normal_force[k];
        assert!(
            (t.normal_force[k] - f).abs() <= 1e-9 * f,
            "{k}: {} vs {f}",
            t.normal_force[k]
        );
        assert!((t.overlap[k] - stepped.overlap[k]).abs() < 1e-17, "{k}");
    }
}

/// A run whose step count is not the setup's, or in which a stock law added a force, is
/// refused, not read.
#[test]
fn a_foreign_force_or_another_step_count_is_refused() {
    let dir = root().join(SAMPLE);
    let log = std::fs::read_to_string(dir.join("log.txt")).unwrap();
    let s = sample_setup();
    let foreign = log.replace("force_mismatch=0.0", "force_mismatch=3.5e-2");
    match KratosPaper.parse(&s, &dir, &foreign) {
        Err(ParseError::ForeignForce { mismatch }) => assert!((mismatch - 3.5e-2).abs() < 1e-18),
        other => panic!("{other:?}"),
    }
    let shorter = CodeSetup {
        steps: 59,
        ..s.clone()
    };
    assert!(matches!(
        KratosPaper.parse(&shorter, &dir, &log),
        Err(ParseError::StepCount { ran: 60, asked: 59 })
    ));
    let bad = log.replace("force_mismatch=0.0", "force_mismatch=x");
    assert!(matches!(
        KratosPaper.parse(&s, &dir, &bad),
        Err(ParseError::BadValue {
            field: "force_mismatch",
            ..
        })
    ));
    // A batch's runs are refused one by one.
    let runs = KratosPaper
        .batch()
        .unwrap()
        .parse_batch(&[s.clone(), s], &dir, &foreign);
    assert_eq!(runs.len(), 2);
    assert!(
        runs.iter()
            .all(|r| matches!(r, Err(ParseError::ForeignForce { .. })))
    );
}

/// Symplectic Euler and velocity Verlet step the paper's law through the same positions: the
/// leap-frog force of step n sees `(y_n, v_n)` with `v_n = (y_n − y_{n−1})/Δt`, velocity
/// Verlet's sees `(y_n, v_{n−1/2})`, the same pair, and both start from a zero force at touch;
/// so the COR is the same to rounding, whatever the start phase, and velocity Verlet's bound
/// ([`paper_cor_step_error`]) is Kratos' too (measured: within 1e-13 at every phase, n = 1 and
/// 1.5, η up to 0.95).
#[test]
fn symplectic_euler_realises_velocity_verlets_cor() {
    for scene in SCENES {
        for eta in [0.0, 0.35, 0.7, 0.95] {
            let s = setup(scene, eta);
            let law = KratosPaper.law(&s);
            let CodeLaw::Paper(paper) = law else {
                unreachable!()
            };
            let v0 = s.impact_velocity;
            let e = exact::restitution(eta);
            let mut worst = 0.0f64;
            for k in 0..16 {
                let gap = f64::from(k) / 16.0 * v0 * s.timestep;
                let cor = |scheme| {
                    let t = step_trajectory_from(&law, v0, s.timestep, s.steps + 2, scheme, gap);
                    trajectory_metrics(&t).unwrap().cor
                };
                let leap_frog = cor(StepScheme::LeapFrog);
                let verlet = cor(StepScheme::VelocityVerlet);
                assert!(
                    (leap_frog - verlet).abs() < 1e-13,
                    "{scene} η={eta} phase {k}: {leap_frog} vs {verlet}"
                );
                worst = worst.max((leap_frog - e).abs());
            }
            let bound = paper_cor_step_error(&paper, v0, s.timestep);
            assert!(worst <= bound, "{scene} η={eta}: {worst:e} > {bound:e}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Live runs of the installed Kratos.

/// Kratos, or a failure naming how to install it.
fn require_kratos() {
    if let Err(e) = KratosPaper.locate() {
        panic!(
            "Kratos is not installed ({e}): this live test needs the Kratos venv in .codes/kratos \
             (bash scripts/install-dem-codes.sh); it fails rather than skips without it"
        );
    }
}

fn run(setup: &CodeSetup) -> TrajectoryMetrics {
    let run = run_code(&KratosPaper, setup, &RunOptions::default())
        .unwrap_or_else(|e| panic!("kratos-paper on {}: {e}", setup.case_name));
    assert_eq!(run.code_version, "10.4.4");
    trajectory_metrics(&run.trajectory).unwrap()
}

/// Each run and the harness's stepping of the law (leap-frog, from touch) agree to 1e-12 in
/// COR (and peak overlap, contact time, peak force, relative) for the three scenes, η from 0 to
/// 0.95 at the default step and at 200 and 4000 steps per contact; and the realised COR lies
/// in the band the law stepped over 32 start phases spans, no point of which is further from
/// the closed form than [`predicted_cor_error`].
#[test]
#[ignore = "live: runs Kratos DEM (bash scripts/test.sh)"]
fn live_runs_equal_the_stepping_and_keep_to_the_step_band() {
    require_kratos();
    let mut settings: Vec<(&str, f64, Option<u32>)> = Vec::new();
    for scene in SCENES {
        settings.extend(ETAS.iter().map(|&eta| (scene, eta, None)));
        settings.extend([(scene, 0.35, Some(200)), (scene, 0.7, Some(4000))]);
    }
    for (scene, eta, spc) in settings {
        let s = setup_at(scene, eta, spc);
        let code = run(&s);
        let label = format!("{scene} η={eta} {spc:?}");
        assert_run_is_the_law_stepped(&KratosPaper, &s, &code, &label);
        assert_cor_within_the_step_band(&KratosPaper, &s, eta, code.cor, &label);
    }
}

/// Each impact of a batch is its single run to the bit (its own bodies, far from the others').
#[test]
#[ignore = "live: runs Kratos DEM (bash scripts/test.sh)"]
fn live_batch_trajectories_equal_single_runs_bit_for_bit() {
    require_kratos();
    for scene in SCENES {
        let setups: Vec<CodeSetup> = [0.0, 0.35, 0.95].map(|eta| setup(scene, eta)).to_vec();
        let batch = run_batch(&KratosPaper, &setups, &RunOptions::default()).unwrap();
        assert_eq!(batch.runs.len(), setups.len());
        for (s, from_batch) in setups.iter().zip(batch.runs) {
            let from_batch = from_batch.unwrap().trajectory;
            let alone = run_code(&KratosPaper, s, &RunOptions::default())
                .unwrap()
                .trajectory;
            let bits = |c: &[f64]| c.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&from_batch.overlap), bits(&alone.overlap), "{scene}");
            assert_eq!(
                bits(&from_batch.approach_velocity),
                bits(&alone.approach_velocity),
                "{scene}"
            );
            assert_eq!(
                bits(&from_batch.normal_force),
                bits(&alone.normal_force),
                "{scene}"
            );
        }
    }
}

/// `reference --code kratos-paper CASE --steps-per-contact 2000 --format json` on cases none
/// of the stored runs use (a glass ball on a rigid plate at 0.7 m/s, η = 0.55; a 30 mm steel
/// ball on a 12 mm one at 3.1 m/s, η = 0.8): COR, peak overlap and peak force within 5e-4 of
/// the closed form and within 1e-9 of the harness's prediction; no model difference.
#[test]
#[ignore = "live: runs Kratos DEM (bash scripts/test.sh)"]
fn live_reference_on_held_out_cases() {
    require_kratos();
    let dir = tempfile::TempDir::new().unwrap();
    let cases = [
        (
            "glass_on_rigid",
            "scene = \"ball_plate\"\nimpact_velocity = 0.7\nloss_coefficient = 0.55\n\n[ball]\nradius = 0.0125\ndensity = 2500.0\nyoungs_modulus = 6.3e10\npoisson_ratio = 0.22\n\n[plate]\nrigid = true\n",
        ),
        (
            "steel_unequal",
            "scene = \"ball_ball\"\nimpact_velocity = 3.1\nloss_coefficient = 0.8\n\n[ball]\nradius = 0.015\ndensity = 7800.0\nyoungs_modulus = 2.1e11\npoisson_ratio = 0.29\n\n[other_ball]\nradius = 0.006\n",
        ),
    ];
    for (name, text) in cases {
        let path = common::write(dir.path(), &format!("{name}.toml"), text);
        let out = millimpact()
            .args(["reference", "--code", "kratos-paper"])
            .arg(&path)
            .args(["--steps-per-contact", "2000", "--format", "json"])
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}: {out:?}");
        let r: millimpact::ReferenceRecord = serde_json::from_slice(&out.stdout).unwrap();
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        for (what, run, predicted, exact) in [
            ("COR", r.figures.cor, r.law_at_step.cor, r.paper_exact.cor),
            (
                "peak overlap",
                r.figures.peak_deformation,
                r.law_at_step.peak_deformation,
                r.paper_exact.peak_deformation,
            ),
            (
                "peak force",
                r.figures.peak_force,
                r.law_at_step.peak_force,
                r.paper_exact.peak_force,
            ),
        ] {
            assert!(
                rel(run, exact) <= 5e-4,
                "{name}: {what} {run:e} vs {exact:e}"
            );
            assert!(
                rel(run, predicted) <= 1e-9,
                "{name}: {what} {run:e} vs predicted {predicted:e}"
            );
        }
        assert!(
            rel(r.figures.cor, r.paper_exact.cor) > 0.0,
            "{name}: a real step error"
        );
        assert_eq!(r.attribution().model.cor.to_bits(), 0f64.to_bits());
    }
}

/// The build run under gravity: the driver's script with `GRAVITY` set, parsed by the driver.
struct UnderGravity(f64);

impl CodeDriver for UnderGravity {
    fn name(&self) -> &'static str {
        KratosPaper.name()
    }
    fn binary(&self) -> &'static str {
        KratosPaper.binary()
    }
    fn locate(&self) -> Result<millimpact::codes::Executable, LocateError> {
        KratosPaper.locate()
    }
    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        render_script(std::slice::from_ref(setup), self.0).map_err(|e| CodeError::Unsupported {
            code: self.name().into(),
            case: setup.case_name.clone(),
            reason: e.to_string(),
        })
    }
    fn parse(&self, setup: &CodeSetup, dir: &Path, log: &str) -> Result<ParsedRun, ParseError> {
        KratosPaper.parse(setup, dir, log)
    }
    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        KratosPaper.law(setup)
    }
}

/// A 10 mm steel ball dropped onto a steel plate from touch at 0.05 m/s under gravity, η = 0.3
/// and 0.6, Δt = 1 µs: it bounces, settles, and then carries its weight step after step: over
/// the last 2000 of 60000 steps every force is m g to 1e-9 (the plain sign would alternate by
/// about ±η of the weight), and no stock force was added (the run would be refused).
#[test]
#[ignore = "live: runs Kratos DEM (bash scripts/test.sh)"]
fn live_a_ball_at_rest_carries_its_weight_without_alternating() {
    require_kratos();
    let g = 9.81;
    for eta in [0.3, 0.6] {
        let mut case = shipped("ball_plate").with_loss_coefficient(eta);
        case.impact_velocity = 0.05;
        let mut s = prepare_with(&KratosPaper, &case, None, Some(1e-6), false, None).unwrap();
        s.sphere.radius = 0.005;
        s.sphere.mass = 4.0 / 3.0 * std::f64::consts::PI * 0.005f64.powi(3) * s.sphere.density;
        s.steps = 60_000;
        let run = run_code(&UnderGravity(g), &s, &RunOptions::default())
            .unwrap_or_else(|e| panic!("η={eta}: {e}"));
        let weight = particle_mass(0.005, s.sphere.density) * g;
        let forces = &run.trajectory.normal_force;
        assert_eq!(forces.len(), 60_001);
        // It did bounce: the force was off (in flight) after it was on.
        let first_on = forces.iter().position(|&f| f > 0.0).unwrap();
        assert!(
            forces[first_on..].iter().any(|&f| f <= 0.0),
            "η={eta}: no bounce"
        );
        let tail = &forces[forces.len() - 2000..];
        for (k, f) in tail.iter().enumerate() {
            assert!(
                ((f - weight) / weight).abs() < 1e-9,
                "η={eta}: step {k} of the tail carries {f} N against m g = {weight} N"
            );
        }
    }
}

/// The lines the book gives a Kratos user (docs/src/paper-law-in-dem.md, "In Kratos DEM"),
/// run through the stage's own `RunSolutionLoop` on the driver's ball_plate model at η = 0.35,
/// rebound at the driver's COR to the last bit.
#[test]
#[ignore = "live: runs Kratos DEM (bash scripts/test.sh)"]
fn live_the_books_lines_realise_the_drivers_cor() {
    require_kratos();
    let book = std::fs::read_to_string(root().join("docs/src/paper-law-in-dem.md")).unwrap();
    let opening = "```python\nimport KratosMultiphysics as KM\n";
    let at = book.find(opening).expect("the book's Kratos lines") + "```python\n".len();
    let lines = &book[at..at + book[at..].find("```").unwrap()];
    let s = setup("ball_plate", 0.35);
    let rendered = KratosPaper.render(&s).unwrap().text;
    // The driver's model (PaperBatch builds the bodies, no wall, no stock law), the book's stage
    // on it, and Kratos' own loop.
    let model = &rendered[..rendered.find("if SCHEME not in SCHEMES:").unwrap()];
    let CodeLaw::Paper(law) = KratosPaper.law(&s) else {
        unreachable!()
    };
    let script = format!(
        "{model}\n{}\nC = {:e}\nETA = {:e}\nstage = PaperLawStage(KM.Model(), stage_parameters(SCHEME, DT, STEPS))\nstage.Initialize()\nstage.RunSolutionLoop()\nprint(\"BOOK cor=%r\" % (stage.spheres_model_part.GetNode(1).GetSolutionStepValue(KM.VELOCITY_Z) / {:e}))\n",
        lines.replace(
            "class PaperLawStage(DEMAnalysisStage):",
            "class PaperLawStage(PaperBatch):"
        ),
        law.stiffness,
        law.loss_coefficient,
        s.impact_velocity,
    );
    let dir = tempfile::TempDir::new().unwrap();
    std::fs::write(dir.path().join("book.py"), script).unwrap();
    let out = KratosPaper
        .locate()
        .unwrap()
        .command()
        .arg("book.py")
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let cor: f64 = stdout
        .lines()
        .find_map(|l| l.strip_prefix("BOOK cor="))
        .unwrap_or_else(|| panic!("{stdout}"))
        .parse()
        .unwrap();
    let driver = run_code(&KratosPaper, &s, &RunOptions::default()).unwrap();
    let realised = trajectory_metrics(&driver.trajectory).unwrap().cor;
    assert_eq!(cor.to_bits(), realised.to_bits(), "{cor} vs {realised}");
}
