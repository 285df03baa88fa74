#!/usr/bin/env python3
"""Pull-off simulations (`verify pulloff --json`) of the stored cases, one record per case.

Cases: the flat punch, two flat annuli, the concave punches at d0/h = 0.3, 1, 3, 10 (pressed
until the hole closes), and the annular branch (--branch annular) of both at d0/h = 0.3 and 1 and
of the cone at 3, where none exists (declined), and the torus at d0/h = 1 and 0.25. Needs gmsh (bash scripts/install_gmsh.sh); about
25 minutes on 2 cores.

Each record is NAME.json in --out: the result (or why the simulation declined the case), the
date, the commit and the command that reproduces it. Records are written through a temporary file
and a rename. A record of a run that declined, failed or stopped early never replaces one with a
result: it goes beside it as NAME.error.json, and the run's exit status is 1. The committed baselines are verify/pulloff/;
refresh them with `--out verify/pulloff`, review the difference and commit it.

Usage: python3 scripts/pulloff/run_all.py --out DIR [NAME ...]   (default: every case)
"""

import argparse
import datetime
import json
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from records import commit_of, verify_binary, write_atomically  # noqa: E402

CASES = [("flat", ["--punch", "flat"]),
         ("flat-annulus-0.5", ["--punch", "flat-annulus", "--eps", "0.5"]),
         ("flat-annulus-0.9", ["--punch", "flat-annulus", "--eps", "0.9"])]
for x in ("0.3", "1", "3", "10"):
    CASES += [(f"cone-d0h{x}", ["--punch", "cone", "--d0h", x]),
              (f"sphere-d0h{x}", ["--punch", "sphere", "--d0h", x])]
# The annular branch where the JKR route has a stable annular contact (d0/h = 1, 0.3) and where
# it has none (d0/h = 3: the hole closes first, declined).
CASES += [(f"{punch}-d0h{x}-annular", ["--punch", punch, "--d0h", x, "--branch", "annular"])
          for punch, x in (("cone", "1"), ("sphere", "1"), ("cone", "3"), ("cone", "0.3"),
                           ("sphere", "0.3"))]
# The torus (two free edges, touched then pulled) at d0/rho = 2 and 0.5 (rho = a/2: d0/h = 1 and
# 0.25), against its two-edge JKR solution.
CASES += [(f"torus-d0h{x}", ["--punch", "torus", "--d0h", x]) for x in ("1", "0.25")]


def has_result(path):
    try:
        with open(path) as f:
            return json.load(f).get("result") is not None
    except (OSError, ValueError):
        return False


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", required=True, help="directory of the records (created)")
    p.add_argument("names", nargs="*", help="cases to run (default: all): "
                   + ", ".join(name for name, _ in CASES))
    args = p.parse_args()
    known = [name for name, _ in CASES]
    unknown = [n for n in args.names if n not in known]
    if unknown:
        p.error(f"unknown case(s) {', '.join(unknown)}; known: {', '.join(known)}")
    verify = verify_binary()
    os.makedirs(args.out, exist_ok=True)
    commit = commit_of(ROOT)
    status = 0
    for name, flags in CASES:
        if args.names and name not in args.names:
            continue
        command = "verify pulloff " + " ".join(flags) + " --json"
        print(f"== {name}: {command}", file=sys.stderr, flush=True)
        run = subprocess.run([verify, "pulloff"] + flags + ["--json"], cwd=ROOT,
                             capture_output=True, text=True)
        record = {
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "command": command,
            "reproduce": "cargo run --release --quiet -- pulloff " + " ".join(flags) + " --json",
            "commit": commit,
        }
        try:
            # A sequence cut short still prints its ranges (with `stopped`), exit status 1.
            record["result"] = json.loads(run.stdout) if run.stdout.strip() else None
        except ValueError:
            record["result"] = None
        if record["result"] is None:
            del record["result"]
        if run.returncode != 0:
            lines = run.stderr.strip().splitlines() or [f"exit status {run.returncode}"]
            record["declined"] = lines[-1]
            print(f"declined, failed or cut short: {lines[-1]}", file=sys.stderr)
        target = os.path.join(args.out, name + ".json")
        if run.returncode != 0 and has_result(target):
            target = os.path.join(args.out, name + ".error.json")
            status = 1
        write_atomically(target, json.dumps(record, indent=1) + "\n")
    return status


if __name__ == "__main__":
    sys.exit(main())
