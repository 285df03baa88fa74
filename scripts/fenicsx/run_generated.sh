#!/usr/bin/env bash
# FEniCSx on meshes made by gmsh for the scene (the FEM's adapted family): each result stores the
# gmsh parameters that remake its mesh, and the harness remakes it (gmsh at run time) and checks
# its SHA-256 before comparing. Needs FEniCSx (scripts/fenicsx/setup.sh) and gmsh
# (scripts/install_gmsh.sh). Usage: bash scripts/fenicsx/run_generated.sh [--large]
# (--large adds the 10^5-10^6-unknown models of the cost table in the README, those above 5e5 in
# verify/fenicsx/large/; FENICSX_MPI=K solves those with `mpirun -n K`, PETSc's distributed
# solvers: see scripts/fenicsx/run_mpi.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
bash scripts/fenicsx/setup.sh
bash scripts/install_gmsh.sh >/dev/null
out=verify/fenicsx
cargo build --release --quiet --bin verify
launcher=()
run_generated() {
  # run_generated NAME "VERIFY MESH ARGS" SOLVE.PY ARGS...  (under ${launcher[@]} when set)
  local name=$1 mesh_args=$2
  shift 2
  local json path params
  json=$(./target/release/verify mesh $mesh_args)
  path=$(echo "$json" | /usr/bin/python3 -c "import json, os, sys; print(os.path.relpath(json.load(sys.stdin)['path']))")
  params=$(echo "$json" | /usr/bin/python3 -c "import json, sys; print(json.dumps(json.load(sys.stdin)['parameters']))")
  "${launcher[@]}" /usr/bin/python3 scripts/fenicsx/solve.py --mesh "$path" --mesh-parameters "$params" \
    --out "$out/$name.json" "$@"
}
run_generated flat-annulus-0.3-adapted-L0-P2 "--eps 0.3 --level 0" --punch flat-annulus --eps 0.3 --degree 2
run_generated flat-annulus-0.3-adapted-L1-P2 "--eps 0.3 --level 1" --punch flat-annulus --eps 0.3 --degree 2
run_generated flat-annulus-0.3-adapted-L1-P3 "--eps 0.3 --level 1" --punch flat-annulus --eps 0.3 --degree 3
run_generated cone-d2-adapted-L1-P2 "--level 1 --free-edge 0.4505" --punch cone --depth 2 --degree 2
# The meshes `--tol 1e-6` makes (cubic elements, rim and free-edge sizes from the tolerance): the
# flat annulus' two models, and the cone's finest one, refined around the free edge its level-0
# model locates (b/a = 0.4505268590, estimated to 2.9e-5).
run_generated flat-annulus-0.3-adapted-L0-tol1e-6-P3 "--eps 0.3 --level 0 --tol 1e-6 --degree 3" --punch flat-annulus --eps 0.3 --degree 3
run_generated flat-annulus-0.3-adapted-L1-tol1e-6-P3 "--eps 0.3 --level 1 --tol 1e-6 --degree 3" --punch flat-annulus --eps 0.3 --degree 3
run_generated cone-d2-adapted-L1-tol1e-6-P3 "--level 1 --free-edge 0.4505268590 --edge-uncertainty 2.9e-5 --tol 1e-6 --degree 3" --punch cone --depth 2 --degree 3
if [ "${1:-}" = "--large" ]; then
  k=${FENICSX_MPI:-1}
  if [ "$k" -gt 1 ]; then
    [ "$(id -u)" != 0 ] || export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    launcher=(mpirun -n "$k")
  fi
  run_generated flat-annulus-0.3-adapted-L2-P2 "--eps 0.3 --level 2" --punch flat-annulus --eps 0.3 --degree 2
  run_generated flat-annulus-0.3-adapted-L3-P2 "--eps 0.3 --level 3" --punch flat-annulus --eps 0.3 --degree 2
  # The top of the cost table, 6e5 to 1.4e6 unknowns (about 7 minutes on 2 cores, 6 GB): stored
  # apart, in verify/fenicsx/large/, compared by `verify fenicsx --large` and the nightly run.
  out=verify/fenicsx/large
  mkdir -p "$out"
  run_generated flat-annulus-0.3-adapted-L4-P2 "--eps 0.3 --level 4" --punch flat-annulus --eps 0.3 --degree 2
  run_generated flat-annulus-0.3-adapted-L4-P3 "--eps 0.3 --level 4" --punch flat-annulus --eps 0.3 --degree 3
  run_generated cone-d2-adapted-L4-P2 "--level 4 --free-edge 0.4505" --punch cone --depth 2 --degree 2
fi
