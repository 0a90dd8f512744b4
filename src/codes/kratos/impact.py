# millimpact: one normal impact in Kratos Multiphysics DEM (KratosMultiphysics and
# KratosDEMApplication 10.4.4 from PyPI), rendered by the kratos driver.
# Run as `.codes/kratos/bin/python impact.py` with OMP_NUM_THREADS=1, in a scratch directory.
# Writes trajectory.csv (header iter,time,overlap,approach_velocity,normal_force; one row per
# step, aligned as YADE's: the state the contact law saw in that step and the force it computed
# from it) and prints MILLIMPACT lines that the driver parses. Writes no other file (no GiD, VTK
# or graph output, no directories).
SCENE = "{{scene}}"  # ball_plate | ball_ball | rod_end
DT = {{timestep}}
STEPS = {{steps}}
R1 = {{radius}}
M1 = {{mass}}
RHO1 = {{density}}
E1 = {{young}}
NU1 = {{poisson}}
V1 = {{velocity}}
R2 = {{other_radius}}
M2 = {{other_mass}}
RHO2 = {{other_density}}
E2 = {{other_young}}
NU2 = {{other_poisson}}
V2 = {{other_velocity}}
WALL_E = {{wall_young}}
WALL_NU = {{wall_poisson}}
# COEFFICIENT_OF_RESTITUTION of the contact (ball scenes): Kratos turns it into DAMPING_GAMMA
# with Thornton's fit (GammaForHertzThornton), as YADE does.
EN = {{restitution}}
# rod_end: the linear spring k (N/m) of DEM_D_Linear_Custom_Constants (K_NORMAL of the contact).
KN = {{linear_stiffness}}
# The contact's damping ratio DAMPING_GAMMA (dashpot 2 gamma sqrt(m* k_tangent)), set directly
# after initialisation when >= 0 (rod_end: the linear law's gamma, instead of Kratos' bisection
# from a restitution coefficient, which stops at a tolerance of 1e-4 in gamma); when negative,
# the gamma Kratos derives from EN stays.
GAMMA = {{damping_gamma}}
# Translational scheme: Symplectic_Euler (default), Velocity_Verlet, Forward_Euler, Taylor_Scheme.
SCHEME = "{{scheme}}"

{{common}}

# Property ids: 1 the moving sphere, 2 the wall (ball_plate, rod_end) or the other sphere.
BALL, OTHER = 1, 2
# The wall's half side, 4 R; the sphere comes down onto the middle of one triangle.
L = 4.0 * R1
CONTACT_X, CONTACT_Y = 0.5 * L, -0.5 * L


class Impact(OneImpact):
    def ReadModelParts(self, max_node_id=0, max_elem_id=0, max_cond_id=0):
        spheres = self.spheres_model_part
        ball = spheres.CreateNewProperties(BALL)
        ball_material(ball, RHO1, E1, NU1, SCHEME)
        other = spheres.CreateNewProperties(OTHER)
        if SCENE == "ball_ball":
            ball_material(other, RHO2, E2, NU2, SCHEME)
            for a, b in ((ball, BALL), (ball, OTHER), (other, BALL), (other, OTHER)):
                relation(a, b, SCENE, EN, KN)
        else:
            wall_material(other, WALL_E, WALL_NU)
            relation(ball, OTHER, SCENE, EN, KN)
            relation(other, BALL, SCENE, EN, KN)

        # The particles read their material through properties proxies: create them before the
        # particles (without them CreateSphericParticle segfaults too).
        DEM.PropertiesProxiesManager().CreatePropertiesProxies(spheres)
        self.place(ball, R1, other, R2, CONTACT_X, CONTACT_Y)
        if SCENE != "ball_ball":
            add_wall(self.rigid_face_model_part, spheres.GetProperties()[OTHER], L, 11)
        self.model_parts_have_been_read = True
        self.all_model_parts.ComputeMaxIds()


{{oblique}}
if SCHEME not in SCHEMES:
    raise SystemExit("unknown translational scheme %r" % SCHEME)
print_version()
stage = Impact(KM.Model(), stage_parameters(SCHEME, DT, STEPS), SCENE, V1, V2)
stage.Initialize()
if GAMMA >= 0.0:
    # After Initialize: sphere_strategy writes DAMPING_GAMMA from COEFFICIENT_OF_RESTITUTION
    # while it initialises; the laws read it from the contact's sub-properties at every contact.
    for props in stage.spheres_model_part.Properties:
        for sub in props.GetSubProperties():
            sub[DEM.DAMPING_GAMMA] = GAMMA
for n in (stage.e1, stage.e2):
    if n is not None:
        # Kratos forms the mass from density and radius; the setup's mass is printed beside it.
        print("MILLIMPACT particle id=%d mass=%r setup_mass=%r radius=%r" % (
            n.Id, n.GetNode(0).GetSolutionStepValue(KM.NODAL_MASS), M1 if n.Id == 1 else M2,
            n.GetNode(0).GetSolutionStepValue(KM.RADIUS)))
sub = stage.spheres_model_part.GetProperties()[BALL].GetSubProperties(OTHER)
if sub.Has(DEM.DAMPING_GAMMA):
    print("MILLIMPACT damping_gamma=%r" % sub[DEM.DAMPING_GAMMA])
stage.run_rows(STEPS, DT, R1, R2, SCHEME == "Velocity_Verlet", "trajectory.csv")
