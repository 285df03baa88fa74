"""Time our grid BEM against Tamaas at 512 x 512 on the same problem, side by side in one run.

Problem: flat circular punch, 512 x 512 cells on [-a, a]^2, E* = 1, total force F = 2 (Tamaas is
load-controlled; ours solves at unit depth, which for a flat punch is the same linear problem).
Each code runs REPEATS times in a fresh process; reported: median wall time of the solve (from
each code's own timer: Tamaas around solver.solve, ours the JSON wall_s of the whole
verify solve), iteration counts, and the peak resident memory of the process (ru_maxrss).

Usage (from the repository root): PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/speed.py
Writes verify/speed/tamaas-512.json.
"""

import datetime
import json
import os
import re
import resource
import statistics
import subprocess
import sys

N = 512
REPEATS = 3

TAMAAS_CHILD = r"""
import resource, sys, time
sys.path.insert(0, "scripts/peers")
from common import punch, tamaas_solve
inside, g, dx = punch("flat", %d)
t = time.perf_counter()
depth, force = tamaas_solve(inside, g, dx, 2.0)
wall = time.perf_counter() - t
print("RESULT", wall, depth, force, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, flush=True)
""" % N


def run_tamaas():
    proc = subprocess.run([sys.executable, "-c", TAMAAS_CHILD], capture_output=True, text=True, check=True)
    line = [l for l in proc.stdout.splitlines() if l.startswith("RESULT")][-1].split()
    log = proc.stdout + "\n" + proc.stderr  # Tamaas logs its iterations
    iterations = [int(m.group(1)) for m in re.finditer(r"^\s*(\d+)\s+\S+\s+\S+\s*$", log, re.M)]
    wall, depth, force, rss_kib = float(line[1]), float(line[2]), float(line[3]), int(line[4])
    return {"wall_s": wall, "stiffness": force / depth, "iterations": max(iterations) if iterations else None,
            "peak_rss_mib": rss_kib / 1024}


def run_ours():
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    proc = subprocess.run(["target/release/verify", "solve", "--punch", "flat", "--method", "grid-bem",
                           "--grid", str(N), "--json"], capture_output=True, text=True, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    out = json.loads(proc.stdout)
    return {"wall_s": out["wall_s"], "stiffness": out["force"] / out["depth"], "iterations": out["iterations"],
            "peak_rss_mib": after / 1024 if after > before else None}


def main():
    ours = [run_ours() for _ in range(REPEATS)]
    tamaas = [run_tamaas() for _ in range(REPEATS)]
    med = lambda rows, k: statistics.median(r[k] for r in rows)
    import tamaas as tm
    record = {
        "problem": f"flat punch, {N} x {N} cells on [-a, a]^2, E* = 1",
        "repeats": REPEATS,
        "ours": {"median_wall_s": med(ours, "wall_s"), "iterations": ours[0]["iterations"],
                 "peak_rss_mib": max((r["peak_rss_mib"] or 0) for r in ours), "stiffness": ours[0]["stiffness"]},
        "tamaas": {"version": tm.__version__, "median_wall_s": med(tamaas, "wall_s"),
                   "iterations": tamaas[0]["iterations"], "peak_rss_mib": max(r["peak_rss_mib"] for r in tamaas),
                   "stiffness": tamaas[0]["stiffness"]},
        "machine": os.uname().machine + ", " + str(os.cpu_count()) + " cores",
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
    }
    record["time_ratio_ours_over_tamaas"] = record["ours"]["median_wall_s"] / record["tamaas"]["median_wall_s"]
    record["stiffness_relative_difference"] = record["ours"]["stiffness"] / record["tamaas"]["stiffness"] - 1
    os.makedirs(os.path.join("verify", "speed"), exist_ok=True)
    with open(os.path.join("verify", "speed", "tamaas-512.json"), "w") as f:
        json.dump(record, f, indent=2)
        f.write("\n")
    print(json.dumps(record, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
