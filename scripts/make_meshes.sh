#!/usr/bin/env bash
# Regenerate every committed mesh in meshes/ with gmsh installed from PyPI into a local virtual
# environment (.venv-gmsh, ignored by git). Idempotent; needs python3 with venv and network access
# to PyPI on first use.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-gmsh
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import gmsh" 2>/dev/null; then
  "$venv/bin/pip" install --quiet "gmsh>=4.11"
fi
"$venv/bin/python" -c "import gmsh; print('gmsh', gmsh.__version__)"
"$venv/bin/python" scripts/make_meshes.py "$@"
