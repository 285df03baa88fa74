#!/usr/bin/env bash
# Refresh every stored FEniCSx result of the default suite (verify/fenicsx/*.json).
# Installs FEniCSx first if needed (scripts/fenicsx/setup.sh). Run from anywhere.
set -euo pipefail
cd "$(dirname "$0")/../.."
bash scripts/fenicsx/setup.sh
out=verify/fenicsx
mkdir -p "$out"
run() { /usr/bin/python3 scripts/fenicsx/solve.py "$@"; }
for degree in 1 2; do
  run --punch flat --mesh meshes/disk-L1.msh --degree $degree --out $out/flat-disk-L1-P$degree.json
  run --punch flat-annulus --eps 0.5 --mesh meshes/annulus-0.5-L1.msh --degree $degree --out $out/flat-annulus-0.5-L1-P$degree.json
  run --punch flat-annulus --eps 0.9 --mesh meshes/annulus-0.9-L1.msh --degree $degree --out $out/flat-annulus-0.9-L1-P$degree.json
  run --punch cone --depth 2 --mesh meshes/disk-L1.msh --degree $degree --out $out/cone-d2-disk-L1-P$degree.json
  run --punch sphere --depth 1.5 --mesh meshes/disk-L1.msh --degree $degree --out $out/sphere-d1.5-disk-L1-P$degree.json
done
# One finer state, so the report shows FEniCSx on the mesh the default tolerance picks.
run --punch cone --depth 2 --mesh meshes/disk-L2.msh --degree 2 --out $out/cone-d2-disk-L2-P2.json
bash scripts/fenicsx/run_generated.sh
