# YADE: a polydisperse pack, 400 glass beads of 200 radii (0.8 to 1.6 mm, two of each) on a floor
glass = O.materials.append(ViscElMat(tc=5e-5, en=0.7, et=0.7, frictionAngle=0.4, density=2500))
floor = O.bodies.append(utils.wall(0, axis=2, material=glass))
for k in range(400):
    # Each radius twice, in an order that mixes the sizes through the pack.
    size = (k * 73) % 200
    radius = 0.8e-3 + 0.8e-3 * size / 199
    x, y, z = k % 10, (k // 10) % 10, k // 100
    O.bodies.append(utils.sphere((4e-3 * x, 4e-3 * y, 2e-3 + 4e-3 * z), radius, material=glass))
for b in O.bodies:
    if isinstance(b.shape, Sphere):
        b.state.vel = Vector3(0, 0, -0.5)
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
O.run(20000)
