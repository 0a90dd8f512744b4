
# The paper's law, F = C y^n (1 + eta sign ydot), added by a PyRunner between ForceResetter and
# NewtonIntegrator: YADE's laws are compiled C++ and its Debian build ships no headers, so the
# law runs as Python once per step (a validation build, not a production one). There is no
# collider and no InteractionLoop: YADE's own contact laws never see the bodies, and the hook's
# force is the only one. It reads each body's position x_i and the velocity v_{i-1/2} of the
# previous half step (what a compiled law sees in YADE's leap-frog), adds F with O.forces.addF,
# and NewtonIntegrator kicks and drifts with it.
print("MILLIMPACT version=" + str(yade.config.version))


def paper_force(overlap, rate, stiffness, exponent, eta, mass, dt):
    """The paper's force, N (repulsive positive), at `overlap` (m) and approach `rate` (m/s) in a
    step of `dt` (s): sign(rate) outside the band 2 eta C y^n dt / mass that one step's jump
    between the branches spans, rate / band inside it, so that a contact at rest carries its
    elastic force instead of alternating between C y^n (1 +- eta). Never attractive."""
    if overlap <= 0.0:
        return 0.0
    elastic = stiffness * overlap ** exponent
    band = 2.0 * eta * elastic * dt / mass
    if rate >= band:
        branch = 1.0 + eta
    elif rate <= -band:
        branch = 1.0 - eta
    else:
        branch = 1.0 + eta * (rate / band)
    return elastic * branch


def build(p):
    """Impact p: sphere 1 moving along +axis onto sphere 2 (ball_ball, along x) or onto the plane
    z = 0 (ball_plate, rod_end: the sphere below it), touching at t = 0, rotations blocked."""
    ball_ball = p["scene"] == "ball_ball"
    r1 = p["radius"]
    mat = FrictMat(young=p["young"], poisson=p["poisson"], frictionAngle=0.0, density=p["density"])
    O.materials.append(mat)
    if ball_ball:
        axis, reach = 0, r1 + p["other_radius"]
        b1 = O.bodies.append(utils.sphere((0.0, 0.0, 0.0), r1, material=mat))
        b2 = O.bodies.append(utils.sphere((reach, 0.0, 0.0), p["other_radius"], material=mat))
        O.bodies[b2].state.mass = p["other_mass"]
        O.bodies[b2].state.vel = Vector3(p["other_velocity"], 0.0, 0.0)
        O.bodies[b2].state.blockedDOFs = "XYZ"
    else:
        axis, reach, b2 = 2, r1, None
        b1 = O.bodies.append(utils.sphere((0.0, 0.0, -r1), r1, material=mat))
    O.bodies[b1].state.mass = p["mass"]
    v = [0.0, 0.0, 0.0]
    v[axis] = p["velocity"]
    O.bodies[b1].state.vel = Vector3(*v)
    O.bodies[b1].state.blockedDOFs = "XYZ"
    return {
        "p": p, "b1": b1, "b2": b2, "axis": axis, "reach": reach, "rows": [],
        "s1": O.bodies[b1].state,
        "s2": O.bodies[b2].state if ball_ball else None,
        "law": (p["stiffness"], p["exponent"], p["loss_coefficient"], p["pair_mass"], p["timestep"]),
    }


def overlap_and_rate(c):
    axis, s1, s2 = c["axis"], c["s1"], c["s2"]
    if s2 is not None:
        return c["reach"] - (s2.pos[axis] - s1.pos[axis]), s1.vel[axis] - s2.vel[axis]
    return c["reach"] - (0.0 - s1.pos[axis]), s1.vel[axis]


current = []


def hook():
    """Each impact's force from its bodies' states, added to them; its row recorded."""
    k, t = O.iter, O.time
    for c in current:
        overlap, rate = overlap_and_rate(c)
        steps = c["p"]["steps"]
        if k > steps:
            continue
        if k == steps:
            if overlap <= 0.0:
                c["rows"].append((k, t, overlap, rate, 0.0))
            continue
        force = paper_force(overlap, rate, *c["law"])
        c["rows"].append((k, t, overlap, rate, force))
        if force != 0.0:
            f = [0.0, 0.0, 0.0]
            f[c["axis"]] = force
            O.forces.addF(c["b1"], -Vector3(*f))
            if c["b2"] is not None:
                O.forces.addF(c["b2"], Vector3(*f))


for group, files in zip(GROUPS, FILES):
    O.reset()
    current = [build(IMPACTS[i]) for i in group]
    O.engines = [
        ForceResetter(),
        # Not `updateGlobals`: each call would import IPython to refresh the script's names.
        PyRunner(iterPeriod=1, initRun=True, command="hook()", updateGlobals=False),
        NewtonIntegrator(damping=0.0, gravity=(0.0, 0.0, 0.0)),
    ]
    O.dt = IMPACTS[group[0]]["timestep"]
    steps = max(c["p"]["steps"] for c in current)
    # One more iteration than the longest impact: its hook records the state after the last
    # step (and adds no force: k == steps).
    start = time.perf_counter()
    for _ in range(steps + 1):
        O.step()
    loop_time = (time.perf_counter() - start) / len(group)
    for i, c, name in zip(group, current, files):
        with open(name, "w") as out:
            out.write("iter,time,overlap,approach_velocity,normal_force\n")
            for row in c["rows"]:
                out.write("%d,%r,%r,%r,%r\n" % row)
        print("MILLIMPACT impact=%d loop_time=%r" % (i + 1, loop_time))
