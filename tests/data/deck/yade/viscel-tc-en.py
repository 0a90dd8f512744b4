# ViscElMat's tc, en, et form: two materials, a wall and a fixed box.
a = O.materials.append(ViscElMat(tc=2e-5, en=0.8, et=0.8, density=2500.0))
b = O.materials.append(ViscElMat(tc=4e-5, en=0.6, et=0.6, density=1100.0))
O.bodies.append(sphere((0, 0, 0), 0.005, material=a))
O.bodies.append(sphere((0, 0, 1), 0.004, material=b))
O.bodies.append(wall(0, axis=2, material=a))
O.bodies.append(box((0, 0, -0.5), (0.5, 0.5, 0.01), fixed=True, material=b))
O.engines = [InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]), NewtonIntegrator(damping=0)]
O.dt = 1e-7
