#!/usr/bin/env bash
# Install gmsh from PyPI into the project's own environment .venv-gmsh (ignored by git), where the
# FEM finds it at run time (crates/ringcontact/src/mesh/gmsh.rs). Idempotent; needs python3 with venv and PyPI access
# the first time. Pinned: generated meshes are cached and compared by content, and stored
# FEniCSx results on generated meshes name their SHA-256. Prints the installed version.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-gmsh
if [ ! -x "$venv/bin/python" ]; then
  if ! python3 -m venv "$venv" 2>/dev/null; then
    # Debian's python3 needs python3-venv for `python3 -m venv`.
    if command -v apt-get >/dev/null 2>&1; then
      apt-get update -qq && apt-get install -y -qq python3-venv >/dev/null
      rm -rf "$venv"
      python3 -m venv "$venv"
    else
      echo "install_gmsh.sh: python3 -m venv failed (install python3-venv)" >&2
      exit 1
    fi
  fi
fi
if ! "$venv/bin/python" -c "import gmsh" 2>/dev/null; then
  "$venv/bin/pip" install --quiet "gmsh==4.15.2"
fi
"$venv/bin/python" "$venv/bin/gmsh" --version
# The tests that need gmsh are ignored when the build found none (build.rs): touching build.rs
# makes the next build look again.
touch build.rs
