#!/usr/bin/env python3
"""Compare two `report.json` files of `verify` runs: every number equal to a relative tolerance
(default 1e-10), every other value equal, timings aside (keys naming wall time, seconds, speed,
dates). Prints the differences and exits 1 if there are any.

Usage: python3 scripts/compare_reports.py OLD/report.json NEW/report.json [--tol 1e-10]
"""
import argparse
import json
import re
import sys

TIMING = re.compile(
    r"(wall|time|_s$|seconds|_ms|speed|elapsed|timings|duration|per_second|rate|started|"
    r"finished|generated|date)",
    re.I,
)


def walk(old, new, path, tol, out, counted):
    """Append `(path, what)` for each difference of `old` and `new` under `path`."""
    if isinstance(old, dict) and isinstance(new, dict):
        for key in sorted(set(old) | set(new)):
            if TIMING.search(key):
                continue
            if key not in old or key not in new:
                out.append((f"{path}/{key}", "missing in " + ("old" if key not in old else "new")))
                continue
            walk(old[key], new[key], f"{path}/{key}", tol, out, counted)
    elif isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            out.append((path, f"length {len(old)} against {len(new)}"))
        for i, (a, b) in enumerate(zip(old, new)):
            walk(a, b, f"{path}[{i}]", tol, out, counted)
    else:
        counted[0] += 1
        numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (old, new))
        if numbers:
            if old != new and abs(old - new) > tol * max(abs(old), abs(new)):
                out.append((path, f"{old!r} against {new!r}"))
        elif old != new:
            out.append((path, f"{str(old)[:80]!r} against {str(new)[:80]!r}"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--tol", type=float, default=1e-10)
    args = parser.parse_args()
    with open(args.old) as f:
        old = json.load(f)
    with open(args.new) as f:
        new = json.load(f)
    out, counted = [], [0]
    walk(old, new, "", args.tol, out, counted)
    print(f"{counted[0]} values compared, {len(out)} differences (relative tolerance {args.tol:g})")
    for path, what in out[:100]:
        print(f"  {path}: {what}")
    sys.exit(1 if out else 0)


if __name__ == "__main__":
    main()
