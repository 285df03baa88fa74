#!/usr/bin/env bash
# Install FEniCSx (Debian's python3-dolfinx, 0.5.2 on bookworm, with PETSc 3.18) and python3-gmsh
# when missing. Idempotent: does nothing if /usr/bin/python3 already imports dolfinx.
set -euo pipefail
if /usr/bin/python3 -c "import dolfinx" 2>/dev/null; then
  /usr/bin/python3 -c "import dolfinx; print('dolfinx', dolfinx.__version__, 'already installed')"
  exit 0
fi
export DEBIAN_FRONTEND=noninteractive
sudo_cmd=""
if [ "$(id -u)" != "0" ]; then sudo_cmd="sudo"; fi
$sudo_cmd apt-get update -qq
$sudo_cmd apt-get install -y -qq --no-install-recommends python3-dolfinx python3-gmsh >/dev/null
/usr/bin/python3 -c "import dolfinx; print('dolfinx', dolfinx.__version__, 'installed')"
