# ---- An oblique or spinning impact (src/codes/kratos/oblique.py, written into the script by the
# ---- renderer for an oblique case only; a normal case's script has none of it).
# The ball also moves along the wall's x axis and spins about y; the frame is the wall's: the
# normal is +z with the ball above, so the ball's surface at the contact moves at
# VELOCITY_X - R ANGULAR_VELOCITY_Y, and the spin is millimpact's (positive rolling towards +x).
# The law stays DEM_D_Hertz_viscous_Coulomb, whose tangential half is Kratos' own and cannot be
# changed from here: a Mindlin spring k_t = 8 G* sqrt(R* delta), updated by increments (its old
# force scaled by sqrt(delta/delta_old) while unloading), a dashpot 2 gamma sqrt(m* k_t) at the
# normal law's DAMPING_GAMMA, and spring plus dashpot bounded by mu times the whole normal force
# (elastic and dashpot, clamped at zero). Friction mu is STATIC_FRICTION = DYNAMIC_FRICTION, so
# FRICTION_DECAY has no effect.
VT = {{tangential_velocity}}  # m/s along x
OMEGA = {{angular_velocity}}  # rad/s about y
MU = {{friction}}


class ObliqueImpact(Impact):
    def __init__(self, model, parameters, scene, v1, v2):
        # Without RotationOption the spheres' spin is neither integrated nor felt by the contact.
        parameters["RotationOption"].SetBool(True)
        super().__init__(model, parameters, scene, v1, v2)

    def ReadModelParts(self, max_node_id=0, max_elem_id=0, max_cond_id=0):
        super().ReadModelParts(max_node_id, max_elem_id, max_cond_id)
        # The law reads mu from the ball's contact sub-properties; the wall's own are set alike
        # so that no reading of either finds another value.
        for props in self.spheres_model_part.Properties:
            for p in [props] + list(props.GetSubProperties()):
                p[DEM.STATIC_FRICTION] = MU
                p[DEM.DYNAMIC_FRICTION] = MU
        for props in self.rigid_face_model_part.Properties:
            props[DEM.STATIC_FRICTION] = MU
            props[DEM.DYNAMIC_FRICTION] = MU

    def SetInitialNodalValues(self):
        super().SetInitialNodalValues()
        n1 = self.e1.GetNode(0)
        n1.SetSolutionStepValue(KM.VELOCITY_X, VT)
        n1.SetSolutionStepValue(KM.ANGULAR_VELOCITY_Y, OMEGA)

    def run_rows(self, steps, dt, r1, r2, verlet, path):
        super().run_rows(steps, dt, r1, r2, verlet, path)
        n1 = self.e1.GetNode(0)
        print("MILLIMPACT inertia=%r" % n1.GetSolutionStepValue(DEM.PARTICLE_MOMENT_OF_INERTIA))
        print("{{tangential_line}} %r %r" % (
            n1.GetSolutionStepValue(KM.VELOCITY_X), n1.GetSolutionStepValue(KM.ANGULAR_VELOCITY_Y)))


# The stage below is the oblique one.
Impact = ObliqueImpact
# ---- End of the oblique part.
