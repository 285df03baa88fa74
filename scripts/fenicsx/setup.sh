#!/usr/bin/env bash
# Install FEniCSx as a competent user would run it here: Debian's python3-dolfinx (0.5.2 on
# bookworm, with PETSc 3.18, MUMPS and SuiteSparse's CHOLMOD), python3-gmsh, and OpenBLAS
# (libopenblas0-pthread: Debian's default reference BLAS makes MUMPS's and CHOLMOD's dense
# kernels several times slower). Idempotent: installs only what is missing. Needs root or sudo.
set -euo pipefail
missing=()
/usr/bin/python3 -c "import dolfinx" 2>/dev/null || missing+=(python3-dolfinx python3-gmsh)
dpkg -s libopenblas0-pthread >/dev/null 2>&1 || missing+=(libopenblas0-pthread)
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  sudo_cmd=""
  if [ "$(id -u)" != "0" ]; then sudo_cmd="sudo"; fi
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
/usr/bin/python3 -c "import dolfinx; print('dolfinx', dolfinx.__version__)"
# The tests that need dolfinx are ignored when the build found none (build.rs): touching build.rs
# makes the next build look again.
touch "$(cd "$(dirname "$0")/../.." && pwd)/build.rs"
