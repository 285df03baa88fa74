#!/usr/bin/env bash
# The pull-off simulations of the stored cases: see scripts/pulloff/run_all.py (this is its
# shell entry). Usage: bash scripts/pulloff/run_all.sh --out DIR [NAME ...]
set -euo pipefail
exec python3 "$(dirname "$0")/run_all.py" "$@"
