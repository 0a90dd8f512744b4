#!/usr/bin/env python3
"""The discrete rule of `model paper` at dy/dt ~ 0, chosen by measurement: candidate rules stepped
as LIGGGHTS steps them (velocity Verlet, the force from the half-step velocity), in one
dimension, standard library only.

    python3 scripts/liggghts-paper/at_rest.py [cor|rest|chain|all]

Each rule gives the force C y^n (1 + eta s) from the approach rate v (> 0 approaching) and the
velocity change one step's force jump makes, band = 2 eta C y^n dt / m*:

  sign        s = sign(v)                                   (the model before)
  dead        s = 0 within |v| < band, else sign(v)          (the elastic force near rest)
  linear 1    s = clamp(2 v / band, -1, 1)                   (dissipative force m* v / dt: stops
                                                              a lone contact's approach in one step)
  linear 1/2  s = clamp(v / band, -1, 1)                     (m* v / (2 dt): halves it; the model now)
  tanh 1/2    s = tanh(v / band)

cor:   the COR's largest error against sqrt((1-eta)/(1+eta)) over 16 start phases, at 250 to
       2000 steps per contact time (steel-like ball on a plate, n = 1.5), and its order.
rest:  a steel ball (R 5 mm) resting on a plate under gravity, eta = 0.3, dt = 1e-6 s, 0.05 s,
       and a column of 5 on the plate: the range of the plate's force over the last 2000
       steps, relative to the weight, and the incline angle the smallest force holds at mu = 0.5
       (atan(mu F_min / m g); 26.57 degrees when the force is constant).
chain: 1 and 6 balls pressed between two walls (aligned contacts pulling one body: where a
       dissipative force scaled to one contact overshoots), random start velocities: kinetic
       energy after 50000 steps.
"""
import math
import random
import sys


def sign_rule(eta, v, band):
    return (v > 0) - (v < 0)


def dead_rule(eta, v, band):
    return 0.0 if abs(v) < band else float((v > 0) - (v < 0))


def linear(alpha):
    def rule(eta, v, band):
        if band == 0.0:
            return float((v > 0) - (v < 0))
        return max(-1.0, min(1.0, 2.0 * alpha * v / band))
    return rule


def smooth(alpha):
    def rule(eta, v, band):
        if band == 0.0:
            return float((v > 0) - (v < 0))
        return math.tanh(2.0 * alpha * v / band)
    return rule


RULES = {
    "sign": sign_rule,
    "dead": dead_rule,
    "linear 1": linear(1.0),
    "linear 1/2": linear(0.5),
    "tanh 1/2": smooth(0.5),
}


def force(rule, stiffness, exponent, eta, y, v, dt, mass):
    if y <= 0.0:
        return 0.0
    elastic = stiffness * y ** exponent
    band = 2.0 * eta * elastic * dt / mass
    return elastic * (1.0 + eta * rule(eta, v, band))


def impact_cor(rule, stiffness, exponent, mass, eta, v0, dt, gap):
    y, v, f = -gap, v0, 0.0
    step = 0
    while True:
        step += 1
        half = v - 0.5 * dt * f / mass
        y += dt * half
        f = force(rule, stiffness, exponent, eta, y, half, dt, mass)
        v = half - 0.5 * dt * f / mass
        if y <= 0.0 and step > 10 and v < 0.0:
            return -v / v0


def cor_table():
    stiffness, exponent, mass, v0 = 2e10, 1.5, 0.26, 2.0
    counts = [250, 500, 1000, 2000]
    print("| eta | rule | " + " | ".join(f"{n} steps" for n in counts) + " | order |")
    print("|---|---|" + "---|" * (len(counts) + 1))
    for eta in [0.3, 0.7, 0.9]:
        exact = math.sqrt((1 - eta) / (1 + eta))
        peak = ((exponent + 1) * mass * v0 * v0 / (2 * stiffness * (1 + eta))) ** (1 / (exponent + 1))
        contact = 1.4716 * peak / v0 * (1 + 1 / exact)
        for name, rule in RULES.items():
            worst = []
            for n in counts:
                dt = contact / n
                worst.append(max(abs(impact_cor(rule, stiffness, exponent, mass, eta, v0, dt,
                                                k / 16 * v0 * dt) - exact) for k in range(16)))
            order = math.log2(worst[-2] / worst[-1])
            print(f"| {eta} | {name} | " + " | ".join(f"{w:.2e}" for w in worst) + f" | {order:.2f} |",
                  flush=True)


STEEL_MASS = 7800 * 4 / 3 * math.pi * 0.005 ** 3
WALL_STIFFNESS = 4 / 3 * 2e11 / (2 * (1 - 0.09)) * math.sqrt(0.005)
PAIR_STIFFNESS = 4 / 3 * 2e11 / (2 * (1 - 0.09)) * math.sqrt(0.0025)


def column(rule, eta, count, dt, steps, gravity=9.81):
    """count balls stacked on a plate, dropped from 0.1 mm gaps; the plate's force over the
    last 2000 steps."""
    m, r = STEEL_MASS, 0.005
    z = [r + i * 2 * r + 1e-4 * (i + 1) for i in range(count)]
    v = [0.0] * count

    def forces(z, vh):
        f = [-m * gravity] * count
        plate = force(rule, WALL_STIFFNESS, 1.5, eta, r - z[0], -vh[0], dt, m)
        f[0] += plate
        for i in range(count - 1):
            fp = force(rule, PAIR_STIFFNESS, 1.5, eta, 2 * r - (z[i + 1] - z[i]), vh[i] - vh[i + 1], dt, m / 2)
            f[i] -= fp
            f[i + 1] += fp
        return f, plate

    f, plate = forces(z, v)
    history = []
    for step in range(steps):
        vh = [v[i] + 0.5 * dt * f[i] / m for i in range(count)]
        z = [z[i] + dt * vh[i] for i in range(count)]
        f, plate = forces(z, vh)
        v = [vh[i] + 0.5 * dt * f[i] / m for i in range(count)]
        if step >= steps - 2000:
            history.append(plate)
    return history


def rest_table():
    eta, dt, steps = 0.3, 1e-6, 50000
    print("| rule | balls | plate force range / weight | holding angle at mu = 0.5 |")
    print("|---|---|---|---|")
    for count in [1, 5]:
        weight = count * STEEL_MASS * 9.81
        for name, rule in RULES.items():
            h = column(rule, eta, count, dt, steps)
            angle = math.degrees(math.atan(0.5 * min(h) / weight))
            print(f"| {name} | {count} | {(max(h) - min(h)) / weight:.2e} | {angle:.2f} |", flush=True)


def chain(rule, eta, count, dt, steps, squeeze=1e-7):
    m, r = STEEL_MASS, 0.005
    random.seed(1)
    top = 2 * r * count - squeeze * (count + 1)
    z = [r - squeeze + i * (2 * r - squeeze) for i in range(count)]
    v = [random.uniform(-1e-3, 1e-3) for _ in range(count)]

    def forces(z, vh):
        f = [0.0] * count
        f[0] += force(rule, WALL_STIFFNESS, 1.5, eta, r - z[0], -vh[0], dt, m)
        f[-1] -= force(rule, WALL_STIFFNESS, 1.5, eta, z[-1] + r - top, vh[-1], dt, m)
        for i in range(count - 1):
            fp = force(rule, PAIR_STIFFNESS, 1.5, eta, 2 * r - (z[i + 1] - z[i]), vh[i] - vh[i + 1], dt, m / 2)
            f[i] -= fp
            f[i + 1] += fp
        return f

    f = forces(z, v)
    for _ in range(steps):
        vh = [v[i] + 0.5 * dt * f[i] / m for i in range(count)]
        z = [z[i] + dt * vh[i] for i in range(count)]
        f = forces(z, vh)
        v = [vh[i] + 0.5 * dt * f[i] / m for i in range(count)]
    return sum(0.5 * m * x * x for x in v)


def chain_table():
    print("| rule | balls between two walls | kinetic energy after 50000 steps (J) |")
    print("|---|---|---|")
    for count in [1, 6]:
        for name, rule in RULES.items():
            print(f"| {name} | {count} | {chain(rule, 0.3, count, 1e-6, 50000):.1e} |", flush=True)


if __name__ == "__main__":
    which = sys.argv[1] if len(sys.argv) > 1 else "all"
    if which not in ("cor", "rest", "chain", "all"):
        sys.exit(f"at_rest.py: unknown table {which!r}; allowed: cor, rest, chain, all")
    for name, table in [("rest", rest_table), ("chain", chain_table), ("cor", cor_table)]:
        if which in (name, "all"):
            table()
            print()
