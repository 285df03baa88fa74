#!/usr/bin/env bash
# Regenerate the committed meshes in meshes/ (the FEM makes any other mesh itself at run time) with gmsh installed from PyPI into a local virtual
# environment (.venv-gmsh, ignored by git). Idempotent; needs python3 with venv and network access
# to PyPI on first use.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-gmsh
bash scripts/install_gmsh.sh >/dev/null
"$venv/bin/python" -c "import gmsh; print('gmsh', gmsh.__version__)"
"$venv/bin/python" scripts/make_meshes.py "$@"
