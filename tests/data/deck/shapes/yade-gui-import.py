# YADE: a script that opens the GUI (from yade import qt, qt.View())
from yade import qt
steel = O.materials.append(FrictMat(young=2e9, poisson=0.3, frictionAngle=0.4, density=7800))
O.bodies.append(utils.wall(0, axis=2, sense=1, material=steel))
O.bodies.append(utils.sphere((0, 0, 0.02), 0.006, material=steel))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
        [Ip2_FrictMat_FrictMat_MindlinPhys(en=0.7)],
        [Law2_ScGeom_MindlinPhys_Mindlin()],
    ),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.dt = 2e-7
qt.View()
qt.Controller()
O.run(20000, True)
