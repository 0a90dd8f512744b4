# YADE: ViscElMat with tc, en and et, a sphere given its speed by state.vel above a facet floor
rubber = O.materials.append(ViscElMat(tc=2e-4, en=0.6, et=0.6, frictionAngle=0.5, density=1200))
O.bodies.append(utils.facet([(-0.1, -0.1, 0), (0.1, -0.1, 0), (0, 0.1, 0)], material=rubber, fixed=True))
O.bodies.append(utils.sphere((0, 0, 0.02), 0.005, material=rubber))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
        [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
        [Law2_ScGeom_ViscElPhys_Basic()],
    ),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.bodies[-1].state.vel = Vector3(0, 0, -1.5)
O.dt = 1e-6
O.run(10000)
