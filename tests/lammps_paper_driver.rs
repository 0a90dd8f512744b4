//! LAMMPS 2025 with the paper's law as a plugin (`lammps-paper`, built by
//! scripts/build-lammps-paper.sh): its decks, its law and what it refuses, and a recorded run
//! read back (no binary needed); live runs of the build: the run against the harness's own
//! stepping of the law and the realised COR within the step band of the closed form (three
//! scenes, η from 0 to 0.95, three steps), `reference` on a held-out case, the plugin's own
//! errors, newton_pair on and off, and a poured bed in one and two processes.
//!
//! The live tests FAIL (not skip) when the build is not installed.

use std::path::{Path, PathBuf};

use millimpact::codes::lammps::paper::{LammpsPaper, plugin_stiffness};
use millimpact::codes::lammps::paper_plugin_modulus as plugin_modulus;
use millimpact::codes::{
    CodeDriver, CodeError, CodeSetup, LocateError, ParseError, ParsedRun, RenderedInput,
    RunOptions, prepare_with, run_code,
};
use millimpact::model::exact;
use millimpact::model::law::{CodeLaw, PaperLaw};
use millimpact::model::trajectory::{TrajectoryMetrics, trajectory_metrics};
use millimpact::solve::dashpot::{StepScheme, step_trajectory_from};

mod common;

use common::paper_build::{
    ETAS, SCENES, assert_cor_within_the_step_band, assert_refuses_eta_outside_its_range,
    assert_run_is_the_law_stepped, run_lammps_paper, stepped,
};
use common::{millimpact, root, shipped};

/// The setup of a shipped case at η and `steps_per_contact` (the default 1000 when `None`),
/// as `reference` makes it.
fn setup_at(scene: &str, eta: f64, steps_per_contact: Option<u32>) -> CodeSetup {
    let case = shipped(scene).with_loss_coefficient(eta);
    prepare_with(&LammpsPaper, &case, steps_per_contact, None, false, None).unwrap()
}

fn setup(scene: &str, eta: f64) -> CodeSetup {
    setup_at(scene, eta, None)
}

// ---------------------------------------------------------------------------------------------
// The decks, the law, the refusals, a recorded run (no binary needed).

/// Each deck loads the plugin and selects the paper's law with the case's η itself and the
/// bodies' own materials: a wall with the plate's E and ν (the rod's `kn` on its wall), two
/// balls with a pair_coeff for each pair of types and ghost velocities.
#[test]
fn the_decks_load_the_plugin_and_select_the_papers_law() {
    for scene in SCENES {
        let text = LammpsPaper.render(&setup(scene, 0.35)).unwrap().text;
        assert!(
            text.lines()
                .any(|l| l == "plugin          load paperplugin.so"),
            "{scene}: {text}"
        );
        assert!(!text.contains("{{"), "{scene}: a placeholder left");
        assert!(
            !text.contains("granular"),
            "{scene}: a stock granular style"
        );
    }
    let plate = LammpsPaper.render(&setup("ball_plate", 0.35)).unwrap().text;
    assert!(
        plate.contains(
            "fix             wall all wall/paper hertz 3.5e-1 2e11 3e-1 2e11 3e-1 zplane 0 NULL"
        ),
        "{plate}"
    );
    let rod = setup("rod_end", 0.35);
    let rod_text = LammpsPaper.render(&rod).unwrap().text;
    assert!(
        rod_text.contains(&format!(
            "wall/paper linear 3.5e-1 {:e} zplane",
            rod.stiffness
        )),
        "{rod_text}"
    );
    let balls = LammpsPaper.render(&setup("ball_ball", 0.35)).unwrap().text;
    for line in [
        "comm_modify     vel yes",
        "pair_style      paper",
        "pair_coeff      1 1 3.5e-1 2e11 3e-1",
        "pair_coeff      2 2 3.5e-1 2e11 3e-1",
        "pair_coeff      1 2 3.5e-1 2e11 3e-1 2e11 3e-1",
    ] {
        assert!(balls.lines().any(|l| l == line), "{line}: {balls}");
    }
}

/// The law is the paper's with the plugin's own numbers: the case's η exactly, the reduced
/// mass, and a stiffness within rounding of the case's `(4/3) E* sqrt(R*)`.
#[test]
fn its_law_is_the_papers_law_with_the_plugins_stiffness() {
    for scene in SCENES {
        for eta in ETAS {
            let s = setup(scene, eta);
            let CodeLaw::Paper(PaperLaw {
                mass,
                stiffness,
                exponent,
                loss_coefficient,
            }) = LammpsPaper.law(&s)
            else {
                panic!("{scene}: not the paper's law")
            };
            assert_eq!(loss_coefficient.to_bits(), eta.to_bits(), "{scene} η {eta}");
            assert_eq!(exponent.to_bits(), s.exponent.to_bits());
            assert_eq!(mass.to_bits(), s.pair_mass().to_bits());
            assert_eq!(stiffness.to_bits(), plugin_stiffness(&s).to_bits());
            assert!(
                ((stiffness - s.stiffness) / s.stiffness).abs() < 1e-15,
                "{scene}: {stiffness:e} vs the case's {:e}",
                s.stiffness
            );
        }
    }
    // A rigid plate is the stand-in E = 1e30: below the rounding of the ball's own compliance.
    let steel: f64 = 2e11 / (1.0 - 0.09);
    assert_eq!(
        plugin_modulus(2e11, 0.3, 1e30, 0.0).to_bits(),
        steel.to_bits()
    );
}

/// η outside [0, 1) and a clamp are refused before a run (the plugin stops on the first too;
/// a clamp has nothing to cut).
#[test]
fn the_driver_refuses_eta_out_of_range_and_a_clamp() {
    assert_refuses_eta_outside_its_range(&LammpsPaper, &setup("ball_plate", 0.35));
    let clamped = CodeSetup {
        clamp_attractive: true,
        ..setup("ball_ball", 0.35)
    };
    assert!(matches!(
        LammpsPaper.render(&clamped),
        Err(CodeError::Unsupported { .. })
    ));
    assert!(LammpsPaper.clamp_refusal().is_some());
}

/// Without the plugin in the codes' folder the run stops naming the file it looked for, the
/// script that installs it and the variable that names another build.
#[test]
fn a_missing_plugin_names_where_it_was_looked_for() {
    let dir = tempfile::TempDir::new().unwrap();
    let out = millimpact()
        .env_remove("MILLIMPACT_LAMMPS_PAPER_BINARY")
        .env("MILLIMPACT_CODES_DIR", dir.path())
        .args([
            "reference",
            "--code",
            "lammps-paper",
            "cases/ball_plate.toml",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("lammps-paper/lib/paperplugin.so")
            && stderr.contains("scripts/install-dem-codes.sh")
            && stderr.contains("MILLIMPACT_LAMMPS_PAPER_BINARY"),
        "{stderr}"
    );
}

/// The recorded run: ball_plate at η = 0.35 and 50 steps per contact, run by the build
/// (`tests/data/lammps-paper/ball_plate/`, made by `live_the_recorded_run_is_current`).
fn recorded() -> (CodeSetup, PathBuf) {
    (
        setup_at("ball_plate", 0.35, Some(50)),
        root().join("tests/data/lammps-paper/ball_plate"),
    )
}

/// The recorded run is read back whole (version, loop time, every row), its input is what the
/// driver renders now, and it is the harness's stepping of the plugin's law to rounding.
#[test]
fn a_recorded_run_is_read_and_is_the_law_stepped() {
    let (s, dir) = recorded();
    let log = std::fs::read_to_string(dir.join("screen.txt")).unwrap();
    let run = LammpsPaper.parse(&s, &dir, &log).unwrap();
    assert_eq!(run.version.as_deref(), Some("22 Jul 2025 - Update 4"));
    assert!(run.loop_time.is_some_and(|t| t > 0.0));
    assert_eq!(run.trajectory.time.len() as u64, s.steps + 1);
    let input = std::fs::read_to_string(dir.join("impact.in")).unwrap();
    assert_eq!(input, LammpsPaper.render(&s).unwrap().text);
    let code = trajectory_metrics(&run.trajectory).unwrap();
    let law = stepped(&LammpsPaper, &s, 0.0);
    assert!(
        (code.cor - law.cor).abs() < 1e-12,
        "{} vs {}",
        code.cor,
        law.cor
    );
    assert!((code.peak_deformation - law.peak_deformation).abs() / law.peak_deformation < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Live runs of the build.

/// The build, or a failure naming how to make it.
fn require_build() {
    if let Err(e) = LammpsPaper.locate() {
        panic!(
            "lammps-paper is not installed ({e}): this live test needs the LAMMPS 2025 venv and \
             its paper plugin (bash scripts/install-dem-codes.sh, which runs \
             scripts/build-lammps-paper.sh); it fails rather than skips without it"
        );
    }
}

fn run(setup: &CodeSetup) -> TrajectoryMetrics {
    let run = run_code(&LammpsPaper, setup, &RunOptions::default())
        .unwrap_or_else(|e| panic!("lammps-paper on {}: {e}", setup.case_name));
    assert_eq!(run.code_version, "22 Jul 2025 - Update 4");
    trajectory_metrics(&run.trajectory).unwrap()
}

/// At 250, 1000 and 4000 steps per elastic contact time, for the three scenes and η in
/// [0, 0.95]: the run is the harness's stepping of the plugin's law to 1e-12 (COR, peak
/// overlap, contact time, peak force), and its COR lies in the band the law stepped over 32
/// start phases spans, no point of which is further from `sqrt((1−η)/(1+η))` than
/// [`paper_cor_step_error`] predicts.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_runs_are_the_law_stepped_and_within_the_step_band() {
    require_build();
    for steps in [250, 1000, 4000] {
        for scene in SCENES {
            for eta in ETAS {
                let s = setup_at(scene, eta, Some(steps));
                let code = run(&s);
                let label = format!("{scene} η={eta} {steps}");
                assert_run_is_the_law_stepped(&LammpsPaper, &s, &code, &label);
                assert_cor_within_the_step_band(&LammpsPaper, &s, eta, code.cor, &label);
            }
        }
    }
}

/// `reference --code lammps-paper` on a case none of the stored runs covers (a 30 mm glass
/// ball on a granite plate at 3.7 m/s, η = 0.42) at 2000 steps per contact: the realised COR
/// within 5e-4 of the closed form, within 1e-9 of the harness's prediction, no model
/// difference.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_reference_on_a_held_out_case() {
    require_build();
    let dir = tempfile::TempDir::new().unwrap();
    let case = dir.path().join("glass_on_granite.toml");
    std::fs::write(
        &case,
        "scene = \"ball_plate\"\nimpact_velocity = 3.7\nloss_coefficient = 0.42\n\n\
         [ball]\nradius = 0.015\ndensity = 2500.0\nyoungs_modulus = 6.3e10\npoisson_ratio = 0.24\n\n\
         [plate]\nrigid = false\nyoungs_modulus = 5.0e10\npoisson_ratio = 0.25\n",
    )
    .unwrap();
    let out = millimpact()
        .args(["reference", "--code", "lammps-paper"])
        .arg(&case)
        .args(["--steps-per-contact", "2000", "--format", "json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let r: millimpact::ReferenceRecord = serde_json::from_slice(&out.stdout).unwrap();
    let e = exact::restitution(0.42);
    let realised = r.figures.cor;
    assert!((realised - e).abs() < 5e-4, "{realised} vs {e}");
    let a = r.attribution();
    assert!(a.remainder.cor.abs() < 1e-9, "{a:?}");
    assert_eq!(a.model.cor.to_bits(), 0f64.to_bits());
    assert_eq!(r.setup.loss_coefficient, Some(0.42));
}

/// A driver that runs the plugin's deck edited as a user's own deck could be.
struct Edited {
    edit: fn(String) -> String,
}

impl CodeDriver for Edited {
    fn name(&self) -> &'static str {
        LammpsPaper.name()
    }
    fn binary(&self) -> &'static str {
        LammpsPaper.binary()
    }
    fn locate(&self) -> Result<millimpact::codes::Executable, LocateError> {
        LammpsPaper.locate()
    }
    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        let mut input = LammpsPaper.render(setup)?;
        input.text = (self.edit)(input.text);
        Ok(input)
    }
    fn parse(&self, setup: &CodeSetup, dir: &Path, log: &str) -> Result<ParsedRun, ParseError> {
        LammpsPaper.parse(setup, dir, log)
    }
    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        LammpsPaper.law(setup)
    }
}

/// A refused deck: the scene, the edit of its deck, and the start of LAMMPS's ERROR line.
type Refusal = (&'static str, fn(String) -> String, &'static str);

/// The plugin's refusals stop LAMMPS with its own ERROR line (not a crash), which the harness
/// passes on and keeps in the log: η out of range (pair and wall), a pair of types without a
/// pair_coeff, and no ghost velocities.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_the_plugins_errors_are_lammps_errors() {
    require_build();
    let cases: [Refusal; 5] = [
        (
            "ball_ball",
            |t| t.replace("pair_coeff      1 2 3.5e-1", "pair_coeff      1 2 1.2"),
            "ERROR: pair paper: 0 <= eta < 1 required, got eta = 1.2",
        ),
        (
            "ball_plate",
            |t| t.replace("wall/paper hertz 3.5e-1", "wall/paper hertz -0.1"),
            "ERROR: fix wall/paper: 0 <= eta < 1 required, got eta = -0.1",
        ),
        (
            "rod_end",
            |t| t.replace("wall/paper linear 3.5e-1", "wall/paper linear 1"),
            "ERROR: fix wall/paper: 0 <= eta < 1 required, got eta = 1",
        ),
        (
            "ball_ball",
            |t| {
                t.lines()
                    .filter(|l| !l.starts_with("pair_coeff      1 2"))
                    .collect::<Vec<_>>()
                    .join("\n")
            },
            "ERROR: pair paper: no pair_coeff for atom types 1 2",
        ),
        (
            "ball_ball",
            |t| t.replace("comm_modify     vel yes", "comm_modify     vel no"),
            "ERROR: pair paper requires ghost velocities: use comm_modify vel yes",
        ),
    ];
    for (scene, edit, wanted) in cases {
        let s = setup(scene, 0.35);
        let err = run_code(&Edited { edit }, &s, &RunOptions::default())
            .expect_err("the plugin refuses it");
        let CodeError::Crashed {
            said, log, status, ..
        } = &err
        else {
            panic!("{scene}: {err}")
        };
        let said = said
            .as_deref()
            .unwrap_or_else(|| panic!("no ERROR line: {err}"));
        assert!(said.starts_with(wanted), "{scene}: {said}");
        assert!(status.contains("exit status: 1"), "{scene}: {status}");
        let text = std::fs::read_to_string(log).unwrap();
        assert!(text.contains(said), "{}", log.display());
        std::fs::remove_dir_all(log.parent().unwrap()).unwrap();
    }
}

/// Two balls with newton_pair off (each pair's force applied from both sides' lists, as on
/// many processes) give the trajectory of newton_pair on to the last bit.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_newton_pair_on_and_off_give_the_same_run() {
    require_build();
    for eta in [0.0, 0.35, 0.9] {
        let s = setup("ball_ball", eta);
        let on = run_code(&LammpsPaper, &s, &RunOptions::default()).unwrap();
        let off = run_code(
            &Edited {
                edit: |t| t.replace("newton          on", "newton          off"),
            },
            &s,
            &RunOptions::default(),
        )
        .unwrap();
        assert!(off.input.contains("newton          off"));
        assert_eq!(on.trajectory, off.trajectory, "η {eta}");
    }
}

/// What one run of `tests/data/lammps-paper/in.bed` printed.
struct Bed {
    kinetic_start: f64,
    kinetic_end: f64,
    largest_pair_force: f64,
    free_cor: f64,
}

/// Run the bed deck with `newton` in `processes` MPI processes (the venv's MPICH `mpiexec`).
fn run_bed(newton: &str, processes: u32) -> Bed {
    let dir = tempfile::TempDir::new().unwrap();
    let deck = root().join("tests/data/lammps-paper/in.bed");
    let text = run_lammps_paper(deck.to_str().unwrap(), dir.path(), newton, processes, "bed");
    let numbers = |prefix: &str| -> Vec<f64> {
        let line = text
            .lines()
            .find(|l| l.starts_with(prefix))
            .unwrap_or_else(|| panic!("no `{prefix}` line: {text}"));
        line[prefix.len()..]
            .split_whitespace()
            .map(|w| w.parse().unwrap())
            .collect()
    };
    let kinetic = numbers("KE ");
    let cor = numbers("COR free ");
    // The deck's own closed form, printed to 15 digits.
    assert!(
        (cor[1] - exact::restitution(0.5)).abs() < 1e-14,
        "{}",
        cor[1]
    );
    Bed {
        kinetic_start: kinetic[0],
        kinetic_end: kinetic[1],
        largest_pair_force: numbers("FMAX ")[0],
        free_cor: cor[0],
    }
}

/// A bed of 250 spheres poured into a box of wall/paper planes under gravity runs without an
/// error in one and two processes, newton_pair on and off: it loses 99 % of its kinetic energy
/// from 0.05 s to 0.45 s, `compute pair/local` reads its contact forces (through the pair
/// style's `single()`), and the free pair above it meets within the step band of its own law
/// (it gains no energy: COR below 1), the same in every run.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_a_poured_bed_settles_and_a_free_pair_inside_its_run_keeps_the_law() {
    require_build();
    // The free pair: r = 5 mm, ρ = 1000, E = 1e8, ν = 0.3, η = 0.5, 1 m/s, Δt = 2e-5 s.
    let mass = 4.0 * std::f64::consts::PI / 3.0 * 0.005f64.powi(3) * 1000.0;
    let law = CodeLaw::Paper(PaperLaw {
        mass: mass * mass / (mass + mass),
        stiffness: 4.0 / 3.0
            * plugin_modulus(1e8, 0.3, 1e8, 0.3)
            * (0.005f64 * 0.005 / 0.01).sqrt(),
        exponent: 1.5,
        loss_coefficient: 0.5,
    });
    let (lo, hi) = (0..32)
        .map(|k| {
            let gap = f64::from(k) / 32.0 * 1.0 * 2e-5;
            let t = step_trajectory_from(&law, 1.0, 2e-5, 200, StepScheme::VelocityVerlet, gap);
            trajectory_metrics(&t).unwrap().cor
        })
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c), hi.max(c))
        });
    let mut cors = Vec::new();
    for (newton, processes) in [("on", 1), ("off", 1), ("on", 2), ("off", 2)] {
        let bed = run_bed(newton, processes);
        assert!(
            bed.kinetic_end < 1e-2 * bed.kinetic_start,
            "newton {newton}, {processes} processes: {} J of {} J left",
            bed.kinetic_end,
            bed.kinetic_start
        );
        // compute pair/local reads the forces through the pair style's single(): some contact
        // carries more than a sphere's weight, none the whole bed's.
        let weight = mass * 9.81;
        assert!(
            bed.largest_pair_force > weight && bed.largest_pair_force < 250.0 * weight,
            "newton {newton}, {processes}: largest pair force {} N (a sphere weighs {weight} N)",
            bed.largest_pair_force
        );
        assert!(bed.free_cor < 1.0);
        assert!(
            bed.free_cor >= lo - 1e-9 && bed.free_cor <= hi + 1e-9,
            "newton {newton}, {processes}: free pair's COR {} outside its step band [{lo}, {hi}]",
            bed.free_cor
        );
        cors.push(bed.free_cor);
    }
    assert!(
        cors.iter().all(|c| c.to_bits() == cors[0].to_bits()),
        "{cors:?}"
    );
}

/// The recorded run of the fast tier is what the build writes now, byte for byte (rerun with
/// `UPDATE_RECORDING=1` to record it again, then review the diff): the rendered deck, LAMMPS's
/// own trajectory file, and the screen output's lines the parser reads (the rest holds timings
/// that change from run to run).
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_the_recorded_run_is_current() {
    require_build();
    let (s, recorded) = recorded();
    let input = LammpsPaper.render(&s).unwrap();
    let scratch = tempfile::TempDir::new().unwrap();
    std::fs::write(scratch.path().join(&input.file_name), &input.text).unwrap();
    let out = LammpsPaper
        .locate()
        .unwrap()
        .command()
        .args(&input.args)
        .current_dir(scratch.path())
        .env("TMPDIR", scratch.path())
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    let screen: String = stdout
        .lines()
        .filter(|l| l.starts_with("LAMMPS (") || l.starts_with("Loop time of "))
        .map(|l| format!("{l}\n"))
        .collect();
    let trajectory = std::fs::read_to_string(scratch.path().join("trajectory.txt")).unwrap();
    if std::env::var_os("UPDATE_RECORDING").is_some() {
        std::fs::create_dir_all(&recorded).unwrap();
        std::fs::write(recorded.join("impact.in"), &input.text).unwrap();
        std::fs::write(recorded.join("trajectory.txt"), &trajectory).unwrap();
        std::fs::write(recorded.join("screen.txt"), &screen).unwrap();
    } else {
        let read = |name: &str| std::fs::read_to_string(recorded.join(name)).unwrap();
        assert_eq!(read("impact.in"), input.text);
        assert_eq!(read("trajectory.txt"), trajectory);
        let version = |text: &str| text.lines().next().map(str::to_string);
        assert_eq!(version(&read("screen.txt")), version(&screen));
    }
}
