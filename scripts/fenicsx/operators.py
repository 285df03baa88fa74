#!/usr/bin/env python3
"""Our assembled operator against FEniCSx's: stiffness matrix and unit-pressure load, entry by
entry, dofs matched by position (FEniCSx's export by scripts/fenicsx/export.py, ours and the
comparison by `verify export --compare`).

One comparison, printed as JSON (what a stored comparison's `reproduce` runs):
    python3 scripts/fenicsx/operators.py --mesh meshes/disk-L0.msh --degree 2
    python3 scripts/fenicsx/operators.py --mesh-parameters a=1,b=0.3,... --degree 3
Every stored comparison, one JSON each into a directory (the committed baselines are
verify/fenicsx/operators/; refresh them with `--out verify/fenicsx/operators`, review, commit):
    python3 scripts/fenicsx/operators.py --out DIR
The matrices (0.3-250 MB of text) stay in a temporary directory. Needs FEniCSx (bash
scripts/fenicsx/setup.sh) and, for generated meshes, gmsh; nothing is installed here.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from records import verify_binary, write_atomically  # noqa: E402

# (name, mesh: a committed file or `verify mesh` arguments, degree)
CASES = [(f"disk-L0-P{k}", "meshes/disk-L0.msh", k) for k in (1, 2, 3)] + [
    ("annulus-0.5-L1-P2", "meshes/annulus-0.5-L1.msh", 2),
    ("annulus-0.9-L2-P2", "meshes/annulus-0.9-L2.msh", 2),
    ("flat-annulus-0.3-adapted-L1-P3", "--eps 0.3 --level 1", 3),
    ("cone-d2-adapted-L1-tol1e-6-P3",
     "--level 1 --free-edge 0.4505268590 --edge-uncertainty 2.9e-5 --tol 1e-6 --degree 3", 3),
    ("flat-annulus-0.3-adapted-L2-P2", "--eps 0.3 --level 2", 2),
]


def mesh_file(verify, mesh=None, parameters=None, request=None):
    """(path relative to the root, parameters text or None) of the mesh to compare on."""
    if mesh:
        return mesh, None
    args = ["--parameters", parameters] if parameters else request.split()
    made = subprocess.run([verify, "mesh"] + args, cwd=ROOT, capture_output=True, text=True)
    if made.returncode:
        sys.exit(f"verify mesh {' '.join(args)} failed: {made.stderr.strip()}")
    out = json.loads(made.stdout)
    return os.path.relpath(out["path"], ROOT), out["mesh_parameters"]


def compare(verify, mesh, parameters, degree):
    """The comparison record of one mesh and degree."""
    with tempfile.TemporaryDirectory() as work:
        fenicsx_dir = os.path.join(work, "fenicsx")
        subprocess.run(["/usr/bin/python3", "scripts/fenicsx/export.py", "--mesh", mesh,
                        "--degree", str(degree), "--out", fenicsx_dir], cwd=ROOT, check=True,
                       stdout=subprocess.DEVNULL)
        ours = subprocess.run([verify, "export", "--mesh", mesh, "--degree", str(degree),
                               "--compare", fenicsx_dir, "--json"], cwd=ROOT,
                              capture_output=True, text=True)
        if not ours.stdout.strip():
            sys.exit(f"verify export failed on {mesh}: {ours.stderr.strip()}")
        comparison = json.loads(ours.stdout)
        with open(os.path.join(fenicsx_dir, "meta.json")) as f:
            meta = json.load(f)
    where = f"--mesh-parameters {parameters}" if parameters else f"--mesh {mesh}"
    comparison.update({
        "dolfinx_version": meta["dolfinx_version"],
        "petsc_version": meta["petsc_version"],
        "fenicsx_lagrange_variant": meta["lagrange_variant"],
        "date": meta["date"],
        "reproduce": f"python3 scripts/fenicsx/operators.py {where} --degree {degree}",
    })
    return comparison


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mesh", help="a gmsh .msh file")
    p.add_argument("--mesh-parameters", help="NAME=VALUE,... of meshes/half_space.geo")
    p.add_argument("--degree", type=int, choices=[1, 2, 3], default=2)
    p.add_argument("--out", help="every stored comparison into this directory")
    args = p.parse_args()
    if bool(args.out) == bool(args.mesh or args.mesh_parameters):
        p.error("give --out DIR (every comparison) or --mesh/--mesh-parameters (one)")
    if subprocess.run(["/usr/bin/python3", "-c", "import dolfinx"], capture_output=True).returncode:
        sys.exit("FEniCSx is not installed for /usr/bin/python3: bash scripts/fenicsx/setup.sh")
    verify = verify_binary()
    if not args.out:
        mesh, parameters = mesh_file(verify, args.mesh, args.mesh_parameters)
        print(json.dumps(compare(verify, mesh, parameters, args.degree), indent=2))
        return 0
    os.makedirs(args.out, exist_ok=True)
    for name, where, degree in CASES:
        if where.endswith(".msh"):
            mesh, parameters = where, None
        else:
            mesh, parameters = mesh_file(verify, request=where)
        record = compare(verify, mesh, parameters, degree)
        write_atomically(os.path.join(args.out, name + ".json"), json.dumps(record, indent=2) + "\n")
        print(f"{name}: K {record['stiffness_difference']:.1e}, load "
              f"{record['load_difference']:.1e}, {record['dofs']} dofs", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
