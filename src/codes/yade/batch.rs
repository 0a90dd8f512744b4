//! YADE batches: several independent sphere-on-plate impacts in one process. Each sphere has
//! its own material, the plate one more, and `Ip2_FrictMat_FrictMat_MindlinPhys` takes each
//! sphere's restitution against the plate from a `MatchMaker` keyed by the two materials; the
//! spheres sit far apart along x. Each impact records the rows its single run records (its
//! own iterations, then its state after them), so it steps through the same arithmetic.

use std::path::Path;

use crate::codes::parse::ParseError;
use crate::codes::template::exact_number;
use crate::codes::yade::{RIGID_WALL_MODULUS, Yade, hertz_input_restitution, parse_trajectory};
use crate::codes::{BatchError, BatchRunner, CodeDriver, CodeSetup, ParsedRun, RenderedInput};
use crate::model::scene::SceneKind;

/// Most impacts in one batch.
pub const MAX_BATCH: usize = 64;

/// The batch script.
pub const BATCH_SCRIPT: &str = "batch.py";

/// The trajectory file of impact `i` (from 0) of a batch.
pub fn batch_trajectory_file(i: usize) -> String {
    format!("trajectory-{}.csv", i + 1)
}

fn plate(setup: &CodeSetup) -> (f64, f64) {
    setup.plate_material.unwrap_or((RIGID_WALL_MODULUS, 0.0))
}

const SCRIPT: &str = r#"
print("MILLIMPACT version=" + str(yade.config.version))
n = len(IMPACTS)
mats = []
for (steps, r, m, rho, e, nu, v, en) in IMPACTS:
    mats.append(O.materials.append(FrictMat(young=e, poisson=nu, frictionAngle=0.0, density=rho)))
wall_mat = O.materials.append(FrictMat(young=WALL_E, poisson=WALL_NU, frictionAngle=0.0, density=IMPACTS[0][3]))
bodies = []
for i, (steps, r, m, rho, e, nu, v, en) in enumerate(IMPACTS):
    b = O.bodies.append(utils.sphere((SPACING * i, 0.0, math.nextafter(-r, -math.inf)), r, material=mats[i]))
    O.bodies[b].state.mass = m
    O.bodies[b].state.vel = Vector3(0.0, 0.0, v)
    O.bodies[b].state.blockedDOFs = "XYZ"
    bodies.append(b)
wall = O.bodies.append(utils.wall(0.0, axis=2, sense=0, material=wall_mat))
rows = [[] for _ in IMPACTS]


def state(i):
    r = IMPACTS[i][1]
    s = O.bodies[bodies[i]].state
    return r - (0.0 - s.pos[2]), s.vel[2]


def record():
    k = O.iter
    for i in range(n):
        steps = IMPACTS[i][0]
        if k < steps:
            overlap, speed = state(i)
            force = -O.forces.f(bodies[i], sync=True)[2]
            rows[i].append((k, O.time, overlap, speed, force))
        elif k == steps:
            overlap, speed = state(i)
            if overlap <= 0.0:
                rows[i].append((k, O.time, overlap, speed, 0.0))


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(hertzian=True)],
        [Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=[(mats[i], wall_mat, IMPACTS[i][7]) for i in range(n)]))],
        [Law2_ScGeom_MindlinPhys_Mindlin()],
    ),
    PyRunner(iterPeriod=1, initRun=True, command="record()"),
    NewtonIntegrator(damping=0.0, gravity=(0.0, 0.0, 0.0)),
]
O.dt = DT
STEPS = max(i[0] for i in IMPACTS)
start = time.perf_counter()
for _ in range(STEPS):
    O.step()
loop_time = time.perf_counter() - start
for i in range(n):
    if IMPACTS[i][0] == STEPS:
        overlap, speed = state(i)
        if overlap <= 0.0:
            rows[i].append((O.iter, O.time, overlap, speed, 0.0))
    with open("trajectory-%d.csv" % (i + 1), "w") as out:
        out.write("iter,time,overlap,approach_velocity,normal_force\n")
        for row in rows[i]:
            out.write("%d,%r,%r,%r,%r\n" % row)
print("MILLIMPACT loop_time=%r" % loop_time)
"#;

/// The batch script for `setups`, or why they cannot run as one.
pub fn render_batch(setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
    let Some(first) = setups.first() else {
        return Err(BatchError::Empty);
    };
    if setups.len() > MAX_BATCH {
        return Err(BatchError::TooMany {
            count: setups.len(),
            most: MAX_BATCH,
            why: "the batch script's size",
        });
    }
    let num = exact_number;
    let mut impacts = String::new();
    for s in setups {
        Yade.render(s)?;
        if s.scene != SceneKind::BallPlate {
            return Err(BatchError::Scene {
                case: s.case_name.clone(),
                scene: s.scene.name(),
                holds: "YADE batches hold ball_plate impacts",
            });
        }
        if plate(s) != plate(first) || s.timestep.to_bits() != first.timestep.to_bits() {
            return Err(BatchError::Differ {
                what: "plate or time step",
            });
        }
        let (v1, _) = s.centre_of_mass_velocities();
        let en = hertz_input_restitution(s.target_restitution).unwrap_or(s.target_restitution);
        impacts += &format!(
            "    ({}, {}, {}, {}, {}, {}, {}, {}),\n",
            s.steps,
            num(s.sphere.radius),
            num(s.sphere.mass),
            num(s.sphere.density),
            num(s.sphere.youngs_modulus),
            num(s.sphere.poisson_ratio.unwrap_or(0.0)),
            num(v1),
            num(en)
        );
    }
    let largest = setups
        .iter()
        .map(|s| s.sphere.radius)
        .fold(0.0f64, f64::max);
    let (wall_e, wall_nu) = plate(first);
    let text = format!(
        "# millimpact: independent sphere-on-plate impacts in one YADE run (src/codes/yade/batch.rs).\nimport math\nimport time\n\nimport yade\nfrom yade import utils\n\nDT = {}\nSPACING = {}\nWALL_E = {}\nWALL_NU = {}\n# (steps, radius, mass, density, E, nu, velocity, en)\nIMPACTS = [\n{impacts}]\n{SCRIPT}",
        num(first.timestep),
        num(8.0 * largest),
        num(wall_e),
        num(wall_nu),
    );
    Ok(RenderedInput {
        file_name: BATCH_SCRIPT.into(),
        text,
        args: ["-j1", "-n", "-x", BATCH_SCRIPT].map(String::from).to_vec(),
    })
}

/// Each impact's run from a batch.
pub fn parse_batch(
    setups: &[CodeSetup],
    workdir: &Path,
    log: &str,
) -> Vec<Result<ParsedRun, ParseError>> {
    let field = |key: &str| {
        log.lines()
            .filter_map(|l| l.trim().strip_prefix("MILLIMPACT "))
            .flat_map(|rest| rest.split_whitespace())
            .find_map(|f| f.strip_prefix(key).map(str::to_string))
    };
    let version = field("version=");
    let loop_time = field("loop_time=")
        .and_then(|v| v.parse::<f64>().ok())
        .map(|t| t / setups.len() as f64);
    (0..setups.len())
        .map(|i| {
            let path = workdir.join(batch_trajectory_file(i));
            let text = std::fs::read_to_string(&path)
                .map_err(|source| ParseError::Read { path, source })?;
            Ok(ParsedRun {
                trajectory: parse_trajectory(&text)?,
                loop_time,
                version: version.clone(),
            })
        })
        .collect()
}

/// Yade's batches: many sphere-on-plate impacts in one run.
pub struct YadeBatch;

impl BatchRunner for YadeBatch {
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

