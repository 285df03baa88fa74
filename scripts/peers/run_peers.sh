#!/usr/bin/env bash
# Install Tamaas and ContactMechanics from PyPI into .venv-peers (idempotent) and refresh the stored
# peer results in verify/peers/. Optional arguments: "speed" also runs the 512 x 512 timing
# comparison with Tamaas (scripts/peers/speed.py); "adhesion" also runs Tamaas's adhesion
# functional on the pull-off cases (scripts/peers/run_adhesion.py -> verify/peers/adhesion/,
# about 10 min on 2 cores).
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
for arg in "$@"; do
  case $arg in
    adhesion) PYTHONPATH=scripts/peers "$venv/bin/python" scripts/peers/run_adhesion.py ;;
    speed)
      cargo build --release --quiet
      PYTHONPATH=scripts/peers "$venv/bin/python" scripts/peers/speed.py ;;
    *) echo "run_peers.sh: unknown argument $arg (speed, adhesion)" >&2; exit 2 ;;
  esac
done
