# YADE: FrictMat dissipating through NewtonIntegrator's local damping
rock = O.materials.append(FrictMat(young=1e8, poisson=0.3, frictionAngle=0.5, density=2600))
O.bodies.append(utils.wall(0, axis=2, sense=1, material=rock))
O.bodies.append(utils.sphere((0, 0, 0.02), 0.005, material=rock))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
        [Ip2_FrictMat_FrictMat_FrictPhys()],
        [Law2_ScGeom_FrictPhys_CundallStrack()],
    ),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81)),
]
O.dt = 1e-6
O.run(10000)
