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
import os

# One thread, set before Kratos (and its OpenMP runtime) loads (impact.py has the measurements).
os.environ["OMP_NUM_THREADS"] = "1"

import math
import time
from importlib.metadata import version

import KratosMultiphysics as KM
import KratosMultiphysics.DEMApplication as DEM
from KratosMultiphysics.DEMApplication.DEM_analysis_stage import DEMAnalysisStage
from KratosMultiphysics.DEMApplication.materials_assignation_utility import MaterialsAssignationUtility

# The user's materials, reduced (JSON).
MATERIALS = {{materials}}
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

KM.Logger.GetDefaultOutput().SetSeverity(KM.Logger.Severity.WARNING)
KM.ParallelUtilities.SetNumThreads(1)

# impact.py's settings, word for word, but for the scheme.
PARAMETERS = """
{
    "problem_name"                   : "impact",
    "do_print_results_option"        : false,
    "post_gid_option"                : false,
    "post_vtk_option"                : false,
    "Dimension"                      : 3,
    "BoundingBoxOption"              : false,
    "dem_inlet_option"               : false,
    "GravityX"                       : 0.0,
    "GravityY"                       : 0.0,
    "GravityZ"                       : 0.0,
    "RotationOption"                 : false,
    "CleanIndentationsOption"        : false,
    "EnergyCalculationOption"        : false,
    "GlobalDamping"                  : 0.0,
    "VirtualMassCoefficient"         : 1.0,
    "DeltaOption"                    : "Absolute",
    "SearchTolerance"                : 0.0,
    "search_tolerance_against_walls" : 0.0,
    "NeighbourSearchFrequency"       : 1,
    "TranslationalIntegrationScheme" : "SCHEME_NAME",
    "RotationalIntegrationScheme"    : "Direct_Integration",
    "AutomaticTimestep"              : false,
    "MaxTimeStep"                    : 1.0,
    "FinalTime"                      : 1.0,
    "ControlTime"                    : 1e30,
    "GraphExportFreq"                : 1e30,
    "VelTrapGraphExportFreq"         : 1e30,
    "OutputTimeStep"                 : 1e30,
    "PostVelocity"                   : false,
    "ElementType"                    : "SphericPartDEMElement3D",
    "echo_level"                     : 0,
    "solver_settings"                : {
        "strategy"                          : "sphere_strategy",
        "RemoveBallsInitiallyTouchingWalls" : false,
        "model_import_settings"             : { "input_type" : "mdpa", "input_filename" : "impact" },
        "material_import_settings"          : { "materials_filename" : "" }
    }
}
""".replace("SCHEME_NAME", SCHEME)

SCHEMES = {"Symplectic_Euler": DEM.SymplecticEulerScheme}

# The wall: the plane z = 0, a square of side 2 L made of two triangles; the sphere comes down
# onto the middle of one triangle (away from the shared diagonal), from z > 0.
L = 4.0 * R1
CONTACT_X, CONTACT_Y = 0.5 * L, -0.5 * L


class Impact(DEMAnalysisStage):
    def ReadModelParts(self, max_node_id=0, max_elem_id=0, max_cond_id=0):
        spheres = self.spheres_model_part
        # Every material of the file becomes properties of the spheres' model part with its
        # relations as sub-properties, by Kratos' own reader (walls' too, as Kratos keeps them).
        MaterialsAssignationUtility(self.model, spheres, KM.Parameters(MATERIALS)).AssignMaterialParametersToProperties()
        particle_ids = (ID1, ID2) if SCENE == "ball_ball" else (ID1,)
        for pid in particle_ids:
            props = spheres.GetProperties()[pid]
            # The scheme in the particles' properties and the properties proxies before any
            # particle is created: without either, CreateSphericParticle segfaults (impact.py).
            # The strategy sets the same scheme again when it initialises.
            SCHEMES[SCHEME]().SetTranslationalIntegrationSchemeInProperties(props, False)
            SCHEMES[SCHEME]().SetRotationalIntegrationSchemeInProperties(props, False)
        DEM.PropertiesProxiesManager().CreatePropertiesProxies(spheres)
        creator = self.creator_destructor
        p1 = spheres.GetProperties()[ID1]
        if SCENE == "ball_ball":
            x2 = math.nextafter(R1 + R2, math.inf)
            self.e1 = creator.CreateSphericParticle(spheres, 1, KM.Array3([0.0, 0.0, 0.0]), p1, R1, "SphericParticle3D")
            self.e2 = creator.CreateSphericParticle(spheres, 2, KM.Array3([x2, 0.0, 0.0]), spheres.GetProperties()[ID2], R2, "SphericParticle3D")
        else:
            z1 = math.nextafter(R1, math.inf)
            self.e1 = creator.CreateSphericParticle(spheres, 1, KM.Array3([CONTACT_X, CONTACT_Y, z1]), p1, R1, "SphericParticle3D")
            self.e2 = None
            walls = self.rigid_face_model_part
            wall_props = spheres.GetProperties()[ID2]
            walls.CreateNewNode(11, -L, -L, 0.0)
            walls.CreateNewNode(12, L, -L, 0.0)
            walls.CreateNewNode(13, L, L, 0.0)
            walls.CreateNewNode(14, -L, L, 0.0)
            walls.CreateNewCondition("RigidFace3D3N", 1, [11, 12, 13], wall_props)
            walls.CreateNewCondition("RigidFace3D3N", 2, [11, 13, 14], wall_props)
        self.model_parts_have_been_read = True
        self.all_model_parts.ComputeMaxIds()

    def SetMaterials(self):
        pass  # assigned in ReadModelParts

    def SetInitialNodalValues(self):
        super().SetInitialNodalValues()
        n1 = self.e1.GetNode(0)
        if SCENE == "ball_ball":
            n1.SetSolutionStepValue(KM.VELOCITY_X, V1)
            self.e2.GetNode(0).SetSolutionStepValue(KM.VELOCITY_X, V2)
        else:
            n1.SetSolutionStepValue(KM.VELOCITY_Z, -V1)


def gap_and_speed(stage):
    """Overlap and approach speed (positive while the bodies close) of the current state."""
    n1 = stage.e1.GetNode(0)
    if SCENE == "ball_ball":
        n2 = stage.e2.GetNode(0)
        overlap = (R1 + R2) - (n2.X - n1.X)
        speed = n1.GetSolutionStepValue(KM.VELOCITY_X) - n2.GetSolutionStepValue(KM.VELOCITY_X)
    else:
        overlap = R1 - n1.Z
        speed = -n1.GetSolutionStepValue(KM.VELOCITY_Z)
    return overlap, speed


def normal_force(stage):
    """The contact force on the moving sphere along the line of approach, repulsive positive."""
    f = stage.e1.GetNode(0).GetSolutionStepValue(KM.TOTAL_FORCES)
    return -f[0] if SCENE == "ball_ball" else f[2]


if SCHEME not in SCHEMES:
    raise SystemExit("unsupported translational scheme %r" % SCHEME)
print("MILLIMPACT version=%s dem=%s threads=%d" % (
    version("KratosMultiphysics"), version("KratosDEMApplication"), KM.ParallelUtilities.GetNumThreads()))
parameters = KM.Parameters(PARAMETERS)
parameters["MaxTimeStep"].SetDouble(DT)
parameters["FinalTime"].SetDouble(DT * STEPS)
stage = Impact(KM.Model(), parameters)
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

solver = stage._GetSolver()
strategy = solver.cplusplus_strategy
walls = stage.rigid_face_model_part
mesh_mover = solver.dem_fem_utils
rows = []
# impact.py's loop and rows (Symplectic_Euler): the state the law saw in a step and the force it
# computed from it.
start = time.perf_counter()
for _ in range(STEPS):
    t = stage.time
    overlap, speed = gap_and_speed(stage)
    stage.time = solver.AdvanceInTime(t)
    mesh_mover.MoveAllMeshes(walls, stage.time, DT)
    strategy.ResetPrescribedMotionFlagsRespectingImposedDofs()
    strategy.InitializeSolutionStep()
    strategy.SolveSolutionStep()
    strategy.FinalizeSolutionStep()
    rows.append((len(rows), t, overlap, speed, normal_force(stage)))
loop_time = time.perf_counter() - start

overlap, speed = gap_and_speed(stage)
with open("trajectory.csv", "w") as out:
    out.write("iter,time,overlap,approach_velocity,normal_force\n")
    for r in rows:
        out.write("%d,%r,%r,%r,%r\n" % r)
    # The state after the last step; its force is known only out of contact (zero).
    if overlap <= 0.0:
        out.write("%d,%r,%r,%r,%r\n" % (len(rows), stage.time, overlap, speed, 0.0))
print("MILLIMPACT iterations=%d dt=%r" % (STEPS, DT))
print("MILLIMPACT loop_time=%r" % loop_time)
