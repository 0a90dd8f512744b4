# A script that settles its packing before it sets its contact law: the reading stops at the
# first O.run, where no InteractionLoop is set yet.
steel = O.materials.append(FrictMat(young=2e11, poisson=0.3, density=7800.0))
O.bodies.append(sphere((0, 0, 0.1), 0.01, material=steel))
O.bodies.append(wall(0, axis=2, material=steel))
O.dt = 1e-7
O.run(1000, True)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5)],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0.0),
]
