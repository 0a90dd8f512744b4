# base.py with ViscElMat's kn, cn form.
steel = O.materials.append(ViscElMat(kn=2e6, ks=0, cn=40.0, cs=0))
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
