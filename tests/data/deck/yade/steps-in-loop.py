# A script that steps its simulation in a loop of its own: the reading stops at the loop's first
# step, and the set-up before it is what is checked.
steel = O.materials.append(FrictMat(young=2e11, poisson=0.3, density=7800))
O.bodies.append(sphere((0, 0, 0.1), 0.01, material=steel))
O.bodies.append(wall(0, axis=2, material=steel))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(hertzian=True)],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5)],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0.0),
]
O.dt = 1e-7
while O.iter < 1000:
    O.step()
O.materials[steel].young = 1.0
