#!/usr/bin/env bash
# Install Tamaas and ContactMechanics from PyPI into .venv-peers (idempotent) and refresh the stored
# peer results in verify/peers/. Optional argument "speed": also run the 512 x 512 timing
# comparison with Tamaas (scripts/peers/speed.py).
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=.venv-peers
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import tamaas, ContactMechanics" 2>/dev/null; then
  "$venv/bin/pip" install --quiet "tamaas>=2.9" "contactmechanics>=1.8"
fi
PYTHONPATH=scripts/peers "$venv/bin/python" scripts/peers/run_peers.py
if [ "${1:-}" = "speed" ]; then
  cargo build --release --quiet
  PYTHONPATH=scripts/peers "$venv/bin/python" scripts/peers/speed.py
fi
