# millimpact deck: one normal impact with the materials and functors of a user's YADE script
# ({{source}}; its lines between the markers, names resolved to their numbers), at the script's
# time step: {{pair}} at {{speed}} m/s. Run as `yade -j1 -n -x impact.py`; writes
# {{trajectory}} (one row per iteration, the state the contact law saw in that iteration) and
# prints the MILLIMPACT lines the driver parses, as the driver's own impact.py does.
import math
import time

import yade
from yade import utils

SCENE = "{{scene}}"  # ball_ball | wall
DT = {{timestep}}
STEPS = {{steps}}
R1 = {{radius}}
M1 = {{mass}}
V1 = {{velocity}}
R2 = {{other_radius}}
M2 = {{other_mass}}
V2 = {{other_velocity}}

print("MILLIMPACT version=" + str(yade.config.version))

# --- the script's lines ---
{{deck_lines}}
# --- end of the script's lines ---

# Body 0 moves towards body 1: the second ball along +x, or the wall's face at z = 0 from
# above. They start one ulp apart: YADE's laws act at zero overlap.
if SCENE == "ball_ball":
    AXIS = 0
    b1 = O.bodies.append(utils.sphere((0.0, 0.0, 0.0), R1, material={{material}}))
    b2 = O.bodies.append(utils.sphere((math.nextafter(R1 + R2, math.inf), 0.0, 0.0), R2, material={{other_material}}))
    O.bodies[b2].state.mass = M2
    O.bodies[b2].state.vel = Vector3(V2, 0.0, 0.0)
    O.bodies[b2].state.blockedDOFs = "XYZ"
    O.bodies[b1].state.vel = Vector3(V1, 0.0, 0.0)
else:
    AXIS = 2
    b1 = O.bodies.append(utils.sphere((0.0, 0.0, math.nextafter(R1, math.inf)), R1, material={{material}}))
    {{wall}}
    O.bodies[b1].state.vel = Vector3(0.0, 0.0, -V1)
O.bodies[b1].state.mass = M1
O.bodies[b1].state.blockedDOFs = "XYZ"


def gap_and_speed():
    p1 = O.bodies[b1].state.pos[AXIS]
    u1 = O.bodies[b1].state.vel[AXIS]
    if SCENE == "ball_ball":
        p2 = O.bodies[b2].state.pos[AXIS]
        u2 = O.bodies[b2].state.vel[AXIS]
        return (R1 + R2) - (p2 - p1), u1 - u2
    return R1 - p1, -u1


rows = []
phys_printed = [False]


def record():
    overlap, speed = gap_and_speed()
    # The force on body 0 along the line of centres, positive when it repels.
    f = O.forces.f(b1, sync=True)[AXIS]
    force = -f if SCENE == "ball_ball" else f
    rows.append((O.iter, O.time, overlap, speed, force))
    if not phys_printed[0] and O.interactions.has(b1, b2) and O.interactions[b1, b2].isReal:
        i = O.interactions[b1, b2]
        p = i.phys
        names = ["kno", "betan", "kn", "cn", "tangensOfFrictionAngle"]
        vals = " ".join("%s=%r" % (k, getattr(p, k)) for k in names if hasattr(p, k))
        print("MILLIMPACT phys %s refR1=%r refR2=%r iter=%d" % (vals, i.geom.refR1, i.geom.refR2, O.iter))
        phys_printed[0] = True


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop(IG2, IP2, LAW2),
    # Between the contact law and the integrator: position x_i, force F(x_i, v_{i-1/2}) and
    # the velocity v_{i-1/2} the law saw.
    PyRunner(iterPeriod=1, initRun=True, command="record()"),
    NewtonIntegrator(damping=0.0, gravity=(0.0, 0.0, 0.0)),
]
O.dt = DT

start = time.perf_counter()
for _ in range(STEPS):
    O.step()
loop_time = time.perf_counter() - start

overlap, speed = gap_and_speed()
with open("{{trajectory}}", "w") as out:
    out.write("iter,time,overlap,approach_velocity,normal_force\n")
    for r in rows:
        out.write("%d,%r,%r,%r,%r\n" % r)
    # The state after the last iteration; its force is known only out of contact (zero).
    if overlap <= 0.0:
        out.write("%d,%r,%r,%r,%r\n" % (O.iter, O.time, overlap, speed, 0.0))
print("MILLIMPACT iterations=%d dt=%r" % (O.iter, O.dt))
print("MILLIMPACT loop_time=%r" % loop_time)
