
print("MILLIMPACT version=" + str(yade.config.version))


def build(slot, p):
    """Impact p as its single script builds it, moved SPACING * slot across, with its own mask bit."""
    ball_ball = p["scene"] == "ball_ball"
    if p["scene"] == "rod_end":
        kn, cn, rho = 2.0 * p["linear_stiffness"], 2.0 * p["linear_damping"], p["density"]
        mat1 = ViscElMat(kn=kn, cn=cn, ks=0.0, cs=0.0, frictionAngle=0.0, density=rho)
        mat2 = ViscElMat(kn=kn, cn=cn, ks=0.0, cs=0.0, frictionAngle=0.0, density=rho)
    else:
        mat1 = FrictMat(young=p["young"], poisson=p["poisson"], frictionAngle=0.0, density=p["density"])
        if ball_ball:
            mat2 = FrictMat(young=p["other_young"], poisson=p["other_poisson"], frictionAngle=0.0, density=p["other_density"])
        else:
            mat2 = FrictMat(young=p["wall_young"], poisson=p["wall_poisson"], frictionAngle=0.0, density=p["density"])
    m1 = O.materials.append(mat1)
    m2 = O.materials.append(mat2)
    r1, y = p["radius"], SPACING * slot
    if ball_ball:
        axis = 0
        r2 = p["other_radius"]
        b1 = O.bodies.append(utils.sphere((0.0, y, 0.0), r1, material=mat1))
        b2 = O.bodies.append(utils.sphere((math.nextafter(r1 + r2, math.inf), y, 0.0), r2, material=mat2))
        O.bodies[b2].state.mass = p["other_mass"]
        O.bodies[b2].state.vel = Vector3(p["other_velocity"], 0.0, 0.0)
        O.bodies[b2].state.blockedDOFs = "XYZ"
    else:
        axis = 2
        b1 = O.bodies.append(utils.sphere((0.0, y, math.nextafter(-r1, -math.inf)), r1, material=mat1))
        b2 = O.bodies.append(utils.wall(0.0, axis=2, sense=0, material=mat2))
    O.bodies[b1].state.mass = p["mass"]
    v = [0.0, 0.0, 0.0]
    v[axis] = p["velocity"]
    O.bodies[b1].state.vel = Vector3(*v)
    O.bodies[b1].state.blockedDOFs = "XYZ"
    O.bodies[b1].mask = 1 << slot
    O.bodies[b2].mask = 1 << slot
    # Looked up once, not every step: the bodies' states (their fields read live), and the sum
    # of radii the overlap is measured from (the same sum the single script forms).
    return {
        "p": p, "m1": m1, "m2": m2, "b1": b1, "b2": b2, "axis": axis, "rows": [],
        "steps": p["steps"],
        "s1": O.bodies[b1].state,
        "s2": O.bodies[b2].state if ball_ball else None,
        "reach": (p["radius"] + p["other_radius"]) if ball_ball else p["radius"],
    }


def gap_and_speed(c):
    axis, s1, s2 = c["axis"], c["s1"], c["s2"]
    p1 = s1.pos[axis]
    u1 = s1.vel[axis]
    if s2 is not None:
        p2 = s2.pos[axis]
        u2 = s2.vel[axis]
        return c["reach"] - (p2 - p1), u1 - u2
    return c["reach"] - (0.0 - p1), u1


current = []


def record():
    k, t, force_on = O.iter, O.time, O.forces.f
    for c in current:
        steps = c["steps"]
        if k < steps:
            overlap, speed = gap_and_speed(c)
            force = -force_on(c["b1"], sync=True)[c["axis"]]
            c["rows"].append((k, t, overlap, speed, force))
        elif k == steps:
            overlap, speed = gap_and_speed(c)
            if overlap <= 0.0:
                c["rows"].append((k, t, overlap, speed, 0.0))


for group in GROUPS:
    O.reset()
    current = [build(slot, IMPACTS[i]) for slot, i in enumerate(group)]
    if IMPACTS[group[0]]["scene"] == "rod_end":
        phys_functor = Ip2_ViscElMat_ViscElMat_ViscElPhys()
        law_functor = Law2_ScGeom_ViscElPhys_Basic()
    else:
        en = MatchMaker(matches=[(c["m1"], c["m2"], c["p"]["restitution"]) for c in current])
        phys_functor = Ip2_FrictMat_FrictMat_MindlinPhys(en=en)
        law_functor = Law2_ScGeom_MindlinPhys_Mindlin()
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
        InteractionLoop(
            [Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(hertzian=True)],
            [phys_functor],
            [law_functor],
        ),
        # Not `updateGlobals`: each call would import IPython to refresh the script's names,
        # which `record` does not need.
        PyRunner(iterPeriod=1, initRun=True, command="record()", updateGlobals=False),
        NewtonIntegrator(damping=0.0, gravity=(0.0, 0.0, 0.0)),
    ]
    O.dt = IMPACTS[group[0]]["timestep"]
    steps = max(c["p"]["steps"] for c in current)
    start = time.perf_counter()
    for _ in range(steps):
        O.step()
    loop_time = (time.perf_counter() - start) / len(group)
    for i, c in zip(group, current):
        if c["p"]["steps"] == steps:
            overlap, speed = gap_and_speed(c)
            if overlap <= 0.0:
                c["rows"].append((O.iter, O.time, overlap, speed, 0.0))
        with open("trajectory-%d.csv" % (i + 1), "w") as out:
            out.write("iter,time,overlap,approach_velocity,normal_force\n")
            for row in c["rows"]:
                out.write("%d,%r,%r,%r,%r\n" % row)
        print("MILLIMPACT impact=%d loop_time=%r" % (i + 1, loop_time))
