# Many independent normal impacts side by side in one Kratos DEM stage (src/codes/kratos/batch.rs).
# Each impact is built as impact.py builds it alone: the same materials and sub-properties, the
# same start state, the same step loop and the same rows; where it sits is below. Writes
# trajectory-K.csv per impact K (from 1) and prints MILLIMPACT lines.
#
# Above this script: IMPACTS (each impact's values, as impact.py is filled with them), SPACING.
{{common}}
import numpy as np

FIRST = IMPACTS[0]
SCHEME = FIRST["scheme"]
DT = FIRST["timestep"]
STEPS = max(p["steps"] for p in IMPACTS)

# Impact k (from 0): properties 2k+1 (its ball) and 2k+2 (the other ball), spheres 2k+1 and
# 2k+2. Two balls sit on the line y = SPACING * k (the coordinate across their line of approach,
# shared by both, so every difference of positions is the single run's). A plate or a rod end
# has no wall of its own: all share one wall, made of the single run's two triangles scaled by
# WALL_SCALE (a power of two), so that its edges and normal are the single wall's scaled exactly
# and its normal comes out as the single run's; its properties are WALL (one sub-property per
# ball). A sphere meets it at its own point of the lower-right triangle, away from every edge:
# across the plane the sphere's offset is multiplied by the normal's exact zeros, so its distance
# to the wall is its single run's to the last bit.
WALL = 2 * len(IMPACTS) + 1
WALL_SCENE = FIRST["scene"] != "ball_ball"
if any((p["scene"] != "ball_ball") != WALL_SCENE for p in IMPACTS):
    raise SystemExit("a batch holds two-ball impacts or wall impacts, not both")
LENGTH = 4.0 * FIRST["radius"]  # the single run's half side, 4 R
GAP = 4.0 * FIRST["radius"]  # between spheres, and from the wall's edges
WALL_SCALE = 1.0
while 2.0 * WALL_SCALE * LENGTH - 4.0 * GAP < GAP * len(IMPACTS):
    WALL_SCALE *= 2.0


def wall_point(k):
    """Where sphere k meets the wall: on a line parallel to the diagonal, GAP below it."""
    half = WALL_SCALE * LENGTH
    d = -half + 2.0 * GAP + GAP * k
    return d + 0.5 * GAP, d - 0.5 * GAP


class Batch(DEMAnalysisStage):
    def ReadModelParts(self, max_node_id=0, max_elem_id=0, max_cond_id=0):
        spheres = self.spheres_model_part
        made = []
        if WALL_SCENE:
            wall = spheres.CreateNewProperties(WALL)
            wall_material(wall, FIRST["wall_young"], FIRST["wall_poisson"])
        for k, p in enumerate(IMPACTS):
            ball_id, other_id = 2 * k + 1, 2 * k + 2
            ball = spheres.CreateNewProperties(ball_id)
            ball_material(ball, p["density"], p["young"], p["poisson"], SCHEME)
            if p["scene"] == "ball_ball":
                other = spheres.CreateNewProperties(other_id)
                ball_material(other, p["other_density"], p["other_young"], p["other_poisson"], SCHEME)
                for a, b in ((ball, ball_id), (ball, other_id), (other, ball_id), (other, other_id)):
                    relation(a, b, p["scene"], p["restitution"], p["linear_stiffness"])
            else:
                relation(ball, WALL, p["scene"], p["restitution"], p["linear_stiffness"])
                relation(wall, ball_id, p["scene"], p["restitution"], p["linear_stiffness"])
            made.append((ball, other_id))
        DEM.PropertiesProxiesManager().CreatePropertiesProxies(spheres)
        creator = self.creator_destructor
        self.impacts = []
        for k, (p, (ball, other_id)) in enumerate(zip(IMPACTS, made)):
            r1 = p["radius"]
            if p["scene"] == "ball_ball":
                r2, y = p["other_radius"], SPACING * k
                x2 = math.nextafter(r1 + r2, math.inf)
                other = spheres.GetProperties()[other_id]
                e1 = creator.CreateSphericParticle(spheres, 2 * k + 1, KM.Array3([0.0, y, 0.0]), ball, r1, "SphericParticle3D")
                e2 = creator.CreateSphericParticle(spheres, 2 * k + 2, KM.Array3([x2, y, 0.0]), other, r2, "SphericParticle3D")
            else:
                x, y = wall_point(k)
                z1 = math.nextafter(r1, math.inf)
                e1 = creator.CreateSphericParticle(spheres, 2 * k + 1, KM.Array3([x, y, z1]), ball, r1, "SphericParticle3D")
                e2 = None
            # Their nodes, looked up once rather than every step.
            n1, n2 = e1.GetNode(0), None if e2 is None else e2.GetNode(0)
            self.impacts.append({"p": p, "e1": e1, "e2": e2, "n1": n1, "n2": n2})
        if WALL_SCENE:
            # Its nodes numbered after every sphere's.
            add_wall(self.rigid_face_model_part, spheres.GetProperties()[WALL], WALL_SCALE * LENGTH, 2 * len(IMPACTS) + 11)
        self.model_parts_have_been_read = True
        self.all_model_parts.ComputeMaxIds()

    def SetMaterials(self):
        pass  # built in ReadModelParts

    def SetInitialNodalValues(self):
        super().SetInitialNodalValues()
        for c in self.impacts:
            n1 = c["n1"]
            if c["p"]["scene"] == "ball_ball":
                n1.SetSolutionStepValue(KM.VELOCITY_X, c["p"]["velocity"])
                c["n2"].SetSolutionStepValue(KM.VELOCITY_X, c["p"]["other_velocity"])
            else:
                n1.SetSolutionStepValue(KM.VELOCITY_Z, -c["p"]["velocity"])


if SCHEME not in SCHEMES:
    raise SystemExit("unknown translational scheme %r" % SCHEME)
if any(p["scheme"] != SCHEME or p["timestep"] != DT for p in IMPACTS):
    raise SystemExit("a batch runs one scheme and one time step")
print_version()
stage = Batch(KM.Model(), stage_parameters(SCHEME, DT, STEPS))
stage.Initialize()
all_properties = stage.spheres_model_part.GetProperties()
for k, c in enumerate(stage.impacts):
    gamma = c["p"]["damping_gamma"]
    if gamma >= 0.0:
        # As impact.py: every sub-property of the impact's bodies (the wall's towards its ball).
        for sub in all_properties[2 * k + 1].GetSubProperties():
            sub[DEM.DAMPING_GAMMA] = gamma
        if c["p"]["scene"] == "ball_ball":
            for sub in all_properties[2 * k + 2].GetSubProperties():
                sub[DEM.DAMPING_GAMMA] = gamma
        else:
            all_properties[WALL].GetSubProperties(2 * k + 1)[DEM.DAMPING_GAMMA] = gamma

stepper = Stepper(stage, DT)
# impact.py's step loop, for every impact at once. Each step records every sphere's state
# before it (position and velocity, read as whole vectors: one call each rather than one per
# sphere) and its force after it; each impact's rows are then impact.py's, read from them:
# its own steps, then its state after them.
nodes = stage.spheres_model_part.Nodes
column = {node.Id: 3 * i for i, node in enumerate(nodes)}
variables = KM.VariableUtils()


def record_state():
    times.append(stage.time)
    positions.append(np.asarray(variables.GetCurrentPositionsVector(nodes, 3)))
    velocities.append(np.asarray(variables.GetSolutionStepValuesVector(nodes, KM.VELOCITY, 0, 3)))


times, positions, velocities, forces = [], [], [], []
start = time.perf_counter()
for step in range(STEPS):
    record_state()
    stepper.step()
    forces.append(np.asarray(variables.GetSolutionStepValuesVector(nodes, KM.TOTAL_FORCES, 0, 3)))
record_state()
loop_time = (time.perf_counter() - start) / len(IMPACTS)

# Row s of the states is the state before step s (the last, after the last step); row s of the
# forces the force after step s. The overlap and approach speed as impact.py forms them.
times = np.array(times)
positions = np.stack(positions)
velocities = np.stack(velocities)
forces = np.stack(forces)
verlet = SCHEME == "Velocity_Verlet"
said = []
for k, c in enumerate(stage.impacts):
    p = c["p"]
    steps = p["steps"]
    one = column[2 * k + 1]
    if p["scene"] == "ball_ball":
        other = column[2 * k + 2]
        overlap = (p["radius"] + p["other_radius"]) - (positions[:, other] - positions[:, one])
        speed = velocities[:, one] - velocities[:, other]
        force = -forces[:, one]
    else:
        overlap = p["radius"] - positions[:, one + 2]
        speed = -velocities[:, one + 2]
        force = forces[:, one + 2]
    t, overlap, speed, force = times.tolist(), overlap.tolist(), speed.tolist(), force.tolist()
    if verlet:
        # The start, then the state after each step with that step's force.
        rows = [(0, t[0], overlap[0], speed[0], 0.0)]
        rows += [(s + 1, t[s + 1], overlap[s + 1], speed[s + 1], force[s]) for s in range(steps)]
    else:
        # The state before each step with that step's force, then the state after the last
        # step; its force is known only out of contact (zero).
        rows = [(s, t[s], overlap[s], speed[s], force[s]) for s in range(steps)]
        if overlap[steps] <= 0.0:
            rows.append((steps, t[steps], overlap[steps], speed[steps], 0.0))
    write_rows("trajectory-%d.csv" % (k + 1), rows)
    said.append("MILLIMPACT impact=%d loop_time=%r" % (k + 1, loop_time))
# One print: each costs about a millisecond here.
print("\n".join(said))
