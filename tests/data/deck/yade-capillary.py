# Wet glass beads in YADE: capillary bridges between the beads (a deck the check refuses: the
# capillary force is no part of a dry contact law).
from yade import utils

glass = O.materials.append(FrictMat(young=7e10, poisson=0.22, density=2500.0, frictionAngle=0.4, label='glass'))
for i in range(10):
    O.bodies.append(utils.sphere((0.0, 0.0, 0.003 * i), 0.001, material=glass))

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom()],
        [Ip2_FrictMat_FrictMat_CapillaryPhys()],
        [Law2_ScGeom_MindlinPhys_Mindlin()],
    ),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
O.dt = 1e-7
