#!/usr/bin/env python3
"""Our FEM's time over FEniCSx's on the stored flat rows, both measured in the same period.

`verify fenicsx` divides our time by the FEniCSx time stored with each result, which was measured
on another day. This script measures both now, in rounds: each round re-solves every stored flat
row's mesh with `scripts/fenicsx/solve.py` (the stored row's arguments; its force is checked
against the stored one to 1e-10, the result written to a scratch directory, the stored files
untouched), optionally waits `--settle` seconds, then runs `verify fenicsx --json` once. The
table gives, per row, the medians of our times and of FEniCSx's, their ratio, and the ratio's
range over the rounds.

The settle pause is there to test the moment: on the virtual machine this project is developed
on, a solve started right after a large process had freed its memory once ran up to 1.4 times
slower for a few seconds, while FEniCSx's own timed region starts after its imports, about 0.6 s
after the previous solve ended. Over five rounds the pause changed little (benches/FENICSX_SPEED.md,
*Where the 92 528-unknown row's time goes*, both protocols' tables).

Usage (from anywhere; needs FEniCSx, see setup.sh, and a release build of `verify`):

    python3 scripts/fenicsx/same_period.py --rounds 5
    python3 scripts/fenicsx/same_period.py --rounds 3 --large --settle 6
"""

import argparse
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def fenicsx_time(row, scratch):
    """Re-solve one stored row with FEniCSx; its wall time (s), the force checked."""
    args = [
        "/usr/bin/python3", os.path.join(ROOT, "scripts", "fenicsx", "solve.py"),
        "--punch", row["punch"], "--mesh", row["mesh"], "--degree", str(row["degree"]),
        "--depth", str(row["depth"]), "--out", scratch,
    ]
    if row["punch"] == "flat-annulus" and row.get("eps") is not None:
        args += ["--eps", str(row["eps"])]
    subprocess.run(args, check=True, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(scratch) as f:
        fresh = json.load(f)
    if abs(fresh["force"] - row["force"]) > 1e-10 * abs(row["force"]):
        sys.exit(f"{row['mesh']}: FEniCSx's force {fresh['force']} is not the stored {row['force']}")
    return fresh["wall_s"]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--rounds", type=int, default=5, help="rounds (each: FEniCSx on every row, then ours)")
    p.add_argument("--large", action="store_true", help="the --large rows (verify/fenicsx/large/)")
    p.add_argument("--settle", type=float, default=0.0,
                   help="seconds of idle between FEniCSx's last solve and `verify fenicsx` (default 0)")
    p.add_argument("--verify", default=os.path.join(ROOT, "target", "release", "verify"),
                   help="the verify binary (default: target/release/verify)")
    p.add_argument("--json", help="also write the table, with every round's times, to this file")
    args = p.parse_args()
    if args.rounds < 1:
        p.error("--rounds must be at least 1")
    if not os.access(args.verify, os.X_OK):
        p.error(f"{args.verify} is not an executable: run `cargo build --release` first")
    pattern = os.path.join(ROOT, "verify", "fenicsx", "large" if args.large else "", "flat*.json")
    files = sorted(f for f in glob.glob(pattern) if "-np" not in os.path.basename(f))
    if not files:
        sys.exit(f"no stored flat rows match {pattern}")
    rows = {os.path.basename(f): json.load(open(f)) for f in files}
    ours = {name: [] for name in rows}
    theirs = {name: [] for name in rows}
    with tempfile.TemporaryDirectory() as scratch_dir:
        scratch = os.path.join(scratch_dir, "fenicsx.json")
        for r in range(args.rounds):
            for name, row in rows.items():
                theirs[name].append(fenicsx_time(row, scratch))
            time.sleep(args.settle)
            command = [args.verify, "fenicsx", "--json"] + (["--large"] if args.large else [])
            out = subprocess.run(command, check=True, cwd=ROOT, capture_output=True, text=True)
            for result in json.loads(out.stdout):
                name = os.path.basename(result["file"])
                if name in ours and result.get("our_wall_s") is not None:
                    ours[name].append(result["our_wall_s"])
            print(f"round {r + 1} of {args.rounds} done", file=sys.stderr)
    table = []
    print(f"{'row':46} {'unknowns':>9} {'ours s':>8} {'FEniCSx s':>9} {'ratio':>6}  per round")
    for name, row in rows.items():
        if len(ours[name]) != len(theirs[name]):
            sys.exit(f"{name}: `verify fenicsx` did not time it in every round")
        mine, fx = statistics.median(ours[name]), statistics.median(theirs[name])
        per_round = [a / b for a, b in zip(ours[name], theirs[name])]
        print(f"{name:46} {row['dofs']:9d} {mine:8.4f} {fx:9.3f} {mine / fx:6.3f}  "
              f"{min(per_round):.3f}-{max(per_round):.3f}")
        table.append(dict(row=name, unknowns=row["dofs"], ours_s=ours[name], fenicsx_s=theirs[name],
                          ours_median_s=mine, fenicsx_median_s=fx, ratio=mine / fx))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(dict(settle_s=args.settle, rounds=args.rounds, large=args.large,
                           verify=args.verify, rows=table), f, indent=1)


if __name__ == "__main__":
    main()
