#!/usr/bin/env python3
"""The measurement that decides the FEM's default sparse Cholesky backend (`--linear-solver`).

Times, paired and interleaved (the backends' order alternates from round to round), the user's
paths with each backend of `ringcontact::sparse`:

- `verify solve --method fem --tol 1e-3 | 1e-6 | 1e-8` on target states of benches/fem_targets
  (meshes from the cache: run once beforehand so that gmsh time is not measured);
- the FEniCSx comparison's fair rows (`verify solve --mesh M --far-field fixed`, the rows of
  scripts/fenicsx/speed.py);
- with `--default-run`, the whole default `verify` run (about a minute a run).

Each time is the program's own `wall_s` (from the mesh file to the answer) or, for the default
run, the process's wall time. Forces of the two backends are checked to agree to 1e-10.
Writes benches/records/linear-solver.{json,md}; prints the table.

  python3 scripts/linear_solver_speed.py [--rounds 5] [--default-run] [--out DIR]
"""

import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "fenicsx"))
from records import ROOT, commit_of, machine, verify_binary, write_atomically  # noqa: E402
import speed as fenicsx_speed  # noqa: E402

BACKENDS = ["native", "faer"]
AGREEMENT = 1e-10
TARGET_STATES = [
    ("cone d/h=2", ["--punch", "cone", "--depth", "2"]),
    ("sphere d/h=1.5", ["--punch", "sphere", "--depth", "1.5"]),
    ("flat annulus b/a=0.5", ["--punch", "flat-annulus", "--eps", "0.5"]),
    ("flat annulus b/a=0.9", ["--punch", "flat-annulus", "--eps", "0.9"]),
]
TOLERANCES = {"1e-3": TARGET_STATES, "1e-6": TARGET_STATES, "1e-8": TARGET_STATES[:2]}


def cases(verify):
    out = []
    for tol, states in TOLERANCES.items():
        for label, args in states:
            out.append((f"--tol {tol}: {label}",
                        ["solve", "--method", "fem", "--tol", tol, "--json"] + args))
    for name in fenicsx_speed.DEFAULT_ROWS:
        row = fenicsx_speed.load_row(name)
        mesh = fenicsx_speed.mesh_of(row, verify)
        out.append((f"fenicsx row {name}",
                    ["solve", "--method", "fem", "--mesh", mesh, "--far-field", "fixed", "--json"]
                    + fenicsx_speed.state_args(row)))
    return out


def run(verify, backend, args):
    start = time.perf_counter()
    p = subprocess.run([verify, "--linear-solver", backend] + args, cwd=ROOT,
                       capture_output=True, text=True)
    wall = time.perf_counter() - start
    if p.returncode != 0:
        sys.exit(f"{' '.join(args)} with {backend} failed: {p.stderr.strip()[-400:]}")
    if args and args[0] == "solve":
        result = json.loads(p.stdout)
        return result["wall_s"], result["force"]
    return wall, None


def spread(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values),
            "runs": values}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--default-run", action="store_true",
                        help="also time the whole default `verify` run")
    parser.add_argument("--out", default=os.path.join(ROOT, "benches", "records"))
    opts = parser.parse_args()
    if opts.rounds < 1:
        parser.error("--rounds must be at least 1")
    verify = verify_binary()
    todo = cases(verify)
    if opts.default_run:
        todo.append(("default verify run", []))
    times = {label: {b: [] for b in BACKENDS} for label, _ in todo}
    forces = {label: {} for label, _ in todo}
    for r in range(opts.rounds):
        for label, args in todo:
            order = BACKENDS if r % 2 == 0 else list(reversed(BACKENDS))
            for backend in order:
                wall, force = run(verify, backend, args)
                times[label][backend].append(wall)
                forces[label].setdefault(backend, force)
        print(f"round {r + 1}/{opts.rounds} done", file=sys.stderr)
    rows = []
    for label, _ in todo:
        native, faer = times[label]["native"], times[label]["faer"]
        ratios = [f / n for f, n in zip(faer, native)]
        fn, ff = forces[label].get("native"), forces[label].get("faer")
        if fn is not None and abs(fn - ff) > AGREEMENT * max(1.0, abs(fn)):
            sys.exit(f"{label}: forces differ, native {fn}, faer {ff}")
        rows.append({"case": label, "native": spread(native), "faer": spread(faer),
                     "faer_over_native": spread(ratios), "force": fn})
    record = {
        "benchmark": "linear-solver",
        "command": "python3 scripts/linear_solver_speed.py --rounds %d%s"
                   % (opts.rounds, " --default-run" if opts.default_run else ""),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "commit": commit_of(),
        "machine": machine(),
        "rounds": opts.rounds,
        "timed_region": "verify's own wall_s (mesh file to answer); the default run: the process",
        "rows": rows,
    }
    lines = [
        "# The FEM's sparse Cholesky backends: native against faer's public API",
        "",
        f"Generated by `{record['command']}` on {record['date']} (commit {record['commit']}) on "
        f"{record['machine']}. {opts.rounds} interleaved rounds; forces of the two backends "
        f"within {AGREEMENT:g}. Times in seconds: median (range). Ratio: faer's time over "
        "native's, median of the per-round ratios (range); above 1.25 native earns its place "
        "on that path.",
        "",
        "| path | native | faer | faer / native |",
        "|---|---|---|---|",
    ]
    fmt = lambda s: f"{s['median']:.3f} ({s['min']:.3f}-{s['max']:.3f})"  # noqa: E731
    fmt_ratio = lambda s: f"{s['median']:.2f} ({s['min']:.2f}-{s['max']:.2f})"  # noqa: E731
    for row in rows:
        lines.append(f"| {row['case']} | {fmt(row['native'])} | {fmt(row['faer'])} | "
                     f"{fmt_ratio(row['faer_over_native'])} |")
    text = "\n".join(lines) + "\n"
    os.makedirs(opts.out, exist_ok=True)
    write_atomically(os.path.join(opts.out, "linear-solver.json"), json.dumps(record, indent=1) + "\n")
    write_atomically(os.path.join(opts.out, "linear-solver.md"), text)
    print(text)


if __name__ == "__main__":
    main()
