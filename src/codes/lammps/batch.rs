//! LAMMPS batches: several independent sphere-on-wall impacts in one process. Each sphere is
//! its own group with its own `fix wall/gran` (its own contact model and damping), the spheres
//! sit far apart along x so that nothing couples them (there is no pair style at all), and
//! each writes its own trajectory with its own `fix print`. The deck per sphere is the single
//! run's, so each impact steps through the same arithmetic as when it runs alone; the run
//! lasts the longest impact's steps and each trajectory is cut at its own.

use std::path::Path;

use crate::codes::lammps::{Build, LOG_FILE, parse_loop_time, parse_trajectory, parse_version};
use crate::codes::parse::ParseError;
use crate::codes::template::exact_number;
use crate::codes::{BatchError, BatchRunner, CodeSetup, ParsedRun, RenderedInput};

/// Most impacts in one batch: LAMMPS allows 32 groups, `all` among them, and each sphere
/// needs its own group for its own wall.
pub const MAX_BATCH: usize = 31;

/// The batch input file.
pub const BATCH_INPUT_FILE: &str = "batch.in";

/// The trajectory file of impact `i` (from 0) of a batch.
pub fn batch_trajectory_file(i: usize) -> String {
    format!("trajectory-{}.txt", i + 1)
}

/// Why `setups` cannot run as one LAMMPS batch, if they cannot.
pub fn batch_refusal(setups: &[CodeSetup]) -> Option<BatchError> {
    let Some(first) = setups.first() else {
        return Some(BatchError::Empty);
    };
    if setups.len() > MAX_BATCH {
        return Some(BatchError::TooMany {
            count: setups.len(),
            most: MAX_BATCH,
            why: "LAMMPS allows 32 groups",
        });
    }
    if let Some(s) = setups.iter().find(|s| s.other_sphere.is_some()) {
        return Some(BatchError::Scene {
            case: s.case_name.clone(),
            scene: s.scene.name(),
            holds: "a LAMMPS batch holds sphere-on-wall impacts",
        });
    }
    if setups
        .iter()
        .any(|s| s.timestep.to_bits() != first.timestep.to_bits())
    {
        return Some(BatchError::Differ { what: "time step" });
    }
    if setups
        .iter()
        .any(|s| s.clamp_attractive != first.clamp_attractive)
    {
        return Some(BatchError::Differ {
            what: "limit_damping",
        });
    }
    None
}

/// The batch input for `setups` in `build`.
pub fn render_batch(build: &Build, setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
    if let Some(reason) = batch_refusal(setups) {
        return Err(reason);
    }
    let first = &setups[0];
    if first.steps == 0 || first.timestep.is_nan() || first.timestep <= 0.0 {
        return Err(BatchError::NoSteps);
    }
    let largest = setups
        .iter()
        .map(|s| s.sphere.radius)
        .fold(0.0f64, f64::max);
    let spacing = 8.0 * largest;
    let steps = setups.iter().map(|s| s.steps).max().unwrap_or(0);
    let limit = if first.clamp_attractive {
        " limit_damping"
    } else {
        ""
    };
    let mut text = String::from(
        "# millimpact: independent sphere-on-wall impacts in one LAMMPS run (src/codes/lammps_batch.rs).\n\
         units           si\natom_style      sphere\natom_modify     map array\ndimension       3\nboundary        f f f\n",
    );
    text += &format!(
        "region          box block {} {} {} {} {} {} units box\ncreate_box      1 box\n",
        exact_number(-4.0 * largest),
        exact_number(spacing * setups.len() as f64),
        exact_number(-4.0 * largest),
        exact_number(4.0 * largest),
        exact_number(-4.0 * largest),
        exact_number(8.0 * largest),
    );
    for (i, s) in setups.iter().enumerate() {
        let plan = build.plan(s)?;
        let id = i + 1;
        let r = s.sphere.radius;
        let (v1, _) = s.centre_of_mass_velocities();
        text += &format!(
            "create_atoms    1 single {} 0 {} units box\nset             atom {id} diameter {}\nset             atom {id} mass {}\nset             atom {id} vz {}\ngroup           g{id} id {id}\nfix             wall{id} g{id} wall/gran granular {} tangential linear_nohistory 0 0{limit} zplane 0 NULL\n",
            exact_number(spacing * i as f64),
            exact_number(r + build.start_gap(s)),
            exact_number(2.0 * r),
            exact_number(s.sphere.mass),
            exact_number(-v1),
            plan.model_args,
        );
    }
    text += &format!(
        "fix             integrate all nve/sphere\ntimestep        {}\nvariable        t equal time\n",
        exact_number(first.timestep)
    );
    for (i, s) in setups.iter().enumerate() {
        let id = i + 1;
        text += &format!(
            "variable        overlap{id} equal ({})-z[{id}]\nvariable        approach{id} equal -vz[{id}]\nvariable        force{id} equal fz[{id}]\nfix             print{id} all print 1 \"${{t}} ${{overlap{id}}} ${{approach{id}}} ${{force{id}}}\" file {} screen no title \"# time overlap approach_velocity normal_force\"\n",
            exact_number(s.sphere.radius),
            batch_trajectory_file(i),
        );
    }
    text += &format!("thermo_style    custom step\nthermo          0\nrun             {steps}\n");
    Ok(RenderedInput {
        file_name: BATCH_INPUT_FILE.into(),
        text,
        args: [
            "-in",
            BATCH_INPUT_FILE,
            "-log",
            LOG_FILE,
            "-nocite",
            "-echo",
            "none",
        ]
        .map(String::from)
        .to_vec(),
    })
}

/// Each impact's run from a batch: its own trajectory, cut after its own steps.
pub fn parse_batch(
    setups: &[CodeSetup],
    workdir: &Path,
    log: &str,
) -> Vec<Result<ParsedRun, ParseError>> {
    let file_log = std::fs::read_to_string(workdir.join(LOG_FILE)).unwrap_or_default();
    let version = parse_version(log).or_else(|| parse_version(&file_log));
    let loop_time = parse_loop_time(log)
        .or_else(|| parse_loop_time(&file_log))
        .map(|t| t / setups.len() as f64);
    setups
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let path = workdir.join(batch_trajectory_file(i));
            let text = std::fs::read_to_string(&path)
                .map_err(|source| ParseError::Read { path, source })?;
            let mut trajectory = parse_trajectory(&text)?;
            // The rows of this impact's own run length: times up to steps · Δt.
            let end = (s.steps as f64 + 0.5) * s.timestep;
            let keep = trajectory.time.iter().take_while(|&&t| t <= end).count();
            trajectory.time.truncate(keep);
            trajectory.overlap.truncate(keep);
            trajectory.approach_velocity.truncate(keep);
            trajectory
                .normal_force
                .truncate(keep.min(trajectory.normal_force.len()));
            Ok(ParsedRun {
                trajectory,
                loop_time,
                version: version.clone(),
            })
        })
        .collect()
}

/// A LAMMPS build's batches: many sphere-on-wall impacts in one run, one group each.
pub struct LammpsBatch(pub &'static Build);

impl BatchRunner for LammpsBatch {
    fn max_batch(&self) -> usize {
        MAX_BATCH
    }

    fn render_batch(&self, setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
        render_batch(self.0, setups)
    }

    fn parse_batch(
        &self,
        setups: &[CodeSetup],
        workdir: &Path,
        log: &str,
    ) -> Vec<Result<ParsedRun, ParseError>> {
        parse_batch(setups, workdir, log)
    }
}

