#!/usr/bin/env bash
# Tamaas and ContactMechanics on the grid BEM's problems, every case into --out DIR
# (scripts/peers/run_peers.py). Extra words: "adhesion" also runs Tamaas's adhesion functional on
# the pull-off cases into DIR/adhesion (scripts/peers/run_adhesion.py, about 10 min); "dugdale"
# its Maugis-Dugdale functional on the flat punch into DIR/dugdale (scripts/peers/run_dugdale.py,
# about 40 min); "speed" also
# times our grid BEM against Tamaas at 512 x 512, interleaved (scripts/peers/speed.py, its
# record in benches/records/). Needs the peers (bash scripts/peers/setup.sh); installs nothing.
# The committed baselines are verify/peers/: refresh with --out verify/peers, review, commit.
# Usage: bash scripts/peers/run_peers.sh --out DIR [adhesion] [dugdale] [speed]
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=.venv-peers
out=""
extra=()
while [ $# -gt 0 ]; do
  case $1 in
    --out) out=$2; shift ;;
    adhesion|dugdale|speed) extra+=("$1") ;;
    *) echo "run_peers.sh: unknown argument $1 (--out DIR, adhesion, dugdale, speed)" >&2; exit 2 ;;
  esac
  shift
done
[ -n "$out" ] || { echo "run_peers.sh: give --out DIR (verify/peers refreshes the baselines)" >&2; exit 2; }
if ! "$venv/bin/python" -c "import tamaas, ContactMechanics" 2>/dev/null; then
  echo "run_peers.sh: Tamaas and ContactMechanics are not in $venv: bash scripts/peers/setup.sh" >&2
  exit 1
fi
export PYTHONPATH=scripts/peers
"$venv/bin/python" scripts/peers/run_peers.py --out "$out"
for arg in "${extra[@]}"; do
  case $arg in
    adhesion) "$venv/bin/python" scripts/peers/run_adhesion.py --out "$out/adhesion" ;;
    dugdale) "$venv/bin/python" scripts/peers/run_dugdale.py --out "$out/dugdale" ;;
    speed) "$venv/bin/python" scripts/peers/speed.py ;;
  esac
done
