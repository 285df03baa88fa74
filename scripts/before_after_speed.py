#!/usr/bin/env python3
"""Two builds of `verify` timed on the FEM's user paths, paired and interleaved: did a change
keep the FEM's speed?

Each case is `verify solve --method fem --tol 1e-3 | 1e-6 --json` at the target states of
scripts/linear_solver_speed.py (the cone, the sphere, the flat annulus). Every round runs each
case with both builds, their order alternating from round to round; a warm-up round first fills
the mesh cache (gmsh time is not measured). Each time is the program's own `wall_s` (mesh file
to answer); the forces of the two builds must agree to 1e-10. Writes
benches/records/before-after.{json,md} (the ratio after / before per case: the median of the
per-round ratios and their range) and prints the table.

With --pause S, the machine sits idle S seconds before every timed run, as before a user's single
solve (a program's first touch of fresh memory can cost more after a pause: on a virtual machine
the host may have taken back the free memory); the record is then before-after-idle.{json,md}.

  python3 scripts/before_after_speed.py --before OLD/verify --after NEW/verify [--rounds 7]
  python3 scripts/before_after_speed.py --before OLD/verify --after NEW/verify --pause 2.5

Build the earlier commit's binary in its own worktree, e.g.
  git worktree add /tmp/before <commit> && (cd /tmp/before && cargo build --release --bin verify)
"""

import argparse
import datetime
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from records import ROOT, commit_of, machine, spread, write_atomically  # noqa: E402
from linear_solver_speed import TARGET_STATES  # noqa: E402

AGREEMENT = 1e-10
TOLERANCES = ["1e-3", "1e-6"]


def cases():
    return [(f"--tol {tol}: {label}", ["solve", "--method", "fem", "--tol", tol, "--json"] + args)
            for tol in TOLERANCES for label, args in TARGET_STATES]


def run(verify, args):
    p = subprocess.run([verify] + args, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{verify} {' '.join(args)} failed: {p.stderr.strip()[-400:]}")
    result = json.loads(p.stdout)
    return result["wall_s"], result["force"]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="Writes benches/records/before-after.{json,md} (before-after-idle with --pause; "
               "or into --out).")
    parser.add_argument("--before", required=True, help="the earlier build's verify binary")
    parser.add_argument("--after", required=True, help="the later build's verify binary")
    parser.add_argument("--before-label", default="before", help="what the earlier build is")
    parser.add_argument("--after-label", default="after", help="what the later build is")
    parser.add_argument("--rounds", type=int, default=7, help="interleaved rounds (default 7)")
    parser.add_argument("--pause", type=float, default=0.0,
                        help="seconds idle before every timed run (default 0: back to back)")
    parser.add_argument("--out", default=os.path.join(ROOT, "benches", "records"))
    opts = parser.parse_args()
    if opts.rounds < 1:
        parser.error("--rounds must be at least 1")
    if not opts.pause >= 0.0:
        parser.error("--pause must be 0 or more seconds")
    name = "before-after-idle" if opts.pause > 0 else "before-after"
    for binary in (opts.before, opts.after):
        if not os.access(binary, os.X_OK):
            parser.error(f"{binary} is not an executable verify binary")
    builds = {"before": opts.before, "after": opts.after}
    todo = cases()
    for _, args in todo:  # warm-up: meshes into the cache
        for binary in builds.values():
            run(binary, args)
    times = {label: {b: [] for b in builds} for label, _ in todo}
    forces = {label: {} for label, _ in todo}
    for r in range(opts.rounds):
        order = ["before", "after"] if r % 2 == 0 else ["after", "before"]
        for label, args in todo:
            for build in order:
                time.sleep(opts.pause)
                wall, force = run(builds[build], args)
                times[label][build].append(wall)
                forces[label].setdefault(build, force)
        print(f"round {r + 1}/{opts.rounds} done", file=sys.stderr)
    rows = []
    for label, _ in todo:
        fb, fa = forces[label]["before"], forces[label]["after"]
        if abs(fa - fb) > AGREEMENT * max(1.0, abs(fb)):
            sys.exit(f"{label}: forces differ, before {fb}, after {fa}")
        ratios = [a / b for a, b in zip(times[label]["after"], times[label]["before"])]
        rows.append({"case": label, "force": fa, "before": spread(times[label]["before"]),
                     "after": spread(times[label]["after"]), "after_over_before": spread(ratios)})
    record = {
        "benchmark": "before-after",
        "command": f"python3 scripts/before_after_speed.py --before <{opts.before_label} build> "
                   f"--after <{opts.after_label} build> --rounds {opts.rounds}"
                   + (f" --pause {opts.pause:g}" if opts.pause > 0 else ""),
        "before": opts.before_label,
        "after": opts.after_label,
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "commit": commit_of(),
        "machine": machine(),
        "rounds": opts.rounds,
        "pause_s": opts.pause,
        "timed_region": "verify's own wall_s (mesh file to answer)",
        "rows": rows,
    }
    fmt = lambda s: f"{s['median']:.3f} ({s['min']:.3f}-{s['max']:.3f})"  # noqa: E731
    fmt_ratio = lambda s: f"{s['median']:.2f} ({s['min']:.2f}-{s['max']:.2f})"  # noqa: E731
    lines = [
        "# The FEM's user paths: two builds, paired and interleaved",
        "",
        f"Generated by `{record['command']}` on {record['date']} (commit {record['commit']}) on "
        f"{record['machine']['description']}. Before: {opts.before_label}; after: "
        f"{opts.after_label}. {opts.rounds} interleaved rounds after a warm-up"
        + (f", the machine idle {opts.pause:g} s before every run" if opts.pause > 0 else
           ", runs back to back")
        + "; forces of both "
        f"builds within {AGREEMENT:g}. Times in seconds: median (range); the ratio is the median "
        "of the per-round ratios (range).",
        "",
        "| path | before | after | after / before |",
        "|---|---|---|---|",
    ]
    for row in rows:
        lines.append(f"| {row['case']} | {fmt(row['before'])} | {fmt(row['after'])} | "
                     f"{fmt_ratio(row['after_over_before'])} |")
    text = "\n".join(lines) + "\n"
    os.makedirs(opts.out, exist_ok=True)
    write_atomically(os.path.join(opts.out, f"{name}.json"), json.dumps(record, indent=1) + "\n")
    write_atomically(os.path.join(opts.out, f"{name}.md"), text)
    print(text)


if __name__ == "__main__":
    main()
