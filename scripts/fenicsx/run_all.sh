#!/usr/bin/env bash
# FEniCSx on every stored row: see scripts/fenicsx/run_all.py (this is its shell entry).
# Usage: bash scripts/fenicsx/run_all.sh --out DIR [--large] [--only NAME,...]
set -euo pipefail
exec python3 "$(dirname "$0")/run_all.py" "$@"
