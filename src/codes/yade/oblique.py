# The tangential half of an oblique impact (src/codes/yade/oblique.rs). The plane's axis is x;
# the ball, below the wall, touches it at +z from its centre, where its surface moves at
# v_x + R w_y: the case's spin W (surface at v_t - R W) is the ball's -w_y.
MU = {{friction}}
VT = {{tangential_velocity}}
W = {{angular_velocity}}
# Coulomb's bound: the interaction takes the smaller of the two materials' angles.
mat1.frictionAngle = math.atan(MU)
mat2.frictionAngle = math.atan(MU)
# No tangential dashpot: given en alone, YADE gives es = en and a shear dashpot of Thornton's
# fit; es = 1 is special-cased to betas = 0, and en keeps the normal damping.
phys_functor.es = 1.0
O.bodies[b1].state.vel = Vector3(VT, 0.0, V1)
O.bodies[b1].state.angVel = Vector3(0.0, -W, 0.0)
# A solid sphere's inertia of the mass set above (utils.sphere gave it the density's).
O.bodies[b1].state.inertia = Vector3(*([0.4 * M1 * R1 * R1] * 3))
# Free to move along x and to turn about y, as the tangential half needs, and no more.
O.bodies[b1].state.blockedDOFs = "yXZ"
