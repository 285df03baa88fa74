#!/usr/bin/env bash
# FEniCSx under MPI: the largest stored models solved with `mpirun -n K` (PETSc's distributed
# vectors and matrices, MUMPS's distributed LU; the contact problem by the same SNES VI), stored
# as verify/fenicsx/NAME-npK.json beside the serial results. The harness compares every stored
# result with our FEM on the identical problem (`verify fenicsx`: force within 1e-8, same active
# set), so the distributed run is checked against the serial one through it. Prints the wall time
# at K = 1 and each K given, and the force difference to the serial run.
# Usage: bash scripts/fenicsx/run_mpi.sh [K ...]      (default: 2; needs FEniCSx and gmsh)
set -euo pipefail
cd "$(dirname "$0")/../.."
bash scripts/fenicsx/setup.sh
bash scripts/install_gmsh.sh >/dev/null
cargo build --release --quiet --bin verify
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(2)
if [ "$(id -u)" = 0 ]; then
  # OpenMPI refuses root unless told (CI and containers run as root).
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
out=verify/fenicsx
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mesh_of() { ./target/release/verify mesh "$@" | /usr/bin/python3 -c "import json, os, sys; print(os.path.relpath(json.load(sys.stdin)['path']))"; }
params_of() { ./target/release/verify mesh "$@" | /usr/bin/python3 -c "import json, sys; print(json.dumps(json.load(sys.stdin)['parameters']))"; }
annulus_mesh=$(mesh_of --eps 0.3 --level 3)
annulus_params=$(params_of --eps 0.3 --level 3)
printf '%-36s %9s %3s %10s %22s %12s\n' model unknowns K wall_s force "vs K=1"
solve() {
  # solve NAME K SOLVE.PY ARGS...
  local name=$1 k=$2
  shift 2
  local target="$scratch/$name-np$k.json"
  if [ "$k" -gt 1 ]; then
    target="$out/$name-np$k.json"
    mpirun -n "$k" /usr/bin/python3 scripts/fenicsx/solve.py --out "$target" "$@" >/dev/null
  else
    /usr/bin/python3 scripts/fenicsx/solve.py --out "$target" "$@" >/dev/null
  fi
  /usr/bin/python3 - "$name" "$k" "$target" "$scratch/$name-np1.json" <<'PY'
import json, sys
name, k, path, serial = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
r = json.load(open(path))
s = json.load(open(serial))
diff = (r["force"] - s["force"]) / s["force"]
print(f"{name:<36} {r['dofs']:>9} {k:>3} {r['wall_s']:>10.2f} {r['force']:>22.15g} {diff:>12.1e}")
PY
}
for k in 1 "${counts[@]}"; do
  solve cone-d2-disk-L2-P2 "$k" --punch cone --depth 2 --mesh meshes/disk-L2.msh --degree 2
  solve flat-annulus-0.3-adapted-L3-P2 "$k" --punch flat-annulus --eps 0.3 --mesh "$annulus_mesh" \
    --mesh-parameters "$annulus_params" --degree 2
done
