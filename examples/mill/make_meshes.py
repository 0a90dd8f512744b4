#!/usr/bin/env python3
"""Write the example mill's drum as an ASCII STL: a cylindrical shell with both end caps and
four lifter bars, all one rotating mesh, in metres.

    python3 examples/mill/make_meshes.py            # writes examples/mill/meshes/drum.stl
    python3 examples/mill/make_meshes.py --check    # exits 1 if the shipped file differs

The drum's axis is the y axis through the origin (gravity is -z in in.mill). Python 3 standard
library only; the output is byte-for-byte reproducible (coordinates written to 9 digits).
"""

import math
import pathlib
import sys

RADIUS = 0.07  # inner radius of the shell, m (a 0.14 m lab drum)
LENGTH = 0.05  # between the end caps, m
SEGMENTS = 48  # facets around the shell
LIFTERS = 4  # bars along the shell, evenly spaced
LIFTER_HEIGHT = 0.008  # how far a bar stands in from the shell, m
LIFTER_WIDTH = 0.006  # its width along the shell, m

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "meshes" / "drum.stl"


def ring(radius, angle, y):
    """A point at `angle` (rad) around the axis, `radius` from it, at `y` along it."""
    return (radius * math.cos(angle), y, radius * math.sin(angle))


def quad(a, b, c, d):
    """Two triangles of the quadrilateral a b c d."""
    return [(a, b, c), (a, c, d)]


def shell():
    triangles = []
    y0, y1 = -LENGTH / 2, LENGTH / 2
    for k in range(SEGMENTS):
        t0 = 2 * math.pi * k / SEGMENTS
        t1 = 2 * math.pi * (k + 1) / SEGMENTS
        triangles += quad(ring(RADIUS, t0, y0), ring(RADIUS, t1, y0),
                          ring(RADIUS, t1, y1), ring(RADIUS, t0, y1))
        # The end caps as fans from the axis.
        triangles.append(((0.0, y0, 0.0), ring(RADIUS, t1, y0), ring(RADIUS, t0, y0)))
        triangles.append(((0.0, y1, 0.0), ring(RADIUS, t0, y1), ring(RADIUS, t1, y1)))
    return triangles


def lifters():
    triangles = []
    y0, y1 = -LENGTH / 2, LENGTH / 2
    inner = RADIUS - LIFTER_HEIGHT
    half = LIFTER_WIDTH / 2 / RADIUS  # half the bar's width as an angle at the shell
    for k in range(LIFTERS):
        centre = 2 * math.pi * k / LIFTERS + math.pi / LIFTERS
        a, b = centre - half, centre + half
        # Two flanks and the top face; the bar's ends lie on the caps.
        triangles += quad(ring(RADIUS, a, y0), ring(inner, a, y0), ring(inner, a, y1), ring(RADIUS, a, y1))
        triangles += quad(ring(inner, a, y0), ring(inner, b, y0), ring(inner, b, y1), ring(inner, a, y1))
        triangles += quad(ring(inner, b, y0), ring(RADIUS, b, y0), ring(RADIUS, b, y1), ring(inner, b, y1))
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
    return "0.000000000e+00" if text.startswith("-0.000000000") else text


def stl(triangles):
    lines = ["solid drum"]
    for t in triangles:
        lines.append("  facet normal " + " ".join(number(c) for c in normal(t)))
        lines.append("    outer loop")
        for p in t:
            lines.append("      vertex " + " ".join(number(c) for c in p))
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append("endsolid drum")
    return "\n".join(lines) + "\n"


def main():
    text = stl(shell() + lifters())
    if "--check" in sys.argv[1:]:
        if not OUT.is_file() or OUT.read_text() != text:
            print(f"{OUT} differs from what make_meshes.py writes: run it again", file=sys.stderr)
            return 1
        return 0
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
