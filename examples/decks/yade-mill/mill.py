# A laboratory ball mill in YADE: a charge of steel and alumina balls in a steel drum (a
# facet cylinder), turned at 75 % of its critical speed. Run it with `yade mill.py`; check its
# contacts with `millimpact deck examples/decks/yade-mill/mill.py`.
import math

from yade import geom, utils

# The charge: two ball sizes of two materials.
R_STEEL = 0.02  # m, 40 mm steel balls
R_ALUMINA = R_STEEL * 0.625  # m, 25 mm alumina balls
N_LAYERS = 2

# The drum: axis along z, gravity along -y.
DRUM_RADIUS = 0.15  # m
DRUM_LENGTH = 0.2  # m
OMEGA = 0.75 * math.sqrt(9.81 / DRUM_RADIUS)  # rad/s

steel = O.materials.append(FrictMat(young=2.1e11, poisson=0.3, density=7850.0, frictionAngle=math.radians(20), label='steel'))
alumina = O.materials.append(FrictMat(young=3.7e11, poisson=0.22, density=3950.0, frictionAngle=math.radians(25), label='alumina'))
liner = O.materials.append(FrictMat(young=2.0e11, poisson=0.29, density=7800.0, frictionAngle=math.radians(30), label='liner'))

drum = O.bodies.append(geom.facetCylinder((0, 0, 0), DRUM_RADIUS, DRUM_LENGTH, segmentsNumber=40, wallMask=7, material=liner))

# The charge in the lower half of the drum, one layer of each size per level.
for layer in range(N_LAYERS):
    y = -0.11 + 0.05 * layer
    for i in range(5):
        O.bodies.append(sphere((-0.09 + 0.045 * i, y, -0.045), R_STEEL, material=steel))
    for i in range(7):
        O.bodies.append(sphere((-0.09 + 0.03 * i, y + 0.005, 0.03), R_ALUMINA, material='alumina'))

# Restitution per pair of materials, as measured in drop tests.
EN = MatchMaker(matches=((steel, steel, 0.8), (steel, alumina, 0.75), (alumina, alumina, 0.7), (steel, liner, 0.6), (alumina, liner, 0.55)), algo='val', val=0.7)

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
        [Ip2_FrictMat_FrictMat_MindlinPhys(en=EN, es=0.7)],
        [Law2_ScGeom_MindlinPhys_Mindlin()],
    ),
    RotationEngine(ids=drum, rotationAxis=(0, 0, 1), rotateAroundZero=True, angularVelocity=OMEGA),
    NewtonIntegrator(damping=0.0, gravity=(0, -9.81, 0)),
    VTKRecorder(fileName='mill-', recorders=['spheres', 'facets'], iterPeriod=20000),
]
O.dt = 0.2 * PWaveTimeStep()

O.run(2000000)
