#!/usr/bin/env bash
# The assembled operator compared with FEniCSx's (issue 12): for each mesh and degree, FEniCSx's
# export (scripts/fenicsx/export.py) and ours (`verify export`) are compared entry by entry, dofs
# matched by position, and the comparison is stored with provenance under verify/fenicsx/operators/
# (the matrices themselves, 0.3-250 MB of text, stay in a temporary directory).
# Needs FEniCSx (scripts/fenicsx/setup.sh) and, for the generated meshes, gmsh
# (scripts/install_gmsh.sh). Usage: bash scripts/fenicsx/run_operators.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
bash scripts/fenicsx/setup.sh >/dev/null
out=verify/fenicsx/operators
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cargo build --release --quiet --bin verify
compare() {
  # compare NAME MESH DEGREE
  local name=$1 mesh=$2 degree=$3
  /usr/bin/python3 scripts/fenicsx/export.py --mesh "$mesh" --degree "$degree" \
    --out "$work/$name/fenicsx" > "$work/$name.meta" 2>/dev/null
  ./target/release/verify export --mesh "$mesh" --degree "$degree" --out "$work/$name/ours" \
    --compare "$work/$name/fenicsx" --json > "$work/$name.json" || true
  /usr/bin/python3 - "$work/$name.json" "$work/$name/fenicsx/meta.json" "$out/$name.json" \
    "$mesh" "$degree" <<'PY'
import json, sys
comparison = json.load(open(sys.argv[1]))
meta = json.load(open(sys.argv[2]))
mesh, degree = sys.argv[4], sys.argv[5]
comparison.update({
    "dolfinx_version": meta["dolfinx_version"],
    "petsc_version": meta["petsc_version"],
    "fenicsx_lagrange_variant": meta["lagrange_variant"],
    "date": meta["date"],
    "reproduce": f"/usr/bin/python3 scripts/fenicsx/export.py --mesh {mesh} --degree {degree} "
                 f"--out F && verify export --mesh {mesh} --degree {degree} --out O --compare F",
})
with open(sys.argv[3], "w") as f:
    json.dump(comparison, f, indent=2)
    f.write("\n")
print(f"{sys.argv[3]}: K {comparison['stiffness_difference']:.1e}, "
      f"load {comparison['load_difference']:.1e}, {comparison['dofs']} dofs")
PY
  rm -rf "$work/$name"
}
generated() {
  # generated "VERIFY MESH ARGS": the relative path of the mesh gmsh makes
  ./target/release/verify mesh $1 | /usr/bin/python3 -c \
    "import json, os, sys; print(os.path.relpath(json.load(sys.stdin)['path']))"
}
for degree in 1 2 3; do
  compare "disk-L0-P$degree" meshes/disk-L0.msh "$degree"
done
compare annulus-0.5-L1-P2 meshes/annulus-0.5-L1.msh 2
compare annulus-0.9-L2-P2 meshes/annulus-0.9-L2.msh 2
if bash scripts/install_gmsh.sh >/dev/null 2>&1; then
  compare flat-annulus-0.3-adapted-L1-P3 "$(generated '--eps 0.3 --level 1')" 3
  compare cone-d2-adapted-L1-tol1e-6-P3 "$(generated '--level 1 --free-edge 0.4505268590 --edge-uncertainty 2.9e-5 --tol 1e-6 --degree 3')" 3
  compare flat-annulus-0.3-adapted-L2-P2 "$(generated '--eps 0.3 --level 2')" 2
fi
