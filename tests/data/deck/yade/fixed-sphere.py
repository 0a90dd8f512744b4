# Beads dropped on fixed anvil spheres: one made with fixed=True, one held by blockedDOFs.
steel = O.materials.append(FrictMat(young=2e11, poisson=0.3, density=7800, frictionAngle=0.3))
glass = O.materials.append(FrictMat(young=6e10, poisson=0.22, density=2500, frictionAngle=0.4))
O.bodies.append(sphere((0, 0, 0), 0.01, material=steel, fixed=True))
anvil = O.bodies.append(sphere((0.05, 0, 0), 0.02, material=steel))
O.bodies[anvil].state.blockedDOFs = 'xyz'
O.bodies.append(sphere((0, 0, 0.02), 0.003, material=glass))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=((0, 1, 0.6),), val=0.8))],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0.0),
]
O.dt = 1e-7
O.run(1000)
