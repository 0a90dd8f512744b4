# YADE: a MatchMaker with matches only for the pairs the script lets meet (beads on fixed anvils)
rest = 0.8
base = O.materials.append(ViscElMat(tc=5e-4, en=rest, et=rest, frictionAngle=0.3, density=7800))
soft = O.materials.append(ViscElMat(tc=5e-4, en=rest, et=rest, frictionAngle=0.3, density=1100))
hard = O.materials.append(ViscElMat(tc=5e-4, en=rest, et=rest, frictionAngle=0.3, density=3900))
r = 0.003
for k, mat in enumerate((soft, hard)):
    x = 10 * r * k
    O.bodies.append(sphere((x, 0, 0), r, material=base, fixed=True))
    bead = O.bodies.append(sphere((x, 0, 2.2 * r), r, material=mat))
    O.bodies[bead].state.vel = (0, 0, -0.8)
pick = lambda table: MatchMaker(matches=((base, soft, table[0]), (base, hard, table[1])))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom()],
        [Ip2_ViscElMat_ViscElMat_ViscElPhys(en=pick((0.7, 0.4)), et=pick((0.7, 0.4)))],
        [Law2_ScGeom_ViscElPhys_Basic()],
    ),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.dt = 1e-6
O.run(2000)
