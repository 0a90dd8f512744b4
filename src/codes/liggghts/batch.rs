//! LIGGGHTS batches: several independent sphere-on-plate impacts in one process. Sphere `i` is
//! atom type `i`, the plate is the last type, and a per-type-pair property
//! (`coefficientRestitution` for the stock `hertz`, `lossCoefficient` for the paper build's
//! `paper`) gives each sphere its own damping against the plate; the spheres sit far apart along x so
//! that they never touch, and each writes its own trajectory. Every value is the single run's,
//! so each impact steps through the same arithmetic as when it runs alone; the run lasts the
//! longest impact's steps and each trajectory is cut at its own.

use std::path::Path;

use crate::codes::liggghts::{
    Liggghts, RIGID_WALL_MODULUS, RIGID_WALL_POISSON, contact_gap, parse_output, version,
};
use crate::codes::parse::ParseError;
use crate::codes::template::exact_number;
use crate::codes::{BatchError, BatchRunner, CodeDriver, CodeSetup, ParsedRun, RenderedInput};
use crate::model::scene::SceneKind;

/// Most impacts in one batch (the per-type-pair tables grow as its square).
pub const MAX_BATCH: usize = 64;

/// The batch input file.
pub const BATCH_INPUT_FILE: &str = "batch.in";

/// The trajectory file of impact `i` (from 0) of a batch.
pub fn batch_trajectory_file(i: usize) -> String {
    format!("traj-{}.txt", i + 1)
}

fn plate(setup: &CodeSetup) -> (f64, f64) {
    setup
        .plate_material
        .unwrap_or((RIGID_WALL_MODULUS, RIGID_WALL_POISSON))
}

/// The contact model of a batch: what differs between the stock build's batch and the paper
/// build's.
pub struct BatchModel {
    /// The driver whose single runs the batch's impacts are (each is checked by its render).
    pub driver: &'static dyn CodeDriver,
    /// The style after `model`.
    pub style: &'static str,
    /// Its settings keywords for a batch like `setup` (empty for a style that takes none).
    pub settings: fn(&CodeSetup) -> String,
    /// The per-type-pair property that carries each impact's damping.
    pub property: &'static str,
    /// Its value for one impact.
    pub value: fn(&CodeSetup) -> f64,
}

/// The stock build's batch: damped `hertz`, `coefficientRestitution` per impact.
pub const HERTZ: BatchModel = BatchModel {
    driver: &Liggghts,
    style: "hertz",
    settings: |s| {
        let limit_force = if s.clamp_attractive { "on" } else { "off" };
        format!("tangential_damping off limitForce {limit_force}")
    },
    property: "coefficientRestitution",
    value: |s| s.target_restitution,
};

/// The stock build's batch input for `setups`, or why they cannot run as one.
pub fn render_batch(setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
    render_batch_with(&HERTZ, setups)
}

/// The batch input for `setups` under `model`, or why they cannot run as one.
pub fn render_batch_with(
    model: &BatchModel,
    setups: &[CodeSetup],
) -> Result<RenderedInput, BatchError> {
    let Some(first) = setups.first() else {
        return Err(BatchError::Empty);
    };
    if setups.len() > MAX_BATCH {
        return Err(BatchError::TooMany {
            count: setups.len(),
            most: MAX_BATCH,
            why: "the batch input's size",
        });
    }
    for s in setups {
        model.driver.render(s)?;
        if s.scene != SceneKind::BallPlate {
            return Err(BatchError::Scene {
                case: s.case_name.clone(),
                scene: s.scene.name(),
                holds: "LIGGGHTS batches hold ball_plate impacts",
            });
        }
        if plate(s) != plate(first) {
            return Err(BatchError::Differ {
                what: "plate (one wall type per batch)",
            });
        }
        if s.timestep.to_bits() != first.timestep.to_bits()
            || s.clamp_attractive != first.clamp_attractive
        {
            return Err(BatchError::Differ {
                what: "time step or limitForce",
            });
        }
    }
    let n = setups.len();
    let wall = n + 1;
    let steps = setups.iter().map(|s| s.steps).max().unwrap_or(0);
    let reach = setups
        .iter()
        .map(|s| s.sphere.radius)
        .fold(0.0f64, f64::max);
    let half = setups
        .iter()
        .map(|s| 4.0 * s.sphere.radius + s.impact_velocity * s.duration() + contact_gap(s))
        .fold(0.0f64, f64::max);
    let spacing = 2.0 * half;
    // A style without settings leaves no trailing blank on its lines.
    let settings = match (model.settings)(first) {
        words if words.is_empty() => words,
        words => format!(" {words}"),
    };
    let style = model.style;
    let property = model.property;
    let (e_wall, nu_wall) = plate(first);
    let list = |values: Vec<String>| values.join(" ");
    let mut young: Vec<String> = setups
        .iter()
        .map(|s| exact_number(s.sphere.youngs_modulus))
        .collect();
    young.push(exact_number(e_wall));
    let mut poisson: Vec<String> = setups
        .iter()
        .map(|s| exact_number(s.sphere.poisson_ratio.unwrap_or_default()))
        .collect();
    poisson.push(exact_number(nu_wall));
    // Type pair (i, wall) and (wall, i) carry sphere i's damping; pairs of spheres, which
    // never meet, the first's.
    let mut damping = Vec::with_capacity(wall * wall);
    for i in 0..wall {
        for j in 0..wall {
            let k = match (i == n, j == n) {
                (true, false) => j,
                (false, true) => i,
                _ => 0,
            };
            damping.push(exact_number((model.value)(&setups[k])));
        }
    }
    let h = exact_number(half);
    let mut text = format!(
        "# millimpact: independent sphere-on-plate impacts in one LIGGGHTS run (src/codes/liggghts/batch.rs).\n\
units           si\natom_style      granular\natom_modify     map array\nboundary        f f f\nnewton          off\n\
communicate     single vel yes\nhard_particles  yes\n\
region          domain block -{h} {} -{h} {h} -{h} {h} units box\ncreate_box      {wall} domain\n\
neighbor        {} bin\nneigh_modify    delay 0\n\
fix youngsModulus          all property/global youngsModulus peratomtype {}\n\
fix poissonsRatio          all property/global poissonsRatio peratomtype {}\n\
fix {property:<22} all property/global {property} peratomtypepair {wall} {}\n\
fix coefficientFriction    all property/global coefficientFriction peratomtypepair {wall} {}\n\
pair_style      gran model {style} tangential no_history{settings}\npair_coeff      * *\n\
fix             plate all wall/gran model {style} tangential no_history primitive type {wall} zplane 0.0{settings}\n\
timestep        {}\n",
        exact_number(spacing * n as f64),
        exact_number(reach),
        list(young),
        list(poisson),
        list(damping),
        list(vec!["0".to_string(); wall * wall]),
        exact_number(first.timestep),
    );
    for (i, s) in setups.iter().enumerate() {
        let id = i + 1;
        let r = s.sphere.radius;
        let (v1, _) = s.centre_of_mass_velocities();
        text += &format!(
            "create_atoms    {id} single {} 0 {} units box\nset             atom {id} diameter {} density {} vz {}\n",
            exact_number(spacing * i as f64),
            exact_number(r + contact_gap(s)),
            exact_number(2.0 * r),
            exact_number(s.sphere.density),
            exact_number(-v1)
        );
    }
    text += "fix             integrate all nve/sphere\nvariable        t equal time\n";
    for (i, s) in setups.iter().enumerate() {
        let id = i + 1;
        let file = batch_trajectory_file(i);
        text += &format!(
            "variable        overlap{id} equal {}-z[{id}]\nvariable        approach{id} equal -vz[{id}]\nvariable        force{id} equal fz[{id}]\n\
print           \"${{t}} ${{overlap{id}}} ${{approach{id}}} ${{force{id}}}\" file {file} screen no\n\
fix             trajectory{id} all print 1 \"${{t}} ${{overlap{id}}} ${{approach{id}}} ${{force{id}}}\" append {file} screen no title none\n",
            exact_number(s.sphere.radius),
        );
    }
    text += &format!("thermo          {steps}\nrun             {steps}\n");
    Ok(RenderedInput {
        file_name: BATCH_INPUT_FILE.into(),
        text,
        args: ["-in", BATCH_INPUT_FILE, "-log", "none", "-echo", "none"]
            .map(String::from)
            .to_vec(),
    })
}

/// Each impact's run from a batch: its own trajectory, cut after its own steps (the single
/// run's `steps + 1` rows).
pub fn parse_batch(
    setups: &[CodeSetup],
    workdir: &Path,
    log: &str,
) -> Vec<Result<ParsedRun, ParseError>> {
    let code_version = version(log);
    setups
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let path = workdir.join(batch_trajectory_file(i));
            let text = std::fs::read_to_string(&path)
                .map_err(|source| ParseError::Read { path, source })?;
            let mut run = parse_output(&text, log)?;
            let keep = usize::try_from(s.steps)
                .map_or(usize::MAX, |n| n.saturating_add(1))
                .min(run.trajectory.time.len());
            let t = &mut run.trajectory;
            t.time.truncate(keep);
            t.overlap.truncate(keep);
            t.approach_velocity.truncate(keep);
            t.normal_force.truncate(keep.min(t.normal_force.len()));
            run.loop_time = run.loop_time.map(|x| x / setups.len() as f64);
            run.version = code_version.clone();
            Ok(run)
        })
        .collect()
}

/// Liggghts's batches: many sphere-on-plate impacts in one run.
pub struct LiggghtsBatch;

impl BatchRunner for LiggghtsBatch {
    fn max_batch(&self) -> usize {
        MAX_BATCH
    }

    fn render_batch(&self, setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
        render_batch(setups)
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

