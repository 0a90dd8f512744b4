# Chung & Ooi's test-3 alumina bead and a wall of it, Hertz–Mindlin with the COR typed in directly
# (en = 0.95): YADE builds its damping from Thornton's fit, which realises 0.948, not 0.95
# (tests/cor_chart_live.rs; the benchmark page's COR chart).
alumina = O.materials.append(FrictMat(young=3.8e11, poisson=0.23, density=4000))
O.bodies.append(sphere((0, 0, 0), 0.0025, material=alumina))
O.bodies.append(wall(-0.0025, axis=2, material=alumina))
O.engines = [
    ForceResetter(),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(en=0.95)],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0.0),
]
O.dt = 6e-9
