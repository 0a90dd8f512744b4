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
{{common}}
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
