# A YADE script written the way users write it: materials built in a loop from a dict, values
# from numpy, spheres made by a function, a material edited after it was appended (by its
# index and through the object appended), the step from PWaveTimeStep(), then the run.
import numpy as np

from yade import utils

PROPERTIES = {
    "glass": dict(young=6.5e10, poisson=0.22, density=2500.0),
    "steel": dict(young=2.1e11, poisson=0.3, density=7850.0),
}
RADII = np.array([0.004, 0.006])

ids = {}
for name, values in PROPERTIES.items():
    ids[name] = O.materials.append(FrictMat(frictionAngle=np.radians(25.0), label=name, **values))

plate = FrictMat(young=2e11, poisson=0.3, density=7800.0, label="plate")
O.materials.append(plate)

# Softer beads than the table says, and a softer plate: edited after they were appended.
O.materials[0].young = 1e7
plate.young = 5e10


def bead(center, radius, material):
    return O.bodies.append(utils.sphere(center, radius, material=material))


for i, r in enumerate(RADII):
    bead((0.02 * i, 0.0, 0.1), float(r), "glass")
bead((0.1, 0.0, 0.1), 0.005, ids["steel"])
O.bodies.append(utils.wall(0.0, axis=2, sense=1, material=plate))

EN = {("glass", "glass"): 0.9, ("glass", "steel"): 0.8, ("steel", "steel"): 0.7}
matches = [(ids[a], ids[b], e) for (a, b), e in EN.items()]

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(hertzian=True)],
        [Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=matches, algo="val", val=0.6))],
        [Law2_ScGeom_MindlinPhys_Mindlin()],
    ),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
O.dt = 0.3 * PWaveTimeStep()
spheres = sorted((b.material.id, b.shape.radius) for b in O.bodies if isinstance(b.shape, Sphere))
print("YADE young=%r wall_young=%r dt=%r spheres=%r" % (O.materials[0].young, O.materials[2].young, O.dt, spheres))

O.run(1000, True)
