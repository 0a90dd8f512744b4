//! What the live tests of every build of the paper's law share: the scenes and η they sweep,
//! the law stepped as the build steps it, and the two checks of a run against that stepping
//! (the run is the law stepped; its COR lies in the band the law stepped over 32 start phases
//! spans, within the step error predicted for velocity Verlet).

use millimpact::codes::{CodeDriver, CodeError, CodeSetup};
use millimpact::model::exact;
use millimpact::model::law::CodeLaw;
use millimpact::model::trajectory::{TrajectoryMetrics, trajectory_metrics};
use millimpact::solve::dashpot::paper_cor_step_error;

/// The three shipped scenes.
pub const SCENES: [&str; 3] = ["ball_plate", "ball_ball", "rod_end"];

/// η over [0, 0.95]: elastic, the paper's 0.35, and up to a COR of 0.16.
pub const ETAS: [f64; 6] = [0.0, 0.2, 0.35, 0.5, 0.7, 0.95];

/// How many start phases within one step the band spans.
const PHASES: u32 = 32;

/// The build's law stepped as the build steps it for `setup`, started `phase` of a step before
/// the setup's own start (0: the run's start, in the build's coordinates).
pub fn stepped(build: &impl CodeDriver, setup: &CodeSetup, phase: f64) -> TrajectoryMetrics {
    let law = build.law(setup);
    let (dt, v0) = (setup.timestep, setup.impact_velocity);
    let trajectory =
        build
            .stepping(setup)
            .trajectory(&law, v0, dt, setup.steps + 2, phase * v0 * dt);
    trajectory_metrics(&trajectory).unwrap()
}

/// The COR error velocity Verlet can make on the build's law at `setup`'s step
/// ([`paper_cor_step_error`]).
pub fn predicted_cor_error(build: &impl CodeDriver, setup: &CodeSetup) -> f64 {
    let CodeLaw::Paper(law) = build.law(setup) else {
        unreachable!("{}'s law is the paper's", build.name())
    };
    paper_cor_step_error(&law, setup.impact_velocity, setup.timestep)
}

/// The relative difference |a − b| / |b|.
fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Assert that `run` is the build's law stepped from the run's own start, to 1e-12 relative in
/// COR, peak overlap, contact time and peak force; `label` names the run in a failure.
pub fn assert_run_is_the_law_stepped(
    build: &impl CodeDriver,
    setup: &CodeSetup,
    run: &TrajectoryMetrics,
    label: &str,
) {
    let law = stepped(build, setup, 0.0);
    for (what, a, b) in [
        ("COR", run.cor, law.cor),
        ("peak overlap", run.peak_deformation, law.peak_deformation),
        ("contact time", run.contact_time, law.contact_time),
        ("peak force", run.peak_force, law.peak_force),
    ] {
        assert!(
            relative(a, b) <= 1e-12,
            "{label}: {what} {a:e} (run) vs {b:e} (stepped), {:.2e}",
            relative(a, b)
        );
    }
}

/// Assert that the realised `cor` of a run at η = `eta` lies (to 1e-12) in the band of offsets
/// from `sqrt((1−η)/(1+η))` that the law stepped over 32 start phases spans, and that no point
/// of that band is further from the closed form than [`predicted_cor_error`].
pub fn assert_cor_within_the_step_band(
    build: &impl CodeDriver,
    setup: &CodeSetup,
    eta: f64,
    cor: f64,
    label: &str,
) {
    let e = exact::restitution(eta);
    let offset = cor - e;
    let phases: Vec<f64> = (0..PHASES)
        .map(|k| stepped(build, setup, f64::from(k) / f64::from(PHASES)).cor - e)
        .collect();
    let lo = phases.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = phases.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!(
        offset >= lo - 1e-12 && offset <= hi + 1e-12,
        "{label}: COR offset {offset:e} outside the predicted [{lo:e}, {hi:e}]"
    );
    let bound = predicted_cor_error(build, setup);
    assert!(
        lo.abs().max(hi.abs()) <= bound,
        "{label}: band [{lo:e}, {hi:e}] beyond the predicted {bound:e}"
    );
}

/// Assert that the build refuses to render `good` with η of 1, above 1, below 0 or NaN, as
/// unsupported, naming the range `0 <= eta < 1`.
pub fn assert_refuses_eta_outside_its_range(build: &impl CodeDriver, good: &CodeSetup) {
    for eta in [1.0, 1.2, -0.1, f64::NAN] {
        let bad = CodeSetup {
            loss_coefficient: Some(eta),
            ..good.clone()
        };
        let err = build.render(&bad).unwrap_err();
        assert!(
            matches!(&err, CodeError::Unsupported { reason, .. } if reason.contains("0 <= eta < 1")),
            "{} η={eta}: {err}",
            build.name()
        );
    }
}

/// Run `reference --code CODE cases/ball_plate.toml --clamp` and assert it is bad input: exit
/// 2, nothing on stdout, one line on stderr naming the build; that line.
pub fn clamp_refused_in_one_line(code: &str) -> String {
    let out = super::millimpact()
        .args([
            "reference",
            "--code",
            code,
            "cases/ball_plate.toml",
            "--clamp",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    assert!(out.stdout.is_empty());
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains(code), "{stderr}");
    stderr
}

/// Run the plugin build's LAMMPS on `input` (a path, or a file in `dir`) in `dir` with
/// `-var newton NEWTON`, in `processes` MPI processes (one: the build's own executable; more: the
/// venv's MPICH `mpiexec` beside it), and return its standard output; a failed run fails the test,
/// naming `what`.
pub fn run_lammps_paper(
    input: &str,
    dir: &std::path::Path,
    newton: &str,
    processes: u32,
    what: &str,
) -> String {
    use millimpact::codes::lammps::paper::LammpsPaper;
    let executable = LammpsPaper.locate().unwrap();
    let mut command = if processes == 1 {
        executable.command()
    } else {
        // bin/mpiexec beside the venv's lib/python3.X/site-packages/lammps/lmp.
        let venv = executable.program.ancestors().nth(5).unwrap();
        let mut c = std::process::Command::new(venv.join("bin/mpiexec"));
        c.envs(executable.env.iter().map(|(k, v)| (k, v)))
            .args(["-n", &processes.to_string()])
            .arg(&executable.program);
        c
    };
    let out = command
        .args([
            "-in", input, "-var", "newton", newton, "-log", "none", "-echo", "none", "-nocite",
        ])
        .current_dir(dir)
        .env("TMPDIR", dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{what}, newton {newton}, {processes} processes: {}{text}",
        String::from_utf8_lossy(&out.stderr)
    );
    text
}
