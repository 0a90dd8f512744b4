# YADE: import yade.qt and a view set up before the run
import yade.qt
glass = O.materials.append(FrictMat(young=5e8, poisson=0.25, frictionAngle=0.5, density=2500))
O.bodies.append(utils.wall(0, axis=2, sense=1, material=glass))
for k in range(3):
    O.bodies.append(utils.sphere((0.03 * k, 0, 0.02), 0.005, material=glass))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
        [Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5)],
        [Law2_ScGeom_MindlinPhys_Mindlin()],
    ),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.dt = 2e-7
v = yade.qt.View()
v.eyePosition = (0, -0.3, 0.05)
O.run(1000)
