#!/usr/bin/env python3
"""FEniCSx on every stored row: one result per row (scripts/fenicsx/solve.py), into --out.

The rows: the committed meshes (flat disk, annuli 0.5 and 0.9, cone, sphere and the power law
n = 1.5; P1, P2), the
meshes the FEM makes for the scene (adapted levels 0-3, the meshes of `--tol 1e-6`, P2 and P3),
two rows under `mpirun -n 2` (NAME-np2), and with --large the rows of 6e5-1.4e6 unknowns
(written under large/). Each is solved with the fastest configuration measured
(solve.py's default; --solver chooses another) and records it, with the command of ours that
solves the identical discrete problem (`reproduce`) and the command of its own (`peer_reproduce`).

Results are written through a temporary file and a rename. The committed baselines are
verify/fenicsx/; refresh them with `--out verify/fenicsx`, review the difference and commit it.
Needs FEniCSx (bash scripts/fenicsx/setup.sh) and, for the generated meshes, gmsh
(bash scripts/install_gmsh.sh); nothing is installed here.

Usage: python3 scripts/fenicsx/run_all.py --out DIR [--large] [--only NAME,...] [--solver S]
"""

import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from records import verify_binary  # noqa: E402

# (name, state arguments of solve.py, mesh: a committed file or `verify mesh` arguments, degree,
# processes, large)
ROWS = []
for degree in (1, 2):
    ROWS += [
        (f"flat-disk-L1-P{degree}", ["--punch", "flat"], "meshes/disk-L1.msh", degree, 1, False),
        (f"flat-annulus-0.5-L1-P{degree}", ["--punch", "flat-annulus", "--eps", "0.5"],
         "meshes/annulus-0.5-L1.msh", degree, 1, False),
        (f"flat-annulus-0.9-L1-P{degree}", ["--punch", "flat-annulus", "--eps", "0.9"],
         "meshes/annulus-0.9-L1.msh", degree, 1, False),
        (f"cone-d2-disk-L1-P{degree}", ["--punch", "cone", "--depth", "2"],
         "meshes/disk-L1.msh", degree, 1, False),
        (f"sphere-d1.5-disk-L1-P{degree}", ["--punch", "sphere", "--depth", "1.5"],
         "meshes/disk-L1.msh", degree, 1, False),
    ]
# The power-law punch n = 1.5 (gap h (1 - (r/a)^1.5)) at d = h, as the peers' grid runs.
POWER = ["--punch", "power", "--exponent", "1.5", "--depth", "1"]
ROWS += [
    ("power-n1.5-d1-disk-L1-P1", POWER, "meshes/disk-L1.msh", 1, 1, False),
    ("power-n1.5-d1-disk-L1-P2", POWER, "meshes/disk-L1.msh", 2, 1, False),
    ("power-n1.5-d1-disk-L2-P2", POWER, "meshes/disk-L2.msh", 2, 1, False),
]
ANNULUS = ["--punch", "flat-annulus", "--eps", "0.3"]
CONE = ["--punch", "cone", "--depth", "2"]
ROWS += [
    ("cone-d2-disk-L2-P2", CONE, "meshes/disk-L2.msh", 2, 1, False),
    ("cone-d2-disk-L2-P2-np2", CONE, "meshes/disk-L2.msh", 2, 2, False),
    ("flat-annulus-0.3-adapted-L0-P2", ANNULUS, "--eps 0.3 --level 0", 2, 1, False),
    ("flat-annulus-0.3-adapted-L1-P2", ANNULUS, "--eps 0.3 --level 1", 2, 1, False),
    ("flat-annulus-0.3-adapted-L1-P3", ANNULUS, "--eps 0.3 --level 1", 3, 1, False),
    ("flat-annulus-0.3-adapted-L2-P2", ANNULUS, "--eps 0.3 --level 2", 2, 1, False),
    ("flat-annulus-0.3-adapted-L3-P2", ANNULUS, "--eps 0.3 --level 3", 2, 1, False),
    ("flat-annulus-0.3-adapted-L3-P2-np2", ANNULUS, "--eps 0.3 --level 3", 2, 2, False),
    ("cone-d2-adapted-L1-P2", CONE, "--level 1 --free-edge 0.4505", 2, 1, False),
    # The meshes `--tol 1e-6` makes (cubic elements, rim and free-edge sizes from the tolerance):
    # the flat annulus' two models, and the cone's finest one, refined around the free edge its
    # level-0 model locates (b/a = 0.4505268590, estimated to 2.9e-5).
    ("flat-annulus-0.3-adapted-L0-tol1e-6-P3", ANNULUS,
     "--eps 0.3 --level 0 --tol 1e-6 --degree 3", 3, 1, False),
    ("flat-annulus-0.3-adapted-L1-tol1e-6-P3", ANNULUS,
     "--eps 0.3 --level 1 --tol 1e-6 --degree 3", 3, 1, False),
    ("cone-d2-adapted-L1-tol1e-6-P3", CONE,
     "--level 1 --free-edge 0.4505268590 --edge-uncertainty 2.9e-5 --tol 1e-6 --degree 3", 3, 1,
     False),
    # The top of the cost table (about 7 minutes on 2 cores, 6 GB).
    ("flat-annulus-0.3-adapted-L4-P2", ANNULUS, "--eps 0.3 --level 4", 2, 1, True),
    ("flat-annulus-0.3-adapted-L4-P3", ANNULUS, "--eps 0.3 --level 4", 3, 1, True),
    ("cone-d2-adapted-L4-P2", CONE, "--level 4 --free-edge 0.4505", 2, 1, True),
]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", required=True, help="directory of the results (created)")
    p.add_argument("--large", action="store_true", help="also the rows of 6e5-1.4e6 unknowns")
    p.add_argument("--only", help="these rows only (names, comma-separated)")
    p.add_argument("--solver", help="solve.py's --solver (default: its own)")
    args = p.parse_args()
    names = [r[0] for r in ROWS]
    only = args.only.split(",") if args.only else None
    if only and any(n not in names for n in only):
        p.error(f"unknown row(s) {[n for n in only if n not in names]}; known: {', '.join(names)}")
    if subprocess.run(["/usr/bin/python3", "-c", "import dolfinx"], capture_output=True).returncode:
        sys.exit("FEniCSx is not installed for /usr/bin/python3: bash scripts/fenicsx/setup.sh")
    verify = verify_binary()
    env = dict(os.environ)
    if os.getuid() == 0:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    status = 0
    for name, state, mesh, degree, processes, large in ROWS:
        if (only and name not in only) or (not only and large and not args.large):
            continue
        command = ["/usr/bin/python3", "scripts/fenicsx/solve.py"] + state
        command += ["--degree", str(degree)]
        if mesh.endswith(".msh"):
            command += ["--mesh", mesh]
        else:
            made = subprocess.run([verify, "mesh"] + mesh.split(), cwd=ROOT, capture_output=True,
                                  text=True)
            if made.returncode:
                sys.exit(f"{name}: verify mesh {mesh} failed: {made.stderr.strip()}")
            made = json.loads(made.stdout)
            command += ["--mesh", os.path.relpath(made["path"], ROOT),
                        "--mesh-parameters", made["mesh_parameters"]]
        if args.solver:
            command += ["--solver", args.solver]
        run_env = dict(env, OPENBLAS_NUM_THREADS="1" if processes > 1 else str(os.cpu_count()))
        if processes > 1:
            command = ["mpirun", "-n", str(processes)] + command
        out_dir = os.path.join(args.out, "large") if large else args.out
        os.makedirs(out_dir, exist_ok=True)
        command += ["--out", os.path.join(out_dir, name + ".json")]
        print(f"== {name}", file=sys.stderr, flush=True)
        if subprocess.run(command, cwd=ROOT, env=run_env).returncode:
            print(f"{name}: FEniCSx failed; its earlier result, if any, is untouched",
                  file=sys.stderr)
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main())
