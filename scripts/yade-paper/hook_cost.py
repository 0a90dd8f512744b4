# The cost of the paper's law as a YADE hook: the book's hook (docs/src/paper-law-in-dem.md,
# "The same law in YADE", read from the page itself) on 1 and on N spheres resting on the plane
# z = 0, 20,000 steps each, against the same scene without the hook.
#
#   cd scripts/yade-paper && yade -j1 -n -x hook_cost.py 100
import os
import sys
import time
from math import sqrt

PAGE = os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), "..", "..", "docs", "src", "paper-law-in-dem.md")
MARKER = "<!-- yade-paper hook: run by tests/yade_paper_driver.rs -->"
page = open(PAGE).read()
block = page[page.index(MARKER):]
start = block.index("```python\n") + len("```python\n")
exec(block[start:block.index("```", start)])

STEPS = 20000
R, E, NU, RHO = 0.005, 2.0e11, 0.3, 7800.0
C = 4.0 / 3.0 * (1.0 / (2.0 * (1.0 - NU**2) / E)) * sqrt(R)
many = int(sys.argv[-1]) if sys.argv[-1].isdigit() else 100


def per_step(count, hooked):
    """Seconds per step of `count` spheres, with or without the hook."""
    O.reset()
    del PAPER_CONTACTS[:]
    for i in range(count):
        b = O.bodies.append(sphere((3.0 * R * i, 0.0, R), R, material=FrictMat(young=E, poisson=NU, density=RHO)))
        PAPER_CONTACTS.append((b, C, 1.5, 0.35))
    hook = [PyRunner(iterPeriod=1, command="paper_hook()")] if hooked else []
    O.engines = [ForceResetter()] + hook + [NewtonIntegrator(damping=0.0, gravity=(0.0, 0.0, -9.81))]
    O.dt = 1e-7
    t = time.perf_counter()
    O.run(STEPS, True)
    return (time.perf_counter() - t) / STEPS


for count in (1, many):
    base, hooked = per_step(count, False), per_step(count, True)
    print("hook_cost contacts=%d without=%.2f us/step with=%.2f us/step hook=%.2f us/step (%.2f us per contact)"
          % (count, base * 1e6, hooked * 1e6, (hooked - base) * 1e6, (hooked - base) * 1e6 / count))
