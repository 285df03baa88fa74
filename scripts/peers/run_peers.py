"""Run Tamaas and ContactMechanics on the grids and profiles of `verify --method grid-bem`: one
JSON per case and package (force at a given depth, with provenance).

Usage (from the repository root, in the environment scripts/peers/setup.sh makes):
    PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_peers.py --out DIR
    PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_peers.py --case tamaas-cone-d2.0-N128
The first writes every case into DIR (through a temporary file and a rename; the committed
baselines are verify/peers/: refresh them with --out verify/peers, review, commit); the second
prints one case's record (what a stored record's `peer_reproduce` runs). Both together
(`--out DIR --case NAME ...`) write only the cases named.
"""

import argparse
import datetime
import json
import os
import sys
import time

from common import contactmechanics_at_depth, punch, tamaas_at_depth

# (punch, b/a of the flat annulus, depth d/h (flat: d/a), cells per side, shape parameter):
# the power law's exponent n; the torus's square half-size L/a (its band at d = h/2 is
# [0.726, 1.385] a, so L = 1.6 a leaves eight cells of 128 beyond it).
CASES = [
    ("flat", 0.0, 1.0, 64, None),
    ("flat", 0.0, 1.0, 128, None),
    ("flat", 0.0, 1.0, 256, None),
    ("flat-annulus", 0.5, 1.0, 128, None),
    ("cone", 0.0, 2.0, 128, None),
    ("cone", 0.0, 2.0, 256, None),
    ("sphere", 0.0, 1.5, 128, None),
    ("sphere", 0.0, 1.5, 256, None),
    ("power", 0.0, 1.0, 128, 1.5),
    ("power", 0.0, 1.0, 256, 1.5),
    ("power", 0.0, 1.0, 128, 4.0),
    ("torus", 0.0, 0.5, 128, 1.6),
    ("torus", 0.0, 0.5, 256, 1.6),
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


# Each peer's documented solver and settings (and the build PyPI gives: Tamaas's serial C++
# backend); wall_s is one run, not a speed comparison (scripts/peers/speed.py makes that).
CONFIGURATION = {
    "tamaas": "PolonskyKeerRey, non-periodic dcfft operator, tolerance 1e-12, load control with a "
              "secant on the load to reach the depth (flat punches: one solve scaled)",
    "contactmechanics": "FreeFFTElasticHalfSpace, minimize_proxy (L-BFGS-B) under displacement "
                        "control, pentol 1e-12 d, maxiter 20000",
}


def name_of(package, kind, eps, depth, n, parameter):
    shape = {"flat-annulus": f"-{eps}", "power": f"-n{parameter}", "torus": f"-L{parameter}"}
    return f"{package}-{kind}{shape.get(kind, '')}-d{depth}-N{n}"


def record_of(package, kind, eps, depth, n, parameter, v):
    exponent = parameter if kind == "power" else None
    half_size = parameter if kind == "torus" else 1.0
    inside, g, dx = punch(kind, n, eps, exponent, half_size)
    flat = kind in ("flat", "flat-annulus")
    start = time.perf_counter()
    if package == "tamaas":
        force, solves = tamaas_at_depth(inside, g, dx, depth, flat)
        iterations = None
    else:
        force, iterations = contactmechanics_at_depth(inside, g, dx, depth)
        solves = 1
    wall = time.perf_counter() - start
    cmd = f"cargo run --release --quiet -- solve --punch {kind} --method grid-bem --grid {n}"
    cmd += f" --eps {eps}" if kind == "flat-annulus" else ""
    cmd += f" --exponent {exponent}" if kind == "power" else ""
    # Tube radius a^2/(2h) = 0.5 makes h = 1, the dimensionless profile (1 - r)^2.
    cmd += f" --tube-radius 0.5 --grid-extent {half_size}" if kind == "torus" else ""
    cmd += f" --depth {depth}" if not flat else ""
    name = name_of(package, kind, eps, depth, n, parameter)
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
        "profile": "cells N x N on [-L, L]^2 (L = 1 but for the torus), centres (i + 1/2) dx - L; "
                   "punch where b <= r <= 1 (r <= 1; torus r <= L); gap 1 - r (cone), 1 - r^2 "
                   "(sphere), 1 - r^n (power), (1 - r)^2 (torus), 0 (flat); E* = 1",
        "configuration": CONFIGURATION[package],
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "reproduce": cmd + " --json",
        "peer_reproduce": "PYTHONPATH=scripts/peers .venv-peers/bin/python "
                          f"scripts/peers/run_peers.py --case {name}",
    }
    if kind == "power":
        record["exponent"] = exponent
    if kind == "torus":
        record["grid_extent"] = half_size
    return record


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", help="write the cases into this directory (every case unless --case)")
    p.add_argument("--case", action="append", default=[],
                   help="this case only (e.g. tamaas-cone-d2.0-N128; repeatable): printed, or "
                        "written with --out")
    args = p.parse_args()
    if not args.out and not args.case:
        p.error("give --out DIR (every case), --case NAME (one, printed) or both (written)")
    v = versions()
    cases = [(package, *case) for case in CASES for package in ("tamaas", "contactmechanics")]
    names = [name_of(*c) for c in cases]
    for name in args.case:
        if name not in names:
            p.error(f"unknown case {name}; known: {', '.join(names)}")
    chosen = [(c, n) for c, n in zip(cases, names) if not args.case or n in args.case]
    if not args.out:
        for case, _ in chosen:
            print(json.dumps(record_of(*case, v), indent=2))
        return 0
    os.makedirs(args.out, exist_ok=True)
    for case, name in chosen:
        record = record_of(*case, v)
        path = os.path.join(args.out, name + ".json")
        tmp = f"{path}.{os.getpid()}.partial"
        with open(tmp, "w") as f:
            json.dump(record, f, indent=2)
            f.write("\n")
        os.replace(tmp, path)
        print(f"{name}: force {record['force']:.12g} ({record['wall_s']:.2f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
