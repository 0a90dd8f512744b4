# A script YADE cannot set up: a name it never defined.
steel = O.materials.append(FrictMat(young=2e11, poisson=0.3, density=7800.0))
O.bodies.append(sphere((0, 0, 0), 0.01, material=steel))


def stiffness():
    return E_STEEL * 2


O.materials[steel].young = stiffness()
O.dt = 1e-7
