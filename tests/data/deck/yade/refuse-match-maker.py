# base.py with one line changed (a case of tests/deck_refusals.rs).
steel = O.materials.append(FrictMat(young=2e11, poisson=0.3, density=7800))
O.bodies.append(sphere((0, 0, 0), 0.01, material=steel))
O.bodies.append(wall(-0.01, axis=2, material=steel))
O.engines = [
    ForceResetter(),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=((0, 1, 0.5),)))],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0.0),
]
O.dt = 1e-7
