"""Our grid BEM against Tamaas at 512 x 512 on the same problem, interleaved, with the spread.

Problem: flat circular punch, 512 x 512 cells on [-a, a]^2, E* = 1 (Tamaas is load-controlled at
F = 2; ours solves at unit depth: for a flat punch the same linear problem). Tamaas runs its
documented solver (PolonskyKeerRey with the non-periodic "dcfft" operator, tolerance 1e-12) in the
configuration PyPI gives (its serial C++ backend); ours `verify solve --method grid-bem --grid 512
--no-grid-estimate` (the one grid, as Tamaas runs it, without the two coarser grids of our error
estimate; its own tolerance, 1e-10 complementarity). Each round runs both, each in a fresh
process, the order alternating; the timed region on both sides is the solve (Tamaas: around solver.solve;
ours: the JSON's wall_s, the whole solve after the process started).

Writes benches/records/tamaas-speed.json (every run, medians, ranges, the ratio per round,
machine, commit) and the table tamaas-speed.md beside it (or into --out).

Usage (from the repository root, in the environment scripts/peers/setup.sh makes):
    PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/speed.py [--rounds 5]
"""

import argparse
import datetime
import json
import os
import re
import resource
import statistics
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from records import commit_of, machine, verify_binary, write_atomically  # noqa: E402

N = 512

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
    proc = subprocess.run([sys.executable, "-c", TAMAAS_CHILD], cwd=ROOT, capture_output=True,
                          text=True, check=True)
    line = [l for l in proc.stdout.splitlines() if l.startswith("RESULT")][-1].split()
    log = proc.stdout + "\n" + proc.stderr  # Tamaas logs its iterations
    iterations = [int(m.group(1)) for m in re.finditer(r"^\s*(\d+)\s+\S+\s+\S+\s*$", log, re.M)]
    wall, depth, force = float(line[1]), float(line[2]), float(line[3])
    return {"wall_s": wall, "stiffness": force / depth,
            "iterations": max(iterations) if iterations else None,
            "peak_rss_mib": int(line[4]) / 1024}


def run_ours(verify):
    proc = subprocess.run([verify, "solve", "--punch", "flat", "--method", "grid-bem", "--grid",
                           str(N), "--no-grid-estimate", "--json"], cwd=ROOT, capture_output=True, text=True, check=True)
    out = json.loads(proc.stdout)
    return {"wall_s": out["wall_s"], "stiffness": out["force"] / out["depth"],
            "iterations": out["iterations"]}


def spread(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values),
            "runs": values}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--out", default=os.path.join(ROOT, "benches", "records"))
    args = p.parse_args()
    verify = verify_binary()
    import tamaas as tm
    ours, tamaas = [], []
    for k in range(args.rounds):
        pair = [("ours", lambda: ours.append(run_ours(verify))),
                ("tamaas", lambda: tamaas.append(run_tamaas()))]
        for _, run in (pair if k % 2 == 0 else pair[::-1]):
            run()
        print(f"round {k + 1} of {args.rounds} done", file=sys.stderr)
    ratio = spread([a["wall_s"] / b["wall_s"] for a, b in zip(ours, tamaas)])
    record = {
        "benchmark": "tamaas-speed",
        "problem": f"flat punch, {N} x {N} cells on [-a, a]^2, E* = 1",
        "command": "PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/speed.py "
                   + " ".join(sys.argv[1:]),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "commit": commit_of(ROOT),
        "machine": machine(),
        "rounds": args.rounds,
        "timed_region": "the solve, inside each process (Tamaas: solver.solve; ours: wall_s)",
        "tamaas_configuration": f"tamaas {tm.__version__}, backend {tm.TamaasInfo.backend}, "
                                "PolonskyKeerRey, dcfft, tolerance 1e-12",
        "ours": {**spread([r["wall_s"] for r in ours]), "iterations": ours[0]["iterations"],
                 "stiffness": ours[0]["stiffness"]},
        "tamaas": {**spread([r["wall_s"] for r in tamaas]), "iterations": tamaas[0]["iterations"],
                   "peak_rss_mib": max(r["peak_rss_mib"] for r in tamaas),
                   "stiffness": tamaas[0]["stiffness"]},
        "ratio_ours_over_tamaas": ratio,
        "stiffness_relative_difference": ours[0]["stiffness"] / tamaas[0]["stiffness"] - 1,
    }
    os.makedirs(args.out, exist_ok=True)
    write_atomically(os.path.join(args.out, "tamaas-speed.json"), json.dumps(record, indent=1) + "\n")
    o, t = record["ours"], record["tamaas"]
    table = "\n".join([
        "# Our grid BEM against Tamaas at 512 x 512 (flat punch)",
        "",
        f"Generated by `{record['command']}` on {record['date']} (commit {record['commit']}) on "
        f"{record['machine']['description']}. {args.rounds} interleaved rounds; times in seconds, "
        "median (range). " + record["tamaas_configuration"] + "; timed region: "
        + record["timed_region"] + ".",
        "",
        "| code | time | iterations | stiffness |",
        "|---|---|---|---|",
        f"| ours | {o['median']:.2f} ({o['min']:.2f}-{o['max']:.2f}) | {o['iterations']} | "
        f"{o['stiffness']:.12f} |",
        f"| Tamaas | {t['median']:.2f} ({t['min']:.2f}-{t['max']:.2f}) | {t['iterations']} | "
        f"{t['stiffness']:.12f} |",
        "",
        f"Our time over Tamaas's: {ratio['median']:.2f} ({ratio['min']:.2f}-{ratio['max']:.2f}); "
        f"stiffnesses differ by {record['stiffness_relative_difference']:.1e}.",
        "",
    ])
    write_atomically(os.path.join(args.out, "tamaas-speed.md"), table)
    print(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
