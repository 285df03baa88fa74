#!/usr/bin/env bash
# Install Tamaas and ContactMechanics from PyPI into .venv-peers (ignored by git). Idempotent.
# Tamaas's PyPI wheel is its serial C++ backend (tamaas.TamaasInfo.backend = 'cpp').
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=.venv-peers
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
if ! "$venv/bin/python" -c "import tamaas, ContactMechanics" 2>/dev/null; then
  "$venv/bin/pip" install --quiet "tamaas>=2.9" "contactmechanics>=1.8"
fi
"$venv/bin/python" -c "import tamaas, ContactMechanics; print('tamaas', tamaas.__version__, '; ContactMechanics', ContactMechanics.__version__)"
