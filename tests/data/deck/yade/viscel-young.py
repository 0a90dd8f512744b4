# base.py with ViscElMat's young, en form.
steel = O.materials.append(ViscElMat(young=1e8, en=0.5, density=1200))
O.bodies.append(sphere((0, 0, 0), 0.01, material=steel))
O.bodies.append(wall(-0.01, axis=2, material=steel))
O.engines = [
    ForceResetter(),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
    NewtonIntegrator(damping=0.0),
]
O.dt = 1e-7
