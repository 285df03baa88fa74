"""Tamaas's grid BEM with its exponential adhesion functional on our punches and law: the peer of
`verify pulloff`: one JSON per case (see Usage).

The law is ours: tension (dw/rho) exp(-g/rho) at gap g, i.e. Tamaas's ExponentialAdhesionFunctional
(potential -dw exp(-g/rho)), with non-penetration; E* = 1 (E = 1, nu = 0), a = 1. Units as
`verify pulloff`: d0 = sqrt(2 pi a dw / E*); the flat punch has d0 = a (dw = 1/(2 pi)), the concave
punches h = 1 and d0 = d0/h (dw = d0^2/(2 pi)); forces in Kendall's F0 = sqrt(8 pi E* dw a^3).

Tamaas's adhesion works in its gap formulation, which is periodic only (its non-periodic operator
is for the pressure formulation): the punch sits in a square cell of side L with its images, the
surface outside the punch far away (-50 d0). The mean gap controls the approach: with Tamaas's
zero-mean displacement, the approach against the cell's mean surface is d_per = -(mean gap shift)
(`curve_shift`: shift / d0, F / F0). The isolated half-space's approach is d_per + F c_img, with
c_img = 1/(2 E* a) - 1/k_cell measured on the flat punch pressed into full contact in the same
cell (F = 2 E* a d there, isolated): `curve` holds (d / d0, F / F0) in that approach, comparable
with ours. The images change the force at pull-off too, by O((a/L)^3) (the curvature of
their displacement field over the punch): each case is solved on two cells (L = 3 and 6 at the
same cell size 3/256) and two cell sizes (3/256 and 3/512 at L = 3); the stored value is the
Richardson extrapolate to L -> infinity (order 3) plus the change to the finer cells; its
uncertainty the Richardson correction plus that change (plus, where the most tensile state is the
end of the branch and the search could not close in on it, the force change over the last step).

Path: displacement control from compression (a state of full contact, approach 0.08 d0) in steps
of 0.04 d0, to the first step past the most tensile force (or the end of the branch: a state that
does not converge within MAX_ITER iterations); the pull-off is found by golden section between
the neighbours of the most tensile step, to 0.002 d0. Tamaas solves each state on its own (no path history); with the hole closed (the
cases here) there is one branch.

Usage (from the repository root, in the environment scripts/peers/setup.sh makes):
    PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_adhesion.py --out DIR [NAME ...]
    PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_adhesion.py NAME
The first writes tamaas-NAME.json into DIR for every case (or those named), through a temporary
file and a rename (the committed baselines are verify/peers/adhesion/: refresh them with --out
verify/peers/adhesion, review, commit); the second prints the one case's record (what a stored
record's `reproduce` runs). Cases: flat, cone-d0h10, sphere-d0h10.
"""

import datetime
import json
import math
import os
import sys
import time

import numpy as np

RANGE_OVER_D0 = 0.1
STEP = 0.04  # d0 per step of the path
REFINE = 0.002  # d0: width at which the golden-section search for the most tensile state stops
OUTSIDE = -50.0  # heights outside the punch, in units of d0 (far beyond the law's range)
CASES = [("flat", None), ("cone", 10.0), ("sphere", 10.0)]
# Tamaas's iteration limit per state, and the error below which a state counts as converged (the
# solver's tolerance is 1e-9): past the end of a branch there is no state near the last one and
# the iteration runs to the limit, which marks the end (20000 cost minutes per state there).
MAX_ITER = 3000
TOLERANCE_MET = 1e-8
# (cell side L, cells per side N): two cell sizes at L = 3, two cells at dx = 3/256.
GRIDS = [(3.0, 256), (3.0, 512), (6.0, 512)]


def exponential_law(tm, heights, d0, dw):
    """Tamaas's exponential functional at our range: tension (dw/rho) exp(-g/rho)."""
    law = tm.ExponentialAdhesionFunctional(heights)
    law.parameters = {"rho": RANGE_OVER_D0 * d0, "surface_energy": dw}
    return law


def setup(kind, d0_over_h, side, n, law=exponential_law):
    """The punch in a periodic cell of side `side` with n x n cells, under `law(tm, heights, d0,
    dw)` (a Tamaas adhesion functional); returns (force_at(shift), d0, F0)."""
    import tamaas as tm
    d0 = 1.0 if d0_over_h is None else d0_over_h
    dw = d0 * d0 / (2.0 * math.pi)
    dx = side / n
    c = (np.arange(n) + 0.5) * dx - side / 2
    x, y = np.meshgrid(c, c, indexing="ij")
    r = np.hypot(x, y)
    inside = r <= 1.0
    if kind == "cone":
        g = 1.0 - r
    elif kind == "sphere":
        g = 1.0 - r * r
    else:
        g = np.zeros_like(r)
    heights = np.where(inside, -g, OUTSIDE * d0)
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [side, side], [n, n])
    model.E = 1.0
    model.nu = 0.0
    solver = tm.PolonskyKeerRey(model, heights, 1e-9, tm.PolonskyKeerRey.gap,
                                tm.PolonskyKeerRey.gap)
    adhesion = law(tm, heights, d0, dw)
    solver.addFunctionalTerm(adhesion)
    solver.max_iter = MAX_ITER
    base = float(np.mean(-heights))  # mean gap of the undeformed surface touching the rim plane
    f0 = math.sqrt(8.0 * math.pi * dw)

    def force_at(shift):
        """Force (compression positive, units of F0) at approach d_per = -shift * d0, or None
        where the solver did not converge (past the end of the branch: no state near the last)."""
        error = solver.solve(base + shift * d0)
        if not (error <= TOLERANCE_MET):
            return None
        return float(np.array(model.traction).sum() * dx * dx) / f0

    # The solver holds the model, surface and functional by reference (C++): keep them alive.
    force_at.keep = (model, heights, adhesion, solver)
    return force_at, d0, f0


def image_compliance(side, n):
    """1/(2 E* a) - 1/k_cell: the compliance the images and the zero-mean displacement of the
    periodic cell take away, from the flat punch pressed into full contact in the same cell
    (F = k_cell d there; isolated, F = 2 E* a d)."""
    import tamaas as tm
    dx = side / n
    c = (np.arange(n) + 0.5) * dx - side / 2
    x, y = np.meshgrid(c, c, indexing="ij")
    heights = np.where(np.hypot(x, y) <= 1.0, 0.0, OUTSIDE)
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [side, side], [n, n])
    model.E = 1.0
    model.nu = 0.0
    solver = tm.PolonskyKeerRey(model, heights, 1e-12, tm.PolonskyKeerRey.gap,
                                tm.PolonskyKeerRey.gap)
    depth = 0.1
    solver.solve(float(np.mean(-heights)) - depth)
    k_cell = float(np.array(model.traction).sum() * dx * dx) / depth
    return 0.5 - 1.0 / k_cell


def close_in_on_branch_end(kind, d0_over_h, side, n, law, marched, end, log):
    """Where the most tensile state ends the branch (`end`: the first shift with no state):
    fresh solvers march again through the `marched` shifts (a solve that failed leaves Tamaas's
    solver off the branch, and a cold start finds no state near the end), then on in steps a
    quarter of the last, until the step is below REFINE or the most tensile state lies inside
    the branch. Returns the converged states met on the way and how much more tension the
    branch may hold than the most tensile of them: the force's rise toward it (from its left
    neighbour) continued to its right neighbour, or to the end of the branch."""
    shifts = [s for s, _ in marched]
    step = STEP
    found = []
    states = list(marched)
    while True:
        step /= 4.0
        force_at, _, _ = setup(kind, d0_over_h, side, n, law)
        for s in shifts:
            if force_at(s) is None:
                raise RuntimeError(f"the march to {s:+.5f} d0 did not converge again")
        s = shifts[-1]
        while s + step < end:
            s = round(s + step, 12)
            f = force_at(s)
            log(f"  {kind} L={side} N={n}: closing in, shift {s:+.5f} d0, F/F0 "
                + ("not converged: end of the branch" if f is None else f"{f:+.5f}"))
            if f is None:
                end = s
                break
            shifts.append(s)
            found.append((s, f))
            states.append((s, f))
        k = min(range(len(states)), key=lambda i: states[i][1])
        right = states[k + 1][0] if k + 1 < len(states) else end
        (s_left, f_left), (s_best, f_best) = states[k - 1], states[k]
        more = (f_left - f_best) / (s_best - s_left) * (right - s_best)
        if k + 1 < len(states) or step <= REFINE:
            return found, abs(more)


def pull(kind, d0_over_h, side, n, log, law=exponential_law, close_in=False):
    """The pull-off of one case on one cell and grid: the march, the search for the most
    tensile state and, with `close_in`, the branch's end approached by finer marches where the
    most tensile state ends it ([`close_in_on_branch_end`])."""
    import tamaas as tm
    tm.set_log_level(tm.LogLevel.error)
    force_at, d0, f0 = setup(kind, d0_over_h, side, n, law)
    start = time.perf_counter()
    # Compression in full contact (flat punch: F = 2 E* a d; the concave ones pressed past 3 h).
    first = -0.08
    curve = []
    s = first
    best = None
    end = None  # first shift with no state on the branch
    while True:
        f = force_at(s)
        log(f"  {kind} L={side} N={n}: shift {s:+.3f} d0, F/F0 "
            + ("not converged: end of the branch" if f is None else f"{f:+.5f}"))
        if f is None:
            end = s
            break
        curve.append((s, f))
        if best is None or f < best[1]:
            best = (s, f)
        elif len(curve) > 3:
            # Past the most tensile state: stop before the branch ends, so that the search
            # below starts from a state on it (a solve past the end leaves the solver's state
            # off the branch, and the next solves from it do not converge).
            break
        if s > first + 3.0:
            raise RuntimeError("no pull-off within 3 d0 of pulling")
        s = round(s + STEP, 10)
    # Golden-section search for the most tensile state between the neighbours of the most
    # tensile step (the force may fall steeply past it, where the branch ends); a trial with no
    # converged state lies past the end and counts as no tension. Each trial starts from the
    # state before it, so the search keeps to the branch where it can.
    k = min(range(len(curve)), key=lambda i: curve[i][1])
    lo = curve[k - 1][0]
    hi = curve[k + 1][0] if k + 1 < len(curve) else end
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
    # Once a solve has failed, the solver's state is off the branch and every later solve from
    # it fails too: the search stops there, and where the most tensile state is the last one
    # before the end of the branch, the force change over the last step bounds how much more
    # tension the branch reaches before it ends (its slope does not steepen toward the end).
    refined = []
    bracket = 0.0
    if end is not None and k == len(curve) - 1:
        bracket = abs(curve[k][1] - curve[k - 1][1])
    failed = False

    def trial(x):
        nonlocal failed
        f = None if failed else force_at(x)
        if f is None:
            failed = True
            return float("inf")
        refined.append((x, f))
        return f

    f1, f2 = trial(x1), trial(x2)
    while hi - lo > REFINE and not failed:
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - ratio * (hi - lo)
            f1 = trial(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + ratio * (hi - lo)
            f2 = trial(x2)
    if not failed:
        bracket = 0.0
    elif close_in and bracket > 0.0:
        closer, bracket = close_in_on_branch_end(kind, d0_over_h, side, n, law, curve[:k + 1],
                                                 end, log)
        refined += closer
    s_best, f_best = min(refined + [curve[k]], key=lambda p: p[1])
    curve = sorted(curve + refined)
    pulloff = -f_best
    wall = time.perf_counter() - start
    c_img = image_compliance(side, n)
    # The approach of the isolated half-space, d = d_per + F c_img, in units of d0.
    isolated = [[-s_ + f * f0 * c_img / d0, f] for s_, f in curve]
    return {
        "side": side,
        "cells": n,
        "cell_size_over_a": side / n,
        "pulloff_over_f0": pulloff,
        "pulloff_shift_over_d0": s_best,
        "curve_shift": [[s_, f] for s_, f in curve],
        "image_compliance": c_img,
        "curve": isolated,
        "wall_s": wall,
        "branch_end_shift_over_d0": end,
        "branch_end_bracket": bracket,
    }


def extrapolated(runs):
    """The stored pull-off from the runs on GRIDS (coarse, fine, wide) and its uncertainty.

    The images act on the punch through the curvature of their displacement field over it
    (constant and linear parts are a rigid body and cancel by symmetry): O((a/L)^3), so
    Richardson with order 3 from L = 3 and 6 at the same cell size; the resolution change from
    the coarse to the fine cell is added. The uncertainty: the Richardson correction plus that
    change plus the largest branch-end bracket."""
    coarse, fine, wide = runs
    images = (wide["pulloff_over_f0"] - coarse["pulloff_over_f0"]) * 8.0 / 7.0
    resolution = fine["pulloff_over_f0"] - coarse["pulloff_over_f0"]
    richardson_correction = (wide["pulloff_over_f0"] - coarse["pulloff_over_f0"]) / 7.0
    return {
        "pulloff_over_f0": coarse["pulloff_over_f0"] + images + resolution,
        "uncertainty": abs(richardson_correction) + abs(resolution)
        + max(r["branch_end_bracket"] for r in runs),
        "image_correction": images,
        "resolution_change": resolution,
    }


def write_record(out_dir, name, record, log):
    """Store `record` as OUT_DIR/tamaas-NAME.json (written whole, then renamed into place) and
    log its pull-off with the parts of its uncertainty."""
    path = os.path.join(out_dir, f"tamaas-{name}.json")
    tmp = f"{path}.{os.getpid()}.partial"
    with open(tmp, "w") as f:
        json.dump(record, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)
    log(f"{path}: pull-off {record['pulloff_over_f0']:.4f} F0 +- {record['uncertainty']:.4f} "
        f"(images {record['image_correction']:+.4f}, "
        f"resolution {record['resolution_change']:+.4f})")


def main():
    import argparse
    import tamaas
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", help="write every case (or those named) into this directory")
    p.add_argument("names", nargs="*", help="cases: flat, cone-d0h10, sphere-d0h10")
    args = p.parse_args()
    if not args.out and len(args.names) != 1:
        p.error("give --out DIR, or exactly one case to print")
    out_dir = args.out
    if out_dir:
        os.makedirs(out_dir, exist_ok=True)
    log = lambda m: print(m, file=sys.stderr, flush=True)
    only = args.names
    for kind, d0_over_h in CASES:
        name = kind if d0_over_h is None else f"{kind}-d0h{d0_over_h:g}"
        if only and name not in only:
            continue
        runs = [pull(kind, d0_over_h, side, n, log) for side, n in GRIDS]
        combined = extrapolated(runs)
        # Flat punch compressed in full contact: F = 2 E* a d (isolated); the cell's stiffness
        # gives the image compliance that converts the approach (stored for every case: the same
        # cell and grid).
        cmd = f"verify pulloff --punch {kind}"
        cmd += f" --d0h {d0_over_h:g}" if d0_over_h is not None else ""
        cmd += f" --ranges {RANGE_OVER_D0}"
        record = {
            "package": "tamaas",
            "package_version": tamaas.__version__,
            "numpy_version": np.__version__,
            "punch": kind,
            "d0_over_h": d0_over_h,
            "range_over_d0": RANGE_OVER_D0,
            "law": "exponential: tension (dw/rho) exp(-g/rho), Tamaas ExponentialAdhesionFunctional "
                   "(rho = range, surface_energy = dw); non-penetration; E* = 1, a = 1",
            "units": "d0 = sqrt(2 pi a dw / E*) (flat: d0 = a; concave: h = 1, d0 = d0/h); "
                     "forces / F0 = sqrt(8 pi E* dw a^3), compression positive in the curves",
            "cell": "periodic square cell of side L centred on the punch; N x N cells; outside "
                    f"the punch the surface is {OUTSIDE} d0 away",
            **combined,
            "runs": runs,
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "reproduce": "PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_adhesion.py "
                         + name,
            "ours": "cargo run --release --quiet -- " + cmd[len("verify "):] + " --json",
        }
        if not out_dir:
            print(json.dumps(record, indent=1))
            continue
        write_record(out_dir, name, record, log)


if __name__ == "__main__":
    main()
