# YADE: a capillary (cohesive) law the check does not model
wet = O.materials.append(FrictMat(young=1e8, poisson=0.3, frictionAngle=0.5, density=2600))
O.bodies.append(utils.sphere((0, 0, 0.02), 0.005, material=wet))
O.bodies.append(utils.sphere((0, 0, 0.031), 0.005, material=wet))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_CapillaryPhys()], [Law2_ScGeom_CapillaryPhys_Capillarity()]),
    NewtonIntegrator(damping=0),
]
O.dt = 1e-6
O.run(100)
