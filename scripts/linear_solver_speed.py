#!/usr/bin/env python3
"""The measurement that decides the FEM's default sparse Cholesky backend (`--linear-solver`).

Times, paired and interleaved (the configurations' order rotates from round to round), the
user's paths with each backend of `ringcontact::sparse` and with the native backend's two-core
split turned off:

- `verify solve --method fem --tol 1e-3 | 1e-6 | 1e-8` on target states of benches/fem_targets
  (meshes from the cache: run once beforehand so that gmsh time is not measured);
- the FEniCSx comparison's fair rows (`verify solve --mesh M --far-field fixed`, the rows of
  scripts/fenicsx/speed.py);
- with `--default-run`, the whole default `verify` run (about a minute a run).

Each time is the program's own `wall_s` (from the mesh file to the answer) or, for the default
run, the process's wall time. Forces of all configurations are checked to agree to 1e-10.
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

# Each configuration: the backend, and the environment it runs with. `native-whole` is the
# native backend with its two-core split turned off (RINGCONTACT_SPLIT_MIN_DOFS beyond every
# model): what the split itself gains, and what the native factorisation gains without it.
CONFIGS = {
    "native": ("native", {}),
    "native-whole": ("native", {"RINGCONTACT_SPLIT_MIN_DOFS": "1000000000"}),
    "faer": ("faer", {}),
}
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


def run(verify, config, args):
    backend, extra = CONFIGS[config]
    env = dict(os.environ, **extra)
    start = time.perf_counter()
    p = subprocess.run([verify, "--linear-solver", backend] + args, cwd=ROOT,
                       capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    if p.returncode != 0:
        sys.exit(f"{' '.join(args)} with {config} failed: {p.stderr.strip()[-400:]}")
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
    names = list(CONFIGS)
    times = {label: {c: [] for c in names} for label, _ in todo}
    forces = {label: {} for label, _ in todo}
    for r in range(opts.rounds):
        for label, args in todo:
            # The order rotates from round to round, so that none always runs first.
            order = names[r % len(names):] + names[:r % len(names)]
            for config in order:
                wall, force = run(verify, config, args)
                times[label][config].append(wall)
                forces[label].setdefault(config, force)
        print(f"round {r + 1}/{opts.rounds} done", file=sys.stderr)
    rows = []
    for label, _ in todo:
        row = {"case": label, "force": forces[label].get("native")}
        for config in names:
            row[config] = spread(times[label][config])
            f = forces[label].get(config)
            fn = forces[label].get("native")
            if fn is not None and abs(f - fn) > AGREEMENT * max(1.0, abs(fn)):
                sys.exit(f"{label}: forces differ, native {fn}, {config} {f}")
        native = times[label]["native"]
        row["faer_over_native"] = spread([f / n for f, n in zip(times[label]["faer"], native)])
        row["native_whole_over_native"] = spread(
            [w / n for w, n in zip(times[label]["native-whole"], native)])
        row["faer_over_native_whole"] = spread(
            [f / w for f, w in zip(times[label]["faer"], times[label]["native-whole"])])
        rows.append(row)
    record = {
        "benchmark": "linear-solver",
        "command": "python3 scripts/linear_solver_speed.py --rounds %d%s"
                   % (opts.rounds, " --default-run" if opts.default_run else ""),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "commit": commit_of(),
        "machine": machine(),
        "rounds": opts.rounds,
        "configurations": {name: {"backend": b, "environment": e} for name, (b, e) in CONFIGS.items()},
        "timed_region": "verify's own wall_s (mesh file to answer); the default run: the process",
        "rows": rows,
    }
    lines = [
        "# The FEM's sparse Cholesky backends: native against faer's public API",
        "",
        f"Generated by `{record['command']}` on {record['date']} (commit {record['commit']}) on "
        f"{record['machine']['description']}. {opts.rounds} interleaved rounds; forces of all "
        "configurations "
        f"within {AGREEMENT:g}. Times in seconds: median (range). Ratios: medians of the "
        "per-round ratios (range). `native-whole` is the native backend without its two-core "
        "split. A home-made piece earns its place on a path where the time without it over the "
        "time with it is at least 1.25: faer / native for the native backend as a whole, "
        "native-whole / native for the split, faer / native-whole for the native factorisation "
        "of a whole matrix.",
        "",
        "| path | native | native-whole | faer | faer / native | native-whole / native "
        "| faer / native-whole |",
        "|---|---|---|---|---|---|---|",
    ]
    fmt = lambda s: f"{s['median']:.3f} ({s['min']:.3f}-{s['max']:.3f})"  # noqa: E731
    fmt_ratio = lambda s: f"{s['median']:.2f} ({s['min']:.2f}-{s['max']:.2f})"  # noqa: E731
    for row in rows:
        lines.append(f"| {row['case']} | {fmt(row['native'])} | {fmt(row['native-whole'])} | "
                     f"{fmt(row['faer'])} | {fmt_ratio(row['faer_over_native'])} | "
                     f"{fmt_ratio(row['native_whole_over_native'])} | "
                     f"{fmt_ratio(row['faer_over_native_whole'])} |")
    text = "\n".join(lines) + "\n"
    os.makedirs(opts.out, exist_ok=True)
    write_atomically(os.path.join(opts.out, "linear-solver.json"), json.dumps(record, indent=1) + "\n")
    write_atomically(os.path.join(opts.out, "linear-solver.md"), text)
    print(text)


if __name__ == "__main__":
    main()
