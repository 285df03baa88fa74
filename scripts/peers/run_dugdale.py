"""Tamaas's grid BEM with its Maugis-Dugdale functional on the flat punch: the peer of
`verify adhesion --punch flat --tabor L` (one JSON per Tabor parameter; see Usage).

The law is ours: a constant tension sigma0 where the gap g is below delta_c = dw / sigma0, none
beyond, non-penetration; Tamaas's MaugisAdhesionFunctional with rho = delta_c and surface_energy
= dw has exactly this potential (-dw (1 - g/rho) below rho). E* = 1, a = 1, dw = 1/(2 pi), so that
d0 = sqrt(2 pi a dw / E*) = a and F0 = sqrt(8 pi E* dw a^3) = 2; the Tabor parameter
lambda = 2 sigma0 sqrt(a / (pi E* dw)) fixes sigma0 = (lambda / 2) sqrt(pi E* dw / a).

The cell, the path and the corrections are `run_adhesion.py`'s: the punch in a periodic square
cell of side L with its images, displacement control from compression, the most tensile state by
golden section; the stored force is the Richardson extrapolate to L -> infinity (order 3, from L =
3 and 6 at the same cell size) plus the change from cell size 3/256 to 3/512; its uncertainty the
Richardson correction plus that change (plus the last step's force change where the most tensile
state ends the branch). Tamaas solves each state on its own, so the most tensile converged state
is the pull-off under fixed grips; for the flat punch it equals the fixed-load pull-off (the
cohesive zone grows inward from the rim and the force falls monotonically to its minimum).

Usage (from the repository root, in the environment scripts/peers/setup.sh makes):
    PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_dugdale.py --out DIR [NAME ...]
    PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_dugdale.py NAME
The first writes tamaas-NAME.json into DIR for every case (or those named); the committed
baselines are verify/peers/dugdale/. The second prints the one case's record (what a stored
record's `reproduce` runs). Cases: flat-tabor2, flat-tabor3 (15-20 min each).
"""

import datetime
import json
import math
import os
import sys

import numpy as np

import run_adhesion

TABORS = [2.0, 3.0]


def dugdale_law(tabor):
    """Tamaas's Maugis-Dugdale functional at Tabor parameter `tabor` (a = E* = 1)."""

    def law(tm, heights, d0, dw):
        sigma0 = 0.5 * tabor * math.sqrt(math.pi * dw)
        functional = tm.MaugisAdhesionFunctional(heights)
        functional.parameters = {"rho": dw / sigma0, "surface_energy": dw}
        return functional

    return law


def record_of(tabor, log):
    """The stored record of the flat punch at Tabor parameter `tabor`."""
    import tamaas

    law = dugdale_law(tabor)
    runs = [run_adhesion.pull("flat", None, side, n, log, law, close_in=True)
            for side, n in run_adhesion.GRIDS]
    dw = 1.0 / (2.0 * math.pi)
    sigma0 = 0.5 * tabor * math.sqrt(math.pi * dw)
    return {
        "package": "tamaas",
        "package_version": tamaas.__version__,
        "numpy_version": np.__version__,
        "punch": "flat",
        "law": "dugdale: tension sigma0 where the gap is below delta_c = dw/sigma0, Tamaas "
               "MaugisAdhesionFunctional (rho = delta_c, surface_energy = dw); non-penetration; "
               "E* = 1, a = 1, dw = 1/(2 pi)",
        "tabor": tabor,
        "sigma0_over_estar": sigma0,
        "range_over_a": dw / sigma0,
        "units": "forces / F0 = sqrt(8 pi E* dw a^3), tensile positive for the pull-off, "
                 "compression positive in the curves; shifts and approaches in d0 = a",
        "cell": "periodic square cell of side L centred on the punch; N x N cells; outside the "
                f"punch the surface is {run_adhesion.OUTSIDE} d0 away",
        **run_adhesion.extrapolated(runs),
        "runs": runs,
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "reproduce": "PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_dugdale.py "
                     f"flat-tabor{tabor:g}",
        "ours": f"cargo run --release --quiet -- adhesion --punch flat --tabor {tabor:g} --json",
    }


def main():
    import argparse

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", help="write every case (or those named) into this directory")
    p.add_argument("names", nargs="*", help="cases: " + ", ".join(f"flat-tabor{t:g}" for t in TABORS))
    args = p.parse_args()
    names = {f"flat-tabor{t:g}": t for t in TABORS}
    unknown = [n for n in args.names if n not in names]
    if unknown:
        p.error(f"unknown case {', '.join(unknown)}; the cases are {', '.join(names)}")
    if not args.out and len(args.names) != 1:
        p.error("give --out DIR, or exactly one case to print")
    log = lambda m: print(m, file=sys.stderr, flush=True)
    if args.out:
        os.makedirs(args.out, exist_ok=True)
    for name, tabor in names.items():
        if args.names and name not in args.names:
            continue
        record = record_of(tabor, log)
        if not args.out:
            print(json.dumps(record, indent=1))
            continue
        run_adhesion.write_record(args.out, name, record, log)


if __name__ == "__main__":
    main()
