#!/usr/bin/env python3
"""The Maugis-Dugdale pull-off's speed: `verify adhesion --tabor L --tol 1e-4` on the flat
annulus (b/a = 0.5), the cone and the sphere (d0/h = 1), timed as a user waits for it (the whole
process), in interleaved rounds with the spread of the runs; against the target of 0.5 s per
pull-off. With --before, an earlier build runs beside this one in the same rounds (order
alternating), and the pull-offs of both must agree within their error bounds.

Writes benches/records/dugdale-speed.{json,md} (or into --out) and prints the table.

  python3 scripts/dugdale_speed.py [--verify target/release/verify] [--rounds 5]
  python3 scripts/dugdale_speed.py --before OLD/verify [--rounds 5]

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

TARGET_S = 0.5
TOLERANCE = "1e-4"
FACES = [
    ("flat annulus b/a = 0.5", ["--punch", "flat-annulus", "--eps", "0.5"]),
    ("cone d0/h = 1", ["--punch", "cone", "--d0h", "1"]),
    ("sphere d0/h = 1", ["--punch", "sphere", "--d0h", "1"]),
]
TABORS = ["1", "2", "5"]


def cases():
    return [(f"{face}, λ = {tabor}",
             ["adhesion"] + args + ["--tabor", tabor, "--tol", TOLERANCE, "--json"])
            for face, args in FACES for tabor in TABORS]


def run(verify, args):
    """(wall seconds, force, its bound) of one run; force None where the command declines."""
    start = time.perf_counter()
    p = subprocess.run([verify] + args, cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if p.returncode != 0:
        return wall, None, p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "failed"
    result = json.loads(p.stdout)
    return wall, result["pulloff_force"], result["pulloff_force_error"]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="Writes benches/records/dugdale-speed.{json,md} (or into --out).")
    parser.add_argument("--verify", default=os.path.join(ROOT, "target", "release", "verify"),
                        help="the build timed (default: target/release/verify)")
    parser.add_argument("--before", help="an earlier build's verify binary, timed beside it")
    parser.add_argument("--before-label", default="before", help="what the earlier build is")
    parser.add_argument("--rounds", type=int, default=5, help="interleaved rounds (default 5)")
    parser.add_argument("--out", default=os.path.join(ROOT, "benches", "records"))
    opts = parser.parse_args()
    if opts.rounds < 1:
        parser.error("--rounds must be at least 1")
    builds = {"after": opts.verify}
    if opts.before:
        builds["before"] = opts.before
    for binary in builds.values():
        if not os.access(binary, os.X_OK):
            parser.error(f"{binary} is not an executable verify binary (cargo build --release)")
    todo = cases()
    times = {label: {b: [] for b in builds} for label, _ in todo}
    answers = {label: {} for label, _ in todo}
    for r in range(opts.rounds):
        order = sorted(builds) if r % 2 == 0 else sorted(builds, reverse=True)
        for label, args in todo:
            for build in order:
                wall, force, bound = run(builds[build], args)
                times[label][build].append(wall)
                answers[label].setdefault(build, (force, bound))
        print(f"round {r + 1}/{opts.rounds} done", file=sys.stderr, flush=True)
    rows = []
    for label, args in todo:
        force, bound = answers[label]["after"]
        row = {"case": label, "command": "verify " + " ".join(args), "force": force,
               "force_error" if force is not None else "declined": bound,
               "seconds": spread(times[label]["after"])}
        if force is not None:
            row["meets_target"] = row["seconds"]["median"] <= TARGET_S
        if opts.before:
            before, before_bound = answers[label]["before"]
            if (before is None) != (force is None) or (
                    force is not None and abs(force - before) > bound + before_bound):
                sys.exit(f"{label}: the builds disagree: before {before} ± {before_bound}, "
                         f"after {force} ± {bound}")
            row["before_seconds"] = spread(times[label]["before"])
            row["after_over_before"] = spread(
                [a / b for a, b in zip(times[label]["after"], times[label]["before"])])
        rows.append(row)
    record = {
        "benchmark": "dugdale-speed",
        "command": "python3 scripts/dugdale_speed.py --rounds " + str(opts.rounds)
                   + (f" --before <{opts.before_label} build>" if opts.before else ""),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "commit": commit_of(),
        "machine": machine(),
        "rounds": opts.rounds,
        "target_s": TARGET_S,
        "tolerance": float(TOLERANCE),
        "timed_region": "the whole `verify adhesion` process, as a user waits for it",
        "rows": rows,
    }
    fmt = lambda s: f"{s['median']:.2f} ({s['min']:.2f}-{s['max']:.2f})"  # noqa: E731
    head = "| pull-off (fixed load) | F/F0 | seconds | target 0.5 s |"
    rule = "|---|---|---|---|"
    if opts.before:
        head += f" {opts.before_label} | ratio |"
        rule += "---|---|"
    lines = [
        "# The Maugis-Dugdale pull-off's speed",
        "",
        f"Generated by `{record['command']}` on {record['date']} (commit {record['commit']}) on "
        f"{record['machine']['description']}. Each pull-off to --tol {TOLERANCE}, the whole "
        f"process timed; {opts.rounds} interleaved rounds; seconds as median (range)"
        + ("; the ratio is the median of the per-round ratios (range)." if opts.before else "."),
        "",
        head,
        rule,
    ]
    for row in rows:
        answer = (f"{row['force']:.6f}" if row["force"] is not None else "declined")
        met = "" if row["force"] is None else ("met" if row["meets_target"] else "unmet")
        line = f"| {row['case']} | {answer} | {fmt(row['seconds'])} | {met} |"
        if opts.before:
            line += f" {fmt(row['before_seconds'])} | {fmt(row['after_over_before'])} |"
        lines.append(line)
    text = "\n".join(lines) + "\n"
    os.makedirs(opts.out, exist_ok=True)
    write_atomically(os.path.join(opts.out, "dugdale-speed.json"),
                     json.dumps(record, indent=1) + "\n")
    write_atomically(os.path.join(opts.out, "dugdale-speed.md"), text)
    print(text)


if __name__ == "__main__":
    main()
