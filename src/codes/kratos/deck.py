# millimpact deck: one normal impact in Kratos Multiphysics DEM (10.4.4) with the materials of a
# user's own MaterialsDEM.json, rendered by the kratos deck reader (src/codes/kratos/deck.rs).
# Run as `.codes/kratos/bin/python impact.py` with OMP_NUM_THREADS=1, in a scratch directory.
# Writes trajectory.csv (impact.py's rows) and prints MILLIMPACT lines the driver parses.
#
# The scene is impact.py's (the same stage settings, start one ulp from touching, step loop and
# rows); what differs is where the materials come from: MATERIALS below is the user's file
# reduced to the materials and material relations of the pairs checked (their "Variables" as
# written), and Kratos' own MaterialsAssignationUtility turns it into properties and
# sub-properties, as DEMAnalysisStage.SetMaterials does; the strategy then derives
# DAMPING_GAMMA from each relation's COEFFICIENT_OF_RESTITUTION and law, as in the user's run.
# The particles are created with the properties of their material id, a wall of two
# RigidFace3D3N triangles with the wall material's.
SCENE = "{{scene}}"  # ball_plate | ball_ball
DT = {{timestep}}
STEPS = {{steps}}
# The moving particle: its material id, radius and velocity.
ID1 = {{material}}
R1 = {{radius}}
V1 = {{velocity}}
# ball_ball: the other particle's material id, radius and velocity; ball_plate: the wall's
# material id (R2, V2 unused).
ID2 = {{other_material}}
R2 = {{other_radius}}
V2 = {{other_velocity}}
# The user's translational scheme (the reader accepts Symplectic_Euler alone).
SCHEME = "{{scheme}}"
# The user's materials, reduced (JSON).
MATERIALS = {{materials}}

{{common}}
from KratosMultiphysics.DEMApplication.materials_assignation_utility import MaterialsAssignationUtility

# The wall's half side, 4 R; the sphere comes down onto the middle of one triangle.
L = 4.0 * R1
CONTACT_X, CONTACT_Y = 0.5 * L, -0.5 * L


class DeckImpact(OneImpact):
    def ReadModelParts(self, max_node_id=0, max_elem_id=0, max_cond_id=0):
        spheres = self.spheres_model_part
        # Every material of the file becomes properties of the spheres' model part with its
        # relations as sub-properties, by Kratos' own reader (walls' too, as Kratos keeps them).
        MaterialsAssignationUtility(self.model, spheres, KM.Parameters(MATERIALS)).AssignMaterialParametersToProperties()
        particle_ids = (ID1, ID2) if SCENE == "ball_ball" else (ID1,)
        for pid in particle_ids:
            set_scheme(spheres.GetProperties()[pid], SCHEME)
        DEM.PropertiesProxiesManager().CreatePropertiesProxies(spheres)
        self.place(spheres.GetProperties()[ID1], R1, spheres.GetProperties()[ID2], R2, CONTACT_X, CONTACT_Y)
        if SCENE != "ball_ball":
            add_wall(self.rigid_face_model_part, spheres.GetProperties()[ID2], L, 11)
        self.model_parts_have_been_read = True
        self.all_model_parts.ComputeMaxIds()


if SCHEME != "Symplectic_Euler":
    raise SystemExit("unsupported translational scheme %r" % SCHEME)
print_version()
stage = DeckImpact(KM.Model(), stage_parameters(SCHEME, DT, STEPS), SCENE, V1, V2)
stage.Initialize()
for n in (stage.e1, stage.e2):
    if n is not None:
        # Kratos forms the mass from the material's density and the radius.
        print("MILLIMPACT particle id=%d mass=%r radius=%r" % (
            n.Id, n.GetNode(0).GetSolutionStepValue(KM.NODAL_MASS), n.GetNode(0).GetSolutionStepValue(KM.RADIUS)))
sub = stage.spheres_model_part.GetProperties()[ID1].GetSubProperties(ID2)
print("MILLIMPACT law=%s" % sub[DEM.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME])
if sub.Has(DEM.DAMPING_GAMMA):
    print("MILLIMPACT damping_gamma=%r" % sub[DEM.DAMPING_GAMMA])
stage.run_rows(STEPS, DT, R1, R2, False, "trajectory.csv")
