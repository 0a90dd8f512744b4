//! Batches against single runs, live: for every code and scene, a batch of 40 impacts (four η,
//! each ten times, interleaved: more than one YADE group, a Kratos wall scaled up) gives, impact
//! by impact, the trajectory of the single run of its η to the last bit (every row: time,
//! overlap, approach speed, force), with the single run's row count and a loop time of its own.
//! Without a code these tests fail; they do not skip.

use millimpact::codes::batch::{run_batch, run_batch_with};
use millimpact::codes::{CodeName, CodeSetup, Executable, RunOptions, prepare, run_code};
use millimpact::model::case::Case;
use millimpact::model::trajectory::CodeTrajectory;

mod common;

/// The η of a batch: elastic, light to heavy damping (the run lengths differ).
const ETAS: [f64; 4] = [0.0, 0.2, 0.5, 0.85];

/// How many times a batch holds each η.
const COPIES: usize = 10;

fn setups(code: CodeName, scene: &str) -> Vec<CodeSetup> {
    ETAS.iter()
        .map(|&eta| {
            let case = Case::load(&common::case_path(scene))
                .unwrap()
                .with_loss_coefficient(eta);
            prepare(code.driver(), &case, Some(200), None, false)
                .unwrap_or_else(|e| panic!("{code} {scene}: {e:#}"))
        })
        .collect()
}

fn bits(t: &CodeTrajectory) -> Vec<[u64; 4]> {
    (0..t.time.len())
        .map(|i| {
            [
                t.time[i].to_bits(),
                t.overlap[i].to_bits(),
                t.approach_velocity[i].to_bits(),
                t.normal_force[i].to_bits(),
            ]
        })
        .collect()
}

fn batch_equals_single_runs(code: CodeName, scene: &str) {
    let driver = code.driver();
    let setups = setups(code, scene);
    let options = RunOptions::default();
    let singles: Vec<_> = setups
        .iter()
        .zip(ETAS)
        .map(|(setup, eta)| {
            run_code(driver, setup, &options)
                .unwrap_or_else(|e| panic!("{code} {scene} η {eta}: the single run failed: {e}"))
        })
        .collect();
    let many: Vec<CodeSetup> = (0..COPIES).flat_map(|_| setups.clone()).collect();
    let batch = run_batch(driver, &many, &options)
        .unwrap_or_else(|e| panic!("{code} {scene}: the batch failed: {e}"));
    assert_eq!(batch.runs.len(), many.len());
    assert!(
        batch.kept.is_none(),
        "{code} {scene}: kept {:?}",
        batch.kept
    );
    for (k, batched) in batch.runs.into_iter().enumerate() {
        let (single, eta) = (&singles[k % ETAS.len()], ETAS[k % ETAS.len()]);
        let batched = batched.unwrap_or_else(|e| panic!("{code} {scene} impact {k}: {e}"));
        assert_eq!(
            batched.trajectory.time.len(),
            single.trajectory.time.len(),
            "{code} {scene} impact {k} (η {eta}): rows"
        );
        let (b, s) = (bits(&batched.trajectory), bits(&single.trajectory));
        if let Some(row) = (0..s.len()).find(|&i| b[i] != s[i]) {
            panic!(
                "{code} {scene} impact {k} (η {eta}): row {row} of {} differs: batch {:?}, single {:?}",
                s.len(),
                b[row].map(f64::from_bits),
                s[row].map(f64::from_bits)
            );
        }
        assert_eq!(
            batched.version.as_deref(),
            Some(single.code_version.as_str())
        );
        assert!(
            batched
                .loop_time
                .is_some_and(|t| t > 0.0 && t < batch.wall_time),
            "{code} {scene} impact {k}: loop time {:?} in a batch of {} s",
            batched.loop_time,
            batch.wall_time
        );
    }
}

macro_rules! batch_tests {
    ($($name:ident: $code:expr, $scene:literal, $why:literal;)+) => {
        $(
            #[test]
            #[ignore = $why]
            fn $name() {
                batch_equals_single_runs($code, $scene);
            }
        )+
    };
}

batch_tests! {
    liggghts_ball_plate: CodeName::Liggghts, "ball_plate", "live: runs LIGGGHTS (bash scripts/test.sh)";
    liggghts_ball_ball: CodeName::Liggghts, "ball_ball", "live: runs LIGGGHTS (bash scripts/test.sh)";
    liggghts_rod_end: CodeName::Liggghts, "rod_end", "live: runs LIGGGHTS (bash scripts/test.sh)";
    yade_ball_plate: CodeName::Yade, "ball_plate", "live: runs YADE (bash scripts/test.sh)";
    yade_ball_ball: CodeName::Yade, "ball_ball", "live: runs YADE (bash scripts/test.sh)";
    yade_rod_end: CodeName::Yade, "rod_end", "live: runs YADE (bash scripts/test.sh)";
    lammps_ball_plate: CodeName::Lammps, "ball_plate", "live: runs LAMMPS (bash scripts/test.sh)";
    lammps_ball_ball: CodeName::Lammps, "ball_ball", "live: runs LAMMPS (bash scripts/test.sh)";
    lammps_rod_end: CodeName::Lammps, "rod_end", "live: runs LAMMPS (bash scripts/test.sh)";
    lammps_2025_ball_plate: CodeName::Lammps2025, "ball_plate", "live: runs LAMMPS 2025 (bash scripts/test.sh)";
    lammps_2025_ball_ball: CodeName::Lammps2025, "ball_ball", "live: runs LAMMPS 2025 (bash scripts/test.sh)";
    lammps_2025_rod_end: CodeName::Lammps2025, "rod_end", "live: runs LAMMPS 2025 (bash scripts/test.sh)";
    kratos_ball_plate: CodeName::Kratos, "ball_plate", "live: runs Kratos (bash scripts/test.sh)";
    kratos_ball_ball: CodeName::Kratos, "ball_ball", "live: runs Kratos (bash scripts/test.sh)";
    kratos_rod_end: CodeName::Kratos, "rod_end", "live: runs Kratos (bash scripts/test.sh)";
    liggghts_paper_ball_plate: CodeName::LiggghtsPaper, "ball_plate", "live: runs LIGGGHTS with the paper's law (bash scripts/test.sh)";
    liggghts_paper_ball_ball: CodeName::LiggghtsPaper, "ball_ball", "live: runs LIGGGHTS with the paper's law (bash scripts/test.sh)";
    liggghts_paper_rod_end: CodeName::LiggghtsPaper, "rod_end", "live: runs LIGGGHTS with the paper's law (bash scripts/test.sh)";
    yade_paper_ball_plate: CodeName::YadePaper, "ball_plate", "live: runs YADE with the paper's law (bash scripts/test.sh)";
    yade_paper_ball_ball: CodeName::YadePaper, "ball_ball", "live: runs YADE with the paper's law (bash scripts/test.sh)";
    yade_paper_rod_end: CodeName::YadePaper, "rod_end", "live: runs YADE with the paper's law (bash scripts/test.sh)";
    lammps_paper_ball_plate: CodeName::LammpsPaper, "ball_plate", "live: runs LAMMPS 2025 with the paper's law plugin (bash scripts/test.sh)";
    lammps_paper_ball_ball: CodeName::LammpsPaper, "ball_ball", "live: runs LAMMPS 2025 with the paper's law plugin (bash scripts/test.sh)";
    lammps_paper_rod_end: CodeName::LammpsPaper, "rod_end", "live: runs LAMMPS 2025 with the paper's law plugin (bash scripts/test.sh)";
    kratos_paper_ball_plate: CodeName::KratosPaper, "ball_plate", "live: runs Kratos with the paper's law (bash scripts/test.sh)";
    kratos_paper_ball_ball: CodeName::KratosPaper, "ball_ball", "live: runs Kratos with the paper's law (bash scripts/test.sh)";
    kratos_paper_rod_end: CodeName::KratosPaper, "rod_end", "live: runs Kratos with the paper's law (bash scripts/test.sh)";
}

/// YADE's batches run by the launcher's Python (its library, without the launcher's shell);
/// through a launcher that is not YADE's Python script, a wrapper, by that launcher itself:
/// the same bits either way.
#[test]
#[ignore = "live: runs YADE (bash scripts/test.sh)"]
fn yade_batches_by_its_python_equal_those_by_a_wrapper_of_its_launcher() {
    let driver = CodeName::Yade.driver();
    let located = driver.locate().expect("YADE is installed");
    let runner = driver.batch().unwrap();
    let setups = setups(CodeName::Yade, "ball_ball");
    let input = runner.render_batch(&setups).unwrap();
    let light = runner.launch(located.clone(), &input);
    assert_ne!(light.executable.program, located.program, "{light:?}");
    let dir = tempfile::tempdir().unwrap();
    let wrapper = dir.path().join("yade-wrapper");
    std::fs::write(
        &wrapper,
        format!("#!/bin/sh\nexec '{}' \"$@\"\n", located.program.display()),
    )
    .unwrap();
    std::fs::set_permissions(
        &wrapper,
        std::os::unix::fs::PermissionsExt::from_mode(0o755),
    )
    .unwrap();
    let wrapped = Executable::plain(wrapper);
    assert_eq!(runner.launch(wrapped.clone(), &input).executable, wrapped);
    let options = RunOptions::default();
    let by_python = run_batch(driver, &setups, &options).unwrap();
    let by_wrapper = run_batch_with(driver, Ok(wrapped), &setups, &options).unwrap();
    for (k, (a, b)) in by_python.runs.iter().zip(&by_wrapper.runs).enumerate() {
        let (a, b) = (a.as_ref().unwrap(), b.as_ref().unwrap());
        assert_eq!(bits(&a.trajectory), bits(&b.trajectory), "impact {k}");
        assert_eq!(a.version, b.version);
    }
}
