"""Regenerate the committed half-space meshes from meshes/half_space.geo with gmsh.

Usage: python make_meshes.py [--out DIR] [--levels N]   (normally run by scripts/make_meshes.sh,
which installs gmsh from PyPI into a local virtual environment first).

Families: one per contact geometry (disk for the flat and concave punches, annuli at b/a = 0.5 and
0.9 for the flat annulus), each in refinement levels L = 0, 1, ...: all mesh sizes (hmin, hline
and the grading) are halved from one level to the next, so the family is a uniform refinement of
one size function (per-level factors below).
"""

import argparse
import os
import sys

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))
GEO = os.path.join(HERE, "..", "meshes", "half_space.geo")

# Level-0 sizes (units of a). Domain radius R = 1e5 a: truncation stiffens the force by about
# 1.2 a/R = 1.2e-5, and the graded far field costs only a few dozen element layers.
BASE = {"R": 1e5, "hmin": 1e-3, "hline": 4e-2, "grading": 0.4}

# Per-level factors. The force error of the element at the rim singularity is proportional to its
# size, so hmin shrinks faster than the rest; the graded layers it adds cost O(log) elements. The
# free inner edge of a concave punch converges more slowly than the force (the force is stationary
# in b), at about 0.01-0.06 of the contact-line element size, so hline shrinks faster too.
FACTOR = {"hmin": 0.25, "hline": 0.35, "grading": 0.5}
# The disk family carries the concave punches, whose free edge can sit anywhere on [0, a].
DISK_HLINE_FACTOR = 0.25

FAMILIES = {
    "disk": 0.0,
    "annulus-0.5": 0.5,
    "annulus-0.9": 0.9,
}


def generate(path, b, level):
    params = dict(BASE, b=b)
    for key, factor in FACTOR.items():
        if key == "hline" and b == 0.0:
            factor = DISK_HLINE_FACTOR
        params[key] = BASE[key] * factor ** level
    args = ["gmsh", "-v", "2"]
    for key, value in params.items():
        args += ["-setnumber", key, repr(value)]
    gmsh.initialize(args)
    try:
        gmsh.open(GEO)
        gmsh.model.mesh.generate(2)
        gmsh.write(path)
        types, tags, _ = gmsh.model.mesh.getElements(2)
        count = sum(len(t) for t in tags)
    finally:
        gmsh.finalize()
    return count


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(HERE, "..", "meshes"))
    parser.add_argument("--levels", type=int, default=4,
                        help="levels L0..L(N-1) per family (L0-L2 are committed; L3 is generated)")
    parser.add_argument("--b", type=float, action="append", default=[],
                        help="also make the family annulus-B for a flat annulus with b/a = B")
    parser.add_argument("--missing-only", action="store_true",
                        help="only write files that do not exist (keeps committed meshes intact)")
    args = parser.parse_args()
    families = dict(FAMILIES)
    for b in args.b:
        if not 0.0 < b < 1.0:
            parser.error(f"--b {b}: need 0 < b/a < 1")
        families[f"annulus-{b}"] = b
    for family, b in families.items():
        for level in range(args.levels):
            path = os.path.join(args.out, f"{family}-L{level}.msh")
            if args.missing_only and os.path.exists(path):
                continue
            count = generate(path, b, level)
            print(f"{os.path.relpath(path)}: {count} triangles")
    return 0


if __name__ == "__main__":
    sys.exit(main())
