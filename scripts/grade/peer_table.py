#!/usr/bin/env python3
"""Stored peer results (verify/peers/<package>-*.json) as one CSV for `verify grade`, on
standard output: punch, its parameters, the depth the peer was given and the force it found.

    python3 scripts/grade/peer_table.py tamaas > verify/grade/tamaas.csv
    verify grade --results verify/grade/tamaas.csv --tol 0.01

The peers solve on a square grid, so their force differs from the converged reference by the
grid's discretisation error (about 1e-3 at 128 cells per side); the torus records' gap (1 - r)^2
is the torus of tube radius 0.5 (gap (r - a)^2 / (2 rho), a = 1).
"""

import glob
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    if len(sys.argv) != 2 or sys.argv[1] not in ("tamaas", "contactmechanics"):
        sys.exit("usage: python3 scripts/grade/peer_table.py tamaas|contactmechanics > FILE")
    package = sys.argv[1]
    files = sorted(glob.glob(os.path.join(ROOT, "verify", "peers", f"{package}-*.json")))
    if not files:
        sys.exit(f"no stored results verify/peers/{package}-*.json")
    out = sys.stdout
    out.write(f"# verify/peers/{package}-*.json as results to grade; scripts/grade/peer_table.py\n")
    out.write("punch,eps,exponent,tube_radius,depth,force,grid,package,package_version,record\n")
    for path in files:
        with open(path) as f:
            r = json.load(f)
        punch = r["punch"]
        eps = r.get("eps") if punch == "flat-annulus" else None
        exponent = r.get("exponent")
        rho = 0.5 if punch == "torus" else None
        cells = [
            punch,
            "" if eps is None else repr(eps),
            "" if exponent is None else repr(exponent),
            "" if rho is None else repr(rho),
            repr(r["depth"]),
            repr(r["force"]),
            str(r["grid"]),
            r["package"],
            r["package_version"],
            os.path.relpath(path, ROOT),
        ]
        out.write(",".join(cells) + "\n")


if __name__ == "__main__":
    main()
