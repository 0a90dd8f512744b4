#!/usr/bin/env python3
"""Write the held-out drum's meshes as ASCII STL files, in metres:

    meshes/shell.stl   the cylindrical shell with six lifter bars (the liner)
    meshes/caps.stl    the two end caps (feed and discharge ends)

    python3 tests/data/mill/heldout/make_meshes.py           # writes both files
    python3 tests/data/mill/heldout/make_meshes.py --check   # exits 1 if a shipped file differs

The drum turns about the x axis through the origin (gravity is -z in in.drum). Its shell and
caps are separate meshes, as a liner and the end plates are in a mill model, each turned by its
own fix move/mesh. Python 3 standard library only; the output is byte-for-byte reproducible
(coordinates written to 9 digits).
"""

import math
import pathlib
import sys

DIAMETER = 0.14  # inside the liner, m
LENGTH = 0.05  # between the end caps, m
FACETS_AROUND = 60  # shell facets around the axis
LIFTERS = 6  # bars along the shell, evenly spaced
LIFTER_HEIGHT = 0.006  # how far a bar stands in from the shell, m
LIFTER_BASE = 0.010  # its width at the shell, m
LIFTER_TOP = 0.006  # its width at its face (a trapezoidal bar), m

HERE = pathlib.Path(__file__).resolve().parent
SHELL = HERE / "meshes" / "shell.stl"
CAPS = HERE / "meshes" / "caps.stl"


def at(radius, angle, x):
    """A point `radius` from the x axis at `angle` (rad, from +y toward +z), `x` along it."""
    return (x, radius * math.cos(angle), radius * math.sin(angle))


def quad(a, b, c, d):
    """The quadrilateral a b c d as two triangles."""
    return [(a, b, c), (a, c, d)]


def shell():
    radius = DIAMETER / 2
    x0, x1 = -LENGTH / 2, LENGTH / 2
    triangles = []
    for k in range(FACETS_AROUND):
        t0 = 2 * math.pi * k / FACETS_AROUND
        t1 = 2 * math.pi * (k + 1) / FACETS_AROUND
        triangles += quad(at(radius, t0, x0), at(radius, t0, x1), at(radius, t1, x1), at(radius, t1, x0))
    inner = radius - LIFTER_HEIGHT
    for k in range(LIFTERS):
        # Bars between shell vertices, so that each bar's base lies on the shell's facets.
        centre = 2 * math.pi * (k + 0.5) / LIFTERS
        base = LIFTER_BASE / 2 / radius
        top = LIFTER_TOP / 2 / inner
        a, b = centre - base, centre + base
        c, d = centre - top, centre + top
        # Two sloping flanks and the face; the bar's ends lie on the caps.
        triangles += quad(at(radius, a, x0), at(inner, c, x0), at(inner, c, x1), at(radius, a, x1))
        triangles += quad(at(inner, c, x0), at(inner, d, x0), at(inner, d, x1), at(inner, c, x1))
        triangles += quad(at(inner, d, x0), at(radius, b, x0), at(radius, b, x1), at(inner, d, x1))
    return triangles


def caps():
    radius = DIAMETER / 2
    triangles = []
    for x in (-LENGTH / 2, LENGTH / 2):
        centre = (x, 0.0, 0.0)
        for k in range(FACETS_AROUND):
            t0 = 2 * math.pi * k / FACETS_AROUND
            t1 = 2 * math.pi * (k + 1) / FACETS_AROUND
            triangles.append((centre, at(radius, t0, x), at(radius, t1, x)))
    return triangles


def normal(triangle):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = triangle
    ux, uy, uz = bx - ax, by - ay, bz - az
    vx, vy, vz = cx - ax, cy - ay, cz - az
    n = (uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx)
    size = math.sqrt(sum(c * c for c in n))
    return tuple(c / size for c in n)


def number(x):
    text = f"{x:.9e}"
    # One spelling of zero, whatever the sign rounding left.
    return "0.000000000e+00" if text.lstrip("-") == "0.000000000e+00" else text


def stl(name, triangles):
    lines = [f"solid {name}"]
    for t in triangles:
        lines.append("  facet normal " + " ".join(number(c) for c in normal(t)))
        lines.append("    outer loop")
        for p in t:
            lines.append("      vertex " + " ".join(number(c) for c in p))
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append(f"endsolid {name}")
    return "\n".join(lines) + "\n"


def main():
    files = {SHELL: stl("shell", shell()), CAPS: stl("caps", caps())}
    if "--check" in sys.argv[1:]:
        stale = [path for path, text in files.items() if not path.is_file() or path.read_text() != text]
        for path in stale:
            print(f"{path} differs from what make_meshes.py writes: run it again", file=sys.stderr)
        return 1 if stale else 0
    for path, text in files.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
