# YADE: a polydisperse cloud from makeCloud (400 spheres, rRelFuzz) on a wall: checked by size classes
from yade import pack
steel = O.materials.append(ViscElMat(tc=4e-5, en=0.8, et=0.8, frictionAngle=0.3, density=7600))
O.bodies.append(utils.wall(0, axis=2, material=steel))
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0.001), (0.06, 0.06, 0.06), rMean=1.5e-3, rRelFuzz=0.4, num=400, seed=11)
cloud.toSimulation(material=steel)
for b in O.bodies:
    if isinstance(b.shape, Sphere):
        b.state.vel = Vector3(0, 0, -0.8)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
        [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
        [Law2_ScGeom_ViscElPhys_Basic()],
    ),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.dt = 1e-6
O.run(50000)
