# millimpact: 1 impacts under the paper's law in Kratos DEM (src/codes/kratos/paper.rs).
# Each impact's values.
IMPACTS = [
    {"scene": "ball_plate", "timestep": 1.2238641617728902e-7, "steps": 60, "radius": 2e-2, "density": 7.8e3, "young": 2e11, "poisson": 3e-1, "velocity": 2e0, "other_radius": 0e0, "other_density": 0e0, "other_young": 0e0, "other_poisson": 0e0, "other_velocity": 0e0, "stiffness": 2.0721077836968426e10, "exponent": 1.5e0, "loss_coefficient": 3.5e-1, "scheme": "Symplectic_Euler"},
]
SPACING = 8e-2
GRAVITY = 0e0
# millimpact: normal impacts under the paper's law F = C y^n (1 + eta sign ydot) in Kratos DEM
# (KratosMultiphysics and KratosDEMApplication 10.4.4), rendered by the kratos-paper driver
# (src/codes/kratos/paper.rs). Kratos' laws are compiled C++ (the wheel has no headers), so the
# law is applied through Kratos' own hook: SphericParticle::ComputeAdditionalForces adds each
# node's EXTERNAL_APPLIED_FORCE to the forces it integrates. Before every SolveSolutionStep the
# script reads each body's position and velocity (the state the step's forces see), computes
# the paper's force with paper_force below and sets it on the nodes. A validation build: one
# Python call per step.
#
# No stock contact law acts: there are no wall conditions (the plate is the plane z = 0 of
# the hook), and the two balls of an impact meet under DEM_D_Linear_Custom_Constants with
# K_NORMAL = K_TANGENTIAL = 0 and no damping, which gives no force. Each step checks this: the
# node's TOTAL_FORCES after the step must be the applied force plus the weight to the rounding
# of that sum (two ulps); the largest excess is printed as force_mismatch, 0.0 when none.
#
# Many impacts run side by side in one stage (one process start); a single run is a batch of
# one. Writes trajectory-K.csv per impact K (from 1): header iter,time,overlap,
# approach_velocity,normal_force; row s the state before step s (what the hook read) and the
# force the hook set from it; the last row the state after the last step with the force the
# next step would get. Prints MILLIMPACT lines that the driver parses.
#
# Above this script: IMPACTS (each impact's values), SPACING, GRAVITY (m/s^2, downwards).
# ---- The part every millimpact Kratos script shares (src/codes/kratos/common.py, written into
# ---- each script by the renderer, so that the script runs on its own in its scratch folder).
# What it sets up, and why (each measured on 10.4.4, see the driver's notes):
# - a DEMAnalysisStage subclass that builds its model in ReadModelParts (no mdpa or materials
#   file): the properties first (with the integration scheme and properties proxies: without
#   either, CreateSphericParticle segfaults), then the spheres (creator_destructor
#   .CreateSphericParticle) and, for a plate, a wall of two RigidFace3D3N triangles;
# - NeighbourSearchFrequency 1 (default 50: the wall contact is found only at step 48);
# - one OpenMP thread (default two: a one-sphere loop 5-10x slower on this machine);
# - no gravity, no friction, no rotation, no global damping, no output files;
# - its own step loop (the stage's costs ~0.65 ms a step, ~90 % of it in Python).
import os

# One thread: Kratos' default of two OpenMP threads makes a one-sphere loop 5-10x slower. This
# must be set before Kratos (and its OpenMP runtime) loads; the driver sets it too.
os.environ["OMP_NUM_THREADS"] = "1"

import math
import time
from importlib.metadata import version

import KratosMultiphysics as KM
import KratosMultiphysics.DEMApplication as DEM
from KratosMultiphysics.DEMApplication.DEM_analysis_stage import DEMAnalysisStage

KM.Logger.GetDefaultOutput().SetSeverity(KM.Logger.Severity.WARNING)
KM.ParallelUtilities.SetNumThreads(1)

PARAMETERS = """
{
    "problem_name"                   : "impact",
    "do_print_results_option"        : false,
    "post_gid_option"                : false,
    "post_vtk_option"                : false,
    "Dimension"                      : 3,
    "BoundingBoxOption"              : false,
    "dem_inlet_option"               : false,
    "GravityX"                       : 0.0,
    "GravityY"                       : 0.0,
    "GravityZ"                       : 0.0,
    "RotationOption"                 : false,
    "CleanIndentationsOption"        : false,
    "EnergyCalculationOption"        : false,
    "GlobalDamping"                  : 0.0,
    "VirtualMassCoefficient"         : 1.0,
    "DeltaOption"                    : "Absolute",
    "SearchTolerance"                : 0.0,
    "search_tolerance_against_walls" : 0.0,
    "NeighbourSearchFrequency"       : 1,
    "TranslationalIntegrationScheme" : "SCHEME_NAME",
    "RotationalIntegrationScheme"    : "Direct_Integration",
    "AutomaticTimestep"              : false,
    "MaxTimeStep"                    : 1.0,
    "FinalTime"                      : 1.0,
    "ControlTime"                    : 1e30,
    "GraphExportFreq"                : 1e30,
    "VelTrapGraphExportFreq"         : 1e30,
    "OutputTimeStep"                 : 1e30,
    "PostVelocity"                   : false,
    "ElementType"                    : "SphericPartDEMElement3D",
    "echo_level"                     : 0,
    "solver_settings"                : {
        "strategy"                          : "sphere_strategy",
        "RemoveBallsInitiallyTouchingWalls" : false,
        "model_import_settings"             : { "input_type" : "mdpa", "input_filename" : "impact" },
        "material_import_settings"          : { "materials_filename" : "" }
    }
}
"""

# Translational schemes: Symplectic_Euler (Kratos' default, a leap-frog), Velocity_Verlet,
# Forward_Euler, Taylor_Scheme.
SCHEMES = {
    "Symplectic_Euler": DEM.SymplecticEulerScheme,
    "Velocity_Verlet": DEM.VelocityVerletScheme,
    "Forward_Euler": DEM.ForwardEulerScheme,
    "Taylor_Scheme": DEM.TaylorScheme,
}


def stage_parameters(scheme, dt, steps):
    """The stage's settings: the ones above with the scheme, the step and the run's length."""
    parameters = KM.Parameters(PARAMETERS.replace("SCHEME_NAME", scheme))
    parameters["MaxTimeStep"].SetDouble(dt)
    parameters["FinalTime"].SetDouble(dt * steps)
    return parameters


def print_version():
    print("MILLIMPACT version=%s dem=%s threads=%d" % (
        version("KratosMultiphysics"), version("KratosDEMApplication"), KM.ParallelUtilities.GetNumThreads()))


def set_scheme(props, scheme):
    # The scheme must be in the particle's properties before the particle is created (and the
    # properties proxies must exist): without either, CreateSphericParticle segfaults (exit 139,
    # no message). The strategy sets the same scheme again when it initialises.
    SCHEMES[scheme]().SetTranslationalIntegrationSchemeInProperties(props, False)
    SCHEMES[scheme]().SetRotationalIntegrationSchemeInProperties(props, False)


def ball_material(props, density, young, poisson, scheme):
    props[DEM.PARTICLE_DENSITY] = density
    props[KM.YOUNG_MODULUS] = young
    props[KM.POISSON_RATIO] = poisson
    props[KM.PARTICLE_MATERIAL] = props.Id
    props[DEM.ROLLING_FRICTION] = 0.0
    props[DEM.ROLLING_FRICTION_WITH_WALLS] = 0.0
    props[DEM.COMPUTE_WEAR] = False
    props[DEM.DEM_TRANSLATIONAL_INTEGRATION_SCHEME_NAME] = scheme
    props[DEM.DEM_ROTATIONAL_INTEGRATION_SCHEME_NAME] = "Direct_Integration"
    set_scheme(props, scheme)


def wall_material(props, young, poisson):
    props[KM.YOUNG_MODULUS] = young
    props[KM.POISSON_RATIO] = poisson
    props[DEM.STATIC_FRICTION] = 0.0
    props[DEM.DYNAMIC_FRICTION] = 0.0
    props[DEM.WALL_COHESION] = 0.0
    props[DEM.COMPUTE_WEAR] = False
    props[DEM.SEVERITY_OF_WEAR] = 0.0
    props[DEM.IMPACT_WEAR_SEVERITY] = 0.0
    props[DEM.BRINELL_HARDNESS] = 200.0


def relation(props, other_id, scene, restitution, linear_stiffness):
    """The contact properties of `props` with material `other_id` (a sub-property).

    Ball scenes: DEM_D_Hertz_viscous_Coulomb, F = k y^1.5 + 2 gamma sqrt(1.5 m* k) y^(1/4) ydot,
    total normal force clamped at zero, k = (4/3) E* sqrt(R*) (E* mixed with the wall's E and
    nu, R* = R at the wall), gamma from `restitution` (COEFFICIENT_OF_RESTITUTION) by Thornton's
    fit, as YADE does. rod_end: DEM_D_Linear_Custom_Constants, F = k y + 2 gamma sqrt(m k) ydot,
    clamped at zero, k = `linear_stiffness` (K_NORMAL, N/m, read from the contact's
    sub-properties).
    """
    sub = KM.Properties(other_id)
    sub[DEM.STATIC_FRICTION] = 0.0
    sub[DEM.DYNAMIC_FRICTION] = 0.0
    sub[DEM.FRICTION_DECAY] = 500.0
    sub[DEM.ROLLING_FRICTION] = 0.0
    sub[DEM.ROLLING_FRICTION_WITH_WALLS] = 0.0
    sub[DEM.PARTICLE_COHESION] = 0.0
    sub[DEM.DEM_ROLLING_FRICTION_MODEL_NAME] = "DEMRollingFrictionModelBounded"
    if scene == "rod_end":
        sub[DEM.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME] = "DEM_D_Linear_Custom_Constants"
        sub[DEM.K_NORMAL] = linear_stiffness
        sub[DEM.K_TANGENTIAL] = 0.0
        sub[DEM.COEFFICIENT_OF_RESTITUTION] = 1.0
    else:
        sub[DEM.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME] = "DEM_D_Hertz_viscous_Coulomb"
        sub[DEM.COEFFICIENT_OF_RESTITUTION] = restitution
    props.AddSubProperties(sub)


def add_wall(walls, props, half, first_node):
    """The wall: the plane z = 0, a square of side 2 `half` made of two RigidFace3D3N triangles
    (nodes from `first_node`); a sphere is met on the lower-right one, away from the diagonal."""
    n = first_node
    walls.CreateNewNode(n, -half, -half, 0.0)
    walls.CreateNewNode(n + 1, half, -half, 0.0)
    walls.CreateNewNode(n + 2, half, half, 0.0)
    walls.CreateNewNode(n + 3, -half, half, 0.0)
    walls.CreateNewCondition("RigidFace3D3N", 1, [n, n + 1, n + 2], props)
    walls.CreateNewCondition("RigidFace3D3N", 2, [n, n + 2, n + 3], props)


class Stepper:
    """The stage's steps without its RunSolutionLoop, which costs ~0.65 ms a step, ~90 % of it
    in Python (two `Parameters.keys()` calls a step, each listing the ~150 settings): the same
    C++ calls as sphere_strategy's AdvanceInTime, Predict, InitializeSolutionStep,
    SolveSolutionStep and FinalizeSolutionStep (measured: the same trajectory to the last bit)."""

    def __init__(self, stage, dt):
        self.stage = stage
        self.dt = dt
        self.solver = stage._GetSolver()
        self.strategy = self.solver.cplusplus_strategy
        self.walls = stage.rigid_face_model_part
        self.mesh_mover = self.solver.dem_fem_utils

    def step(self):
        stage, strategy = self.stage, self.strategy
        stage.time = self.solver.AdvanceInTime(stage.time)
        self.mesh_mover.MoveAllMeshes(self.walls, stage.time, self.dt)
        strategy.ResetPrescribedMotionFlagsRespectingImposedDofs()
        strategy.InitializeSolutionStep()
        strategy.SolveSolutionStep()
        strategy.FinalizeSolutionStep()


def write_rows(path, rows):
    """A trajectory file: header iter,time,overlap,approach_velocity,normal_force."""
    with open(path, "w") as out:
        out.write("iter,time,overlap,approach_velocity,normal_force\n")
        out.write("".join("%d,%r,%r,%r,%r\n" % r for r in rows))


class OneImpact(DEMAnalysisStage):
    """A stage of one impact: sphere 1 (`e1`) moving along an axis at `v1` towards sphere 2
    (`e2`, ball_ball, moving at `v2`) or a wall at z = 0. A subclass makes them in
    ReadModelParts."""

    def __init__(self, model, parameters, scene, v1, v2):
        self.scene, self.v1, self.v2 = scene, v1, v2
        super().__init__(model, parameters)

    def SetMaterials(self):
        pass  # built in ReadModelParts

    def SetInitialNodalValues(self):
        super().SetInitialNodalValues()
        n1 = self.e1.GetNode(0)
        if self.scene == "ball_ball":
            n1.SetSolutionStepValue(KM.VELOCITY_X, self.v1)
            self.e2.GetNode(0).SetSolutionStepValue(KM.VELOCITY_X, self.v2)
        else:
            n1.SetSolutionStepValue(KM.VELOCITY_Z, -self.v1)

    def place(self, props1, r1, props2, r2, contact_x, contact_y):
        """Sphere 1 of radius r1 and, for two balls, sphere 2 of radius r2, one ulp from touching."""
        spheres, creator = self.spheres_model_part, self.creator_destructor
        if self.scene == "ball_ball":
            # Along x, centres r1 + r2 apart plus one ulp: touching but not overlapping. (10.4.4
            # does not count an overlap of exactly 0 as contact; the ulp guards a build that would,
            # as LAMMPS 2021 and YADE do.)
            x2 = math.nextafter(r1 + r2, math.inf)
            self.e1 = creator.CreateSphericParticle(spheres, 1, KM.Array3([0.0, 0.0, 0.0]), props1, r1, "SphericParticle3D")
            self.e2 = creator.CreateSphericParticle(spheres, 2, KM.Array3([x2, 0.0, 0.0]), props2, r2, "SphericParticle3D")
        else:
            z1 = math.nextafter(r1, math.inf)  # one ulp above touching, as for two balls
            self.e1 = creator.CreateSphericParticle(spheres, 1, KM.Array3([contact_x, contact_y, z1]), props1, r1, "SphericParticle3D")
            self.e2 = None

    def gap_and_speed(self, r1, r2):
        """Overlap and approach speed (positive while the bodies close) of the current state."""
        n1 = self.e1.GetNode(0)
        if self.scene == "ball_ball":
            n2 = self.e2.GetNode(0)
            overlap = (r1 + r2) - (n2.X - n1.X)
            speed = n1.GetSolutionStepValue(KM.VELOCITY_X) - n2.GetSolutionStepValue(KM.VELOCITY_X)
        else:
            overlap = r1 - n1.Z
            speed = -n1.GetSolutionStepValue(KM.VELOCITY_Z)
        return overlap, speed

    def normal_force(self):
        """The contact force on the moving sphere along the line of approach, repulsive positive."""
        f = self.e1.GetNode(0).GetSolutionStepValue(KM.TOTAL_FORCES)
        return -f[0] if self.scene == "ball_ball" else f[2]

    def run_rows(self, steps, dt, r1, r2, verlet, path):
        """Run `steps` steps; write their rows to `path` and print the MILLIMPACT lines of the run.

        Rows. Symplectic_Euler (and Forward_Euler, Taylor_Scheme): the law of a step sees the
        current state (x_n, v_n) and the force it computes is read after the step, when the node
        already holds x_{n+1}, v_{n+1}; a row pairs the state before the step with the force read
        after it (YADE's rows: the state the law saw and the force it gave), and a last row holds
        the state after the last step (its force is known only out of contact: zero).
        Velocity_Verlet: the force read after a step is F(x_{n+1}, v_{n+1/2}); a row is the state
        after the step with that force (LAMMPS' rows), after a first row with the initial state.
        """
        stepper = Stepper(self, dt)
        rows = []
        if verlet:
            overlap, speed = self.gap_and_speed(r1, r2)
            rows.append((0, self.time, overlap, speed, 0.0))
        start = time.perf_counter()
        for _ in range(steps):
            t = self.time
            if not verlet:
                overlap, speed = self.gap_and_speed(r1, r2)
            stepper.step()
            if verlet:
                overlap, speed = self.gap_and_speed(r1, r2)
                rows.append((len(rows), self.time, overlap, speed, self.normal_force()))
            else:
                rows.append((len(rows), t, overlap, speed, self.normal_force()))
        loop_time = time.perf_counter() - start
        overlap, speed = self.gap_and_speed(r1, r2)
        if overlap <= 0.0 and not verlet:
            rows.append((len(rows), self.time, overlap, speed, 0.0))
        write_rows(path, rows)
        print("MILLIMPACT iterations=%d dt=%r" % (steps, dt))
        print("MILLIMPACT loop_time=%r" % loop_time)
# ---- End of the shared part.
import numpy as np

FIRST = IMPACTS[0]
SCHEME = FIRST["scheme"]
DT = FIRST["timestep"]
STEPS = max(p["steps"] for p in IMPACTS)


def paper_force(y, v, stiffness, exponent, eta, mass, dt):
    """The paper's force C y^n (1 + eta s), N, at overlap y (m) and approach rate v (m/s),
    never attractive. s is sign(v) outside the band 2 eta C y^n dt / M (the change of v one
    step's jump between the branches makes) and v / band within it, so that a contact at rest
    carries the elastic force instead of flipping branch every step. The same operations in
    the same order as the harness's paper_force_in_step (src/solve/dashpot.rs)."""
    if y <= 0.0:
        return 0.0
    elastic = stiffness * y ** exponent
    band = 2.0 * eta * elastic * dt / mass
    if v >= band:
        branch = 1.0 + eta
    elif v <= -band:
        branch = 1.0 - eta
    else:
        branch = 1.0 + eta * (v / band)
    return elastic * branch


class PaperBatch(DEMAnalysisStage):
    """Impact k (from 0): properties 2k+1 (its ball) and 2k+2 (the other ball), spheres 2k+1
    and 2k+2, on the line y = SPACING * k (x = SPACING * k for a ball over the plane), so no
    two impacts' bodies ever meet."""

    def ReadModelParts(self, max_node_id=0, max_elem_id=0, max_cond_id=0):
        spheres = self.spheres_model_part
        made = []
        for k, p in enumerate(IMPACTS):
            ball_id, other_id = 2 * k + 1, 2 * k + 2
            ball = spheres.CreateNewProperties(ball_id)
            ball_material(ball, p["density"], p["young"], p["poisson"], SCHEME)
            if p["scene"] == "ball_ball":
                other = spheres.CreateNewProperties(other_id)
                ball_material(other, p["other_density"], p["other_young"], p["other_poisson"], SCHEME)
                # The stock law off: a linear law of zero stiffness, zero damping.
                for a, b in ((ball, ball_id), (ball, other_id), (other, ball_id), (other, other_id)):
                    relation(a, b, "rod_end", 1.0, 0.0)
            else:
                relation(ball, ball_id, "rod_end", 1.0, 0.0)
            made.append(ball)
        DEM.PropertiesProxiesManager().CreatePropertiesProxies(spheres)
        creator = self.creator_destructor
        self.impacts = []
        for k, (p, ball) in enumerate(zip(IMPACTS, made)):
            r1 = p["radius"]
            if p["scene"] == "ball_ball":
                # Touching: the overlap (r1 + r2) - (x2 - 0) is exactly 0 at the start.
                r2, y = p["other_radius"], SPACING * k
                other = spheres.GetProperties()[2 * k + 2]
                e1 = creator.CreateSphericParticle(spheres, 2 * k + 1, KM.Array3([0.0, y, 0.0]), ball, r1, "SphericParticle3D")
                e2 = creator.CreateSphericParticle(spheres, 2 * k + 2, KM.Array3([r1 + r2, y, 0.0]), other, r2, "SphericParticle3D")
            else:
                # Touching the plane z = 0: the overlap r1 - z is exactly 0 at the start.
                e1 = creator.CreateSphericParticle(spheres, 2 * k + 1, KM.Array3([SPACING * k, 0.0, r1]), ball, r1, "SphericParticle3D")
                e2 = None
            self.impacts.append({"p": p, "e1": e1, "e2": e2})
        self.model_parts_have_been_read = True
        self.all_model_parts.ComputeMaxIds()

    def SetMaterials(self):
        pass  # built in ReadModelParts

    def SetInitialNodalValues(self):
        super().SetInitialNodalValues()
        for c in self.impacts:
            n1 = c["e1"].GetNode(0)
            if c["p"]["scene"] == "ball_ball":
                n1.SetSolutionStepValue(KM.VELOCITY_X, c["p"]["velocity"])
                c["e2"].GetNode(0).SetSolutionStepValue(KM.VELOCITY_X, c["p"]["other_velocity"])
            else:
                n1.SetSolutionStepValue(KM.VELOCITY_Z, -c["p"]["velocity"])


class PaperStepper(Stepper):
    """The shared step with the hook's forces set just before SolveSolutionStep, the call that
    computes the forces (ComputeAdditionalForces reads EXTERNAL_APPLIED_FORCE) and integrates."""

    def step_with(self, set_forces):
        """One step; `set_forces(t)` is called with the time the step starts from."""
        stage, strategy = self.stage, self.strategy
        before = stage.time
        stage.time = self.solver.AdvanceInTime(stage.time)
        self.mesh_mover.MoveAllMeshes(self.walls, stage.time, self.dt)
        strategy.ResetPrescribedMotionFlagsRespectingImposedDofs()
        strategy.InitializeSolutionStep()
        set_forces(before)
        strategy.SolveSolutionStep()
        strategy.FinalizeSolutionStep()


if SCHEME not in SCHEMES:
    raise SystemExit("unknown translational scheme %r" % SCHEME)
if any(p["scheme"] != SCHEME or p["timestep"] != DT for p in IMPACTS):
    raise SystemExit("a batch runs one scheme and one time step")
if any(not (0.0 <= p["loss_coefficient"] < 1.0) for p in IMPACTS):
    raise SystemExit("the paper's law requires 0 <= loss coefficient < 1")
print_version()
parameters = stage_parameters(SCHEME, DT, STEPS)
parameters["GravityZ"].SetDouble(-GRAVITY)
stage = PaperBatch(KM.Model(), parameters)
stage.Initialize()

nodes = stage.spheres_model_part.Nodes
column = {node.Id: 3 * i for i, node in enumerate(nodes)}
masses = {node.Id: node.GetSolutionStepValue(KM.NODAL_MASS) for node in nodes}
variables = KM.VariableUtils()
# Each impact: its columns in the node vectors, the mass its band divides by (the ball's own
# over the plane, the two balls' reduced mass, from the masses Kratos formed) and its law.
laws = []
for k, c in enumerate(stage.impacts):
    p = c["p"]
    one = column[2 * k + 1]
    m1 = masses[2 * k + 1]
    if p["scene"] == "ball_ball":
        other = column[2 * k + 2]
        mass = 1.0 / (1.0 / m1 + 1.0 / masses[2 * k + 2])
    else:
        other = None
        mass = m1
    laws.append((p, one, other, mass, p["stiffness"], p["exponent"], p["loss_coefficient"]))
weights = np.zeros(3 * len(column))
for node in nodes:
    weights[column[node.Id] + 2] = -GRAVITY * masses[node.Id]


def state(positions, velocities, law):
    """Overlap and approach rate (positive while the bodies close) of one impact."""
    p, one, other = law[0], law[1], law[2]
    if other is not None:
        overlap = (p["radius"] + p["other_radius"]) - (positions[other] - positions[one])
        return overlap, velocities[one] - velocities[other]
    return p["radius"] - positions[one + 2], -velocities[one + 2]


stepper = PaperStepper(stage, DT)
rows = [[] for _ in laws]
applied = np.zeros(3 * len(column))
mismatch = 0.0  # the largest excess over the rounding, N; never below 0


def read_and_set(t):
    """The hook: the state each step's forces see, the paper's force from it, on the nodes."""
    positions = np.asarray(variables.GetCurrentPositionsVector(nodes, 3)).tolist()
    velocities = np.asarray(variables.GetSolutionStepValuesVector(nodes, KM.VELOCITY, 0, 3)).tolist()
    applied[:] = 0.0
    for k, law in enumerate(laws):
        y, v = state(positions, velocities, law)
        f = paper_force(y, v, law[4], law[5], law[6], law[3], DT)
        rows[k].append((len(rows[k]), t, y, v, f))
        if law[2] is not None:
            applied[law[1]] = -f
            applied[law[2]] = f
        else:
            applied[law[1] + 2] = f
    variables.SetSolutionStepValuesVector(nodes, KM.EXTERNAL_APPLIED_FORCE, applied.tolist(), 0)


start = time.perf_counter()
for step in range(STEPS):
    stepper.step_with(read_and_set)
    total = np.asarray(variables.GetSolutionStepValuesVector(nodes, KM.TOTAL_FORCES, 0, 3))
    # Beyond the rounding of Kratos' own sum of the force and the weight (two ulps of it).
    expected = applied + weights
    excess = np.abs(total - expected) - 2.0 * np.spacing(np.abs(expected))
    mismatch = max(mismatch, float(np.max(excess)))
# The state after the last step, and the force the next step would get from it.
positions = np.asarray(variables.GetCurrentPositionsVector(nodes, 3)).tolist()
velocities = np.asarray(variables.GetSolutionStepValuesVector(nodes, KM.VELOCITY, 0, 3)).tolist()
for k, law in enumerate(laws):
    y, v = state(positions, velocities, law)
    rows[k].append((len(rows[k]), stage.time, y, v, paper_force(y, v, law[4], law[5], law[6], law[3], DT)))
loop_time = (time.perf_counter() - start) / len(IMPACTS)

said = ["MILLIMPACT iterations=%d dt=%r force_mismatch=%r" % (STEPS, DT, mismatch)]
for k, law in enumerate(laws):
    # Its own steps' rows, then the state after them.
    write_rows("trajectory-%d.csv" % (k + 1), rows[k][: law[0]["steps"] + 1])
    # The mass the band divided by, beside Kratos' loop time.
    said.append("MILLIMPACT impact=%d loop_time=%r mass=%r" % (k + 1, loop_time, law[3]))
print("\n".join(said))
