#!/usr/bin/env python3
"""Checks the LIGGGHTS build with the paper's model (scripts/build-liggghts-paper.sh) against the
paper's closed forms, and prints what it measured.

  python3 scripts/liggghts-paper/verify.py [--binary PATH] [--debian PATH] [--steps-per-contact N]

1. example.in runs and realises its expected COR.
2. model paper, eta = 0: the same trajectory, to the last printed digit, as the stock model hertz
   with coefficientRestitution 1 (the stiffness is formed exactly as hertz forms it).
3. Ball on plate (model paper, fix wall/gran), ball on ball (model paper, pair_style gran) and
   rod end on plate (model paper/linear) at eta = 0, 0.35, 0.7, 0.95, N steps over the paper's
   contact time: COR, peak overlap, contact time and peak force against the closed forms.
4. eta = 1.2 and eta = -0.1 stop both models with an error naming lossCoefficient, exit != 0.
5. With --debian: the stock model hertz deck runs the same in this build as in Debian's liggghts.

Exit status 1 when a check fails. Scenes are the project's cases/ball_plate.toml,
cases/ball_ball.toml and cases/rod_end.toml (their values are restated below).
"""

import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.join(ROOT, "scripts", "liggghts-paper")
V0 = 2.0  # impact speed, m/s (relative speed for ball on ball)

# cases/ball_plate.toml, cases/ball_ball.toml: 40 mm steel balls, steel plate
BALL = dict(radius=0.02, density=7800.0, E=2.0e11, nu=0.3)
# cases/rod_end.toml: 30 mm rod, 0.5 m long; a sphere of the rod's mass, as wide as the rod
ROD = dict(diameter=0.03, length=0.5, density=7800.0, E=2.0e11)

FAILURES = []


def check(ok, what):
    if not ok:
        FAILURES.append(what)
        print("FAILED: " + what)


def fmt(x):
    return repr(float(x))


def J(n):
    """J(n) = int_0^1 (1 - u^(n+1))^(-1/2) du."""
    a = 1.0 / (n + 1.0)
    return math.sqrt(math.pi) * math.gamma(1.0 + a) / math.gamma(0.5 + a)


def scene(kind):
    """(mass M, stiffness C, exponent n, sphere radius, sphere density) of a scene."""
    if kind == "rod_end":
        h = ROD["length"] / 2.0
        area = math.pi * ROD["diameter"] ** 2 / 4.0
        mass = ROD["density"] * area * ROD["length"]
        r = ROD["diameter"] / 2.0
        return mass, area * ROD["E"] / h, 1.0, r, mass / (4.0 / 3.0 * math.pi * r**3)
    r, rho = BALL["radius"], BALL["density"]
    m = 4.0 / 3.0 * math.pi * r**3 * rho
    # LIGGGHTS's createYeff: 1/((1-nu1^2)/E1 + (1-nu2^2)/E2)
    e_star = 1.0 / ((1.0 - BALL["nu"] ** 2) / BALL["E"] * 2.0)
    if kind == "ball_plate":
        return m, 4.0 / 3.0 * e_star * math.sqrt(r), 1.5, r, rho
    return m / 2.0, 4.0 / 3.0 * e_star * math.sqrt(r / 2.0), 1.5, r, rho


def paper_exact(kind, eta):
    m, c, n, _, _ = scene(kind)
    e = math.sqrt((1.0 - eta) / (1.0 + eta))
    y_max = ((n + 1.0) * m * V0**2 / (2.0 * c * (1.0 + eta))) ** (1.0 / (n + 1.0))
    return dict(
        cor=e,
        peak=y_max,
        contact_time=J(n) * y_max / V0 * (1.0 + 1.0 / e),
        peak_force=c * (1.0 + eta) * y_max**n,
    )


def deck(kind, model, eta, dt, steps, restitution=None):
    """One impact in the layout of the project's scripts/liggghts/impact.in."""
    m, c, n, r, rho = scene(kind)
    gap = max(1e-6 * V0 * dt, 1e-13 * r)
    half = 4.0 * r + V0 * dt * steps + gap
    pair = lambda name, v: (
        f"fix {name} all property/global {name} peratomtypepair 2 {v} {v} {v} {v}"
    )
    props = []
    if model == "paper/linear":
        props += [pair("kn", fmt(c)), pair("kt", "0")]
    else:
        props += [
            f"fix youngsModulus all property/global youngsModulus peratomtype {fmt(BALL['E'])} {fmt(BALL['E'])}",
            f"fix poissonsRatio all property/global poissonsRatio peratomtype {fmt(BALL['nu'])} {fmt(BALL['nu'])}",
        ]
    if restitution is None:
        props.append(pair("lossCoefficient", fmt(eta)))
    else:
        props.append(pair("coefficientRestitution", fmt(restitution)))
    props.append(pair("coefficientFriction", "0"))
    settings = "" if restitution is None else "tangential_damping off limitForce off"
    if kind == "ball_ball":
        wall = "# no wall: the second ball is atom 2"
        atoms = (
            f"create_atoms 1 single 0 0 {fmt(r + gap)} units box\n"
            f"set atom 1 diameter {fmt(2 * r)} density {fmt(rho)} vz {fmt(-V0 / 2)}\n"
            f"create_atoms 2 single 0 0 {fmt(-r)} units box\n"
            f"set atom 2 diameter {fmt(2 * r)} density {fmt(rho)} vz {fmt(V0 / 2)}"
        )
        overlap, approach = f"{fmt(2 * r)}-(z[1]-z[2])", "vz[2]-vz[1]"
    else:
        wall = f"fix plate all wall/gran model {model} tangential no_history primitive type 2 zplane 0.0 {settings}"
        atoms = (
            f"create_atoms 1 single 0 0 {fmt(r + gap)} units box\n"
            f"set atom 1 diameter {fmt(2 * r)} density {fmt(rho)} vz {fmt(-V0)}"
        )
        overlap, approach = f"{fmt(r)}-z[1]", "-vz[1]"
    props_text = "\n".join(props)
    return f"""units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
hard_particles yes
region domain block {-half} {half} {-half} {half} {-half} {half} units box
create_box 2 domain
neighbor {fmt(r)} bin
neigh_modify delay 0
{props_text}
pair_style gran model {model} tangential no_history {settings}
pair_coeff * *
{wall}
timestep {fmt(dt)}
{atoms}
fix integrate all nve/sphere
variable t equal time
variable overlap equal {overlap}
variable approach equal {approach}
variable force equal fz[1]
print "${{t}} ${{overlap}} ${{approach}} ${{force}}" file traj.txt screen no
fix trajectory all print 1 "${{t}} ${{overlap}} ${{approach}} ${{force}}" append traj.txt screen no title none
thermo {steps}
run {steps}
"""


def run(binary, text, workdir):
    with open(os.path.join(workdir, "in.lmp"), "w") as f:
        f.write(text)
    start = time.perf_counter()
    p = subprocess.run(
        [binary, "-in", "in.lmp", "-log", "none", "-echo", "none"],
        cwd=workdir,
        capture_output=True,
        text=True,
        errors="replace",
    )
    wall = time.perf_counter() - start
    return p.returncode, p.stdout + p.stderr, wall


def measure(workdir, dt):
    """COR, peak overlap, contact time (by overlap, zero crossings interpolated), peak force."""
    rows = []
    with open(os.path.join(workdir, "traj.txt")) as f:
        for line in f:
            w = line.split()
            if len(w) == 4:
                rows.append([float(x) for x in w])
    t = [r[0] for r in rows]
    y = [r[1] for r in rows]
    v_in, v_out = rows[0][2], rows[-1][2]
    first = next(i for i, v in enumerate(y) if v > 0)
    last = next(i for i in range(first, len(y)) if y[i] <= 0)
    cross = lambda i: t[i - 1] + (t[i] - t[i - 1]) * y[i - 1] / (y[i - 1] - y[i])
    return dict(
        cor=-v_out / v_in,
        peak=max(y),
        contact_time=cross(last) - cross(first),
        peak_force=max(abs(r[3]) for r in rows),
        steps_in_contact=last - first,
    ), rows


def loop_time(log):
    m = re.search(r"Loop time of ([0-9.eE+-]+)", log)
    return float(m.group(1)) if m else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument(
        "--binary",
        default=os.path.join(
            os.environ.get("MILLIMPACT_CODES_DIR", os.path.join(ROOT, ".codes")),
            "liggghts-paper", "bin", "liggghts-paper",
        ),
    )
    ap.add_argument("--debian", help="Debian's liggghts, to compare a stock hertz run with")
    ap.add_argument("--steps-per-contact", type=int, default=1000)
    args = ap.parse_args()
    binary = args.binary
    spc = args.steps_per_contact

    # 1. the shipped example
    with tempfile.TemporaryDirectory() as d:
        code, log, wall = run(binary, open(os.path.join(HERE, "example.in")).read(), d)
        m = re.search(r"^COR (\S+) (\S+)", log, re.M)
        check(code == 0 and m is not None, "example.in runs and prints COR")
        if m:
            cor, want = float(m.group(1)), float(m.group(2))
            print(f"example.in: COR {cor:.15g}, paper {want:.15g}, offset {cor - want:+.2e}, "
                  f"wall {wall * 1e3:.0f} ms")
            check(abs(cor - want) < 1e-4, "example.in COR within 1e-4")

    # 2. eta = 0 against stock hertz, e = 1
    for kind in ("ball_plate", "ball_ball"):
        ex = paper_exact(kind, 0.0)
        dt = ex["contact_time"] / spc
        steps = int(1.1 * spc) + 10
        with tempfile.TemporaryDirectory() as d1, tempfile.TemporaryDirectory() as d2:
            c1, _, _ = run(binary, deck(kind, "paper", 0.0, dt, steps), d1)
            c2, _, _ = run(binary, deck(kind, "hertz", 0.0, dt, steps, restitution=1.0), d2)
            same = c1 == 0 and c2 == 0 and open(os.path.join(d1, "traj.txt")).read() == open(
                os.path.join(d2, "traj.txt")).read()
            print(f"{kind}: model paper eta=0 vs model hertz e=1, trajectories identical: {same}")
            check(same, f"{kind}: paper eta=0 == hertz e=1")

    # 3. the law at four eta
    print()
    print(f"{spc} steps over the paper's contact time; offsets are realised - exact "
          "(COR absolute, the others relative)")
    print("| scene | model | eta | dt (s) | COR | exact COR | COR offset | peak overlap | "
          "contact time | peak force | wall (ms) | loop (ms) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for kind, model in (("ball_plate", "paper"), ("ball_ball", "paper"), ("rod_end", "paper/linear")):
        for eta in (0.0, 0.35, 0.7, 0.95):
            ex = paper_exact(kind, eta)
            dt = ex["contact_time"] / spc
            steps = int(1.1 * spc) + 10
            with tempfile.TemporaryDirectory() as d:
                code, log, wall = run(binary, deck(kind, model, eta, dt, steps), d)
                check(code == 0, f"{kind} eta={eta} runs")
                if code != 0:
                    print(log[-2000:])
                    continue
                got, _ = measure(d, dt)
            rel = lambda q: (got[q] - ex[q]) / ex[q]
            off = got["cor"] - ex["cor"]
            print(f"| {kind} | {model} | {eta} | {dt:.4e} | {got['cor']:.12f} | {ex['cor']:.12f} | "
                  f"{off:+.2e} | {rel('peak'):+.1e} | {rel('contact_time'):+.1e} | "
                  f"{rel('peak_force'):+.1e} | {wall * 1e3:.0f} | {loop_time(log) * 1e3:.1f} |")
            # The force jumps at the turning point; velocity Verlet sees the half-step velocity:
            # an O(dt) error, a few 1e-3 at most at 1000 steps per contact.
            check(abs(off) < 10.0 / spc, f"{kind} eta={eta}: |COR offset| < {10.0 / spc:g}")
            check(abs(rel("peak")) < 10.0 / spc, f"{kind} eta={eta}: peak overlap")

    # 4. refusals
    print()
    for model, kind in (("paper", "ball_plate"), ("paper/linear", "rod_end")):
        for eta in (1.2, -0.1):
            with tempfile.TemporaryDirectory() as d:
                code, log, _ = run(binary, deck(kind, model, eta, 1e-7, 10), d)
            err = next((l for l in log.splitlines() if l.startswith("ERROR")), "(no ERROR line)")
            print(f"model {model}, eta={eta}: exit {code}: {err}")
            check(code != 0 and "lossCoefficient" in err and "0 <= lossCoefficient < 1" in err,
                  f"model {model} eta={eta} refused")

    # 5. the stock deck in both builds
    if args.debian:
        print()
        for kind in ("ball_plate", "ball_ball"):
            ex = paper_exact(kind, 0.35)
            dt = ex["contact_time"] / spc
            steps = int(1.1 * spc) + 10
            cors = []
            for b in (binary, args.debian):
                with tempfile.TemporaryDirectory() as d:
                    code, log, wall = run(b, deck(kind, "hertz", 0.0, dt, steps, restitution=ex["cor"]), d)
                    got, _ = measure(d, dt)
                    cors.append(got["cor"])
                    print(f"{kind}, model hertz e={ex['cor']:.15g}: {os.path.basename(b)} COR "
                          f"{got['cor']:.15g}, wall {wall * 1e3:.0f} ms")
            check(cors[0] == cors[1], f"{kind}: stock hertz identical in both builds")

    print()
    print("all checks passed" if not FAILURES else f"{len(FAILURES)} checks failed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
