"""Run Tamaas and ContactMechanics on the grids and profiles of `verify --method grid-bem` and store
one JSON per case and package under verify/peers/ (force at a given depth, with provenance).

Usage (from the repository root, in the environment made by scripts/peers/run_peers.sh):
    python scripts/peers/run_peers.py
"""

import datetime
import json
import os
import sys
import time

from common import contactmechanics_at_depth, punch, tamaas_at_depth

CASES = [
    ("flat", 0.0, 1.0, 64),
    ("flat", 0.0, 1.0, 128),
    ("flat", 0.0, 1.0, 256),
    ("flat-annulus", 0.5, 1.0, 128),
    ("cone", 0.0, 2.0, 128),
    ("cone", 0.0, 2.0, 256),
    ("sphere", 0.0, 1.5, 128),
    ("sphere", 0.0, 1.5, 256),
]


def versions():
    import numpy
    out = {"numpy": numpy.__version__}
    try:
        import tamaas
        out["tamaas"] = tamaas.__version__
    except ImportError:
        pass
    try:
        import ContactMechanics
        out["contactmechanics"] = ContactMechanics.__version__
    except ImportError:
        pass
    return out


def main():
    out_dir = os.path.join("verify", "peers")
    os.makedirs(out_dir, exist_ok=True)
    v = versions()
    for kind, eps, depth, n in CASES:
        inside, g, dx = punch(kind, n, eps)
        flat = kind in ("flat", "flat-annulus")
        for package in ("tamaas", "contactmechanics"):
            start = time.perf_counter()
            if package == "tamaas":
                force, solves = tamaas_at_depth(inside, g, dx, depth, flat)
                iterations = None
            else:
                force, iterations = contactmechanics_at_depth(inside, g, dx, depth)
                solves = 1
            wall = time.perf_counter() - start
            cmd = f"verify solve --punch {kind} --method grid-bem --grid {n}"
            cmd += f" --eps {eps}" if kind == "flat-annulus" else ""
            cmd += f" --depth {depth}" if not flat else ""
            record = {
                "package": package,
                "package_version": v.get(package, "unknown"),
                "numpy_version": v["numpy"],
                "punch": kind,
                "eps": eps if kind == "flat-annulus" else None,
                "grid": n,
                "depth": depth,
                "force": force,
                "solves": solves,
                "iterations": iterations,
                "wall_s": wall,
                "profile": "cells N x N on [-1, 1]^2, centres (i + 1/2) dx - 1; punch where b <= r <= 1 "
                           "(r <= 1); gap 1 - r (cone), 1 - r^2 (sphere), 0 (flat); E* = 1",
                "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                "reproduce": cmd + " --json",
            }
            name = f"{package}-{kind}{'-' + str(eps) if kind == 'flat-annulus' else ''}-d{depth}-N{n}.json"
            with open(os.path.join(out_dir, name), "w") as f:
                json.dump(record, f, indent=2)
                f.write("\n")
            print(f"{name}: force {force:.12g} ({wall:.2f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
