# millimpact: one normal impact in YADE, rendered by src/codes/yade.rs.
# Run as `yade -n -x impact.py`. Writes trajectory.csv (one row per iteration, the state the
# contact law saw in that iteration) and prints MILLIMPACT lines that the driver parses.
import math
import time

import yade
from yade import utils

SCENE = "{{scene}}"  # ball_plate | ball_ball | rod_end
DT = {{timestep}}
STEPS = {{steps}}
R1 = {{radius}}
M1 = {{mass}}
RHO1 = {{density}}
E1 = {{young}}
NU1 = {{poisson}}
V1 = {{velocity}}
R2 = {{other_radius}}
M2 = {{other_mass}}
RHO2 = {{other_density}}
E2 = {{other_young}}
NU2 = {{other_poisson}}
V2 = {{other_velocity}}
WALL_E = {{wall_young}}
WALL_NU = {{wall_poisson}}
EN = {{restitution}}
# Linear spring and dashpot of the contact (rod_end). YADE joins the two bodies' values in
# series, so each body gets twice the contact's value.
KN = {{linear_stiffness}}
CN = {{linear_damping}}

print("MILLIMPACT version=" + str(yade.config.version))

if SCENE == "rod_end":
    mat1 = ViscElMat(kn=2.0 * KN, cn=2.0 * CN, ks=0.0, cs=0.0, frictionAngle=0.0, density=RHO1)
    mat2 = ViscElMat(kn=2.0 * KN, cn=2.0 * CN, ks=0.0, cs=0.0, frictionAngle=0.0, density=RHO1)
    phys_functor = Ip2_ViscElMat_ViscElMat_ViscElPhys()
    law_functor = Law2_ScGeom_ViscElPhys_Basic()
else:
    mat1 = FrictMat(young=E1, poisson=NU1, frictionAngle=0.0, density=RHO1)
    if SCENE == "ball_ball":
        mat2 = FrictMat(young=E2, poisson=NU2, frictionAngle=0.0, density=RHO2)
    else:
        mat2 = FrictMat(young=WALL_E, poisson=WALL_NU, frictionAngle=0.0, density=RHO1)
    phys_functor = Ip2_FrictMat_FrictMat_MindlinPhys(en=EN)
    law_functor = Law2_ScGeom_MindlinPhys_Mindlin()
O.materials.append(mat1)
O.materials.append(mat2)

# Body 0 moves along +axis towards body 1 (the second ball, or the wall ahead of it). The bodies
# start one ulp apart instead of exactly touching: YADE's laws act at zero overlap (they skip
# only a negative one), so a dashpot without an overlap factor (ViscElPhys) would push with
# c*v0 at t = 0, where the compared law (and the physics) has no force.
if SCENE == "ball_ball":
    AXIS = 0
    b1 = O.bodies.append(utils.sphere((0.0, 0.0, 0.0), R1, material=mat1))
    b2 = O.bodies.append(utils.sphere((math.nextafter(R1 + R2, math.inf), 0.0, 0.0), R2, material=mat2))
    O.bodies[b2].state.mass = M2
    O.bodies[b2].state.vel = Vector3(V2, 0.0, 0.0)
    O.bodies[b2].state.blockedDOFs = "XYZ"
else:
    AXIS = 2
    b1 = O.bodies.append(utils.sphere((0.0, 0.0, math.nextafter(-R1, -math.inf)), R1, material=mat1))
    b2 = O.bodies.append(utils.wall(0.0, axis=2, sense=0, material=mat2))
O.bodies[b1].state.mass = M1
v = [0.0, 0.0, 0.0]
v[AXIS] = V1
O.bodies[b1].state.vel = Vector3(*v)
O.bodies[b1].state.blockedDOFs = "XYZ"


def gap_and_speed():
    p1 = O.bodies[b1].state.pos[AXIS]
    u1 = O.bodies[b1].state.vel[AXIS]
    if SCENE == "ball_ball":
        p2 = O.bodies[b2].state.pos[AXIS]
        u2 = O.bodies[b2].state.vel[AXIS]
        return (R1 + R2) - (p2 - p1), u1 - u2
    return R1 - (0.0 - p1), u1


rows = []
phys_printed = [False]


def record():
    overlap, speed = gap_and_speed()
    # The force on body 0 points along -axis when it repels.
    force = -O.forces.f(b1, sync=True)[AXIS]
    rows.append((O.iter, O.time, overlap, speed, force))
    if not phys_printed[0] and O.interactions.has(b1, b2) and O.interactions[b1, b2].isReal:
        i = O.interactions[b1, b2]
        p = i.phys
        names = ["kno", "betan", "betas", "alpha", "kn", "cn", "tangensOfFrictionAngle"]
        vals = " ".join("%s=%r" % (k, getattr(p, k)) for k in names if hasattr(p, k))
        print("MILLIMPACT phys %s refR1=%r refR2=%r iter=%d" % (vals, i.geom.refR1, i.geom.refR2, O.iter))
        phys_printed[0] = True


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(hertzian=True)],
        [phys_functor],
        [law_functor],
    ),
    # Between the contact law and the integrator: position x_i, force F(x_i, v_{i-1/2}) and
    # the velocity v_{i-1/2} the dashpot saw.
    PyRunner(iterPeriod=1, initRun=True, command="record()"),
    NewtonIntegrator(damping=0.0, gravity=(0.0, 0.0, 0.0)),
]
O.dt = DT

# O.run(STEPS, True) would do the same iterations, but its wait polls in 40 ms ticks (measured:
# 0.040 s for 10, 1000 and 10000 steps alike), so the loop is timed around O.step() instead.
# The time includes the per-step recording.
start = time.perf_counter()
for _ in range(STEPS):
    O.step()
loop_time = time.perf_counter() - start

overlap, speed = gap_and_speed()
with open("trajectory.csv", "w") as out:
    out.write("iter,time,overlap,approach_velocity,normal_force\n")
    for r in rows:
        out.write("%d,%r,%r,%r,%r\n" % r)
    # The state after the last iteration; its force is known only out of contact (zero).
    if overlap <= 0.0:
        out.write("%d,%r,%r,%r,%r\n" % (O.iter, O.time, overlap, speed, 0.0))
print("MILLIMPACT iterations=%d dt=%r" % (O.iter, O.dt))
print("MILLIMPACT loop_time=%r" % loop_time)
