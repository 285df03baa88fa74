#!/usr/bin/env bash
# Nightly verification run: the full suite into one report directory, its headline figures
# appended to a history file and compared with the previous run (an accuracy beyond its
# tolerance or a time more than 1.5x slower is a regression: exit status 1).
#
# Usage: bash scripts/nightly.sh [--out DIR] [--history FILE] [--quick] [--help]
#   --out DIR       the report directory (default reports/<UTC date>)
#   --history FILE  the JSON-lines history (default history.jsonl beside DIR: reports/history.jsonl)
#   --quick         the default report, the stability probes and fresh peer runs only (no pull-off
#                   simulations, no FEM at 1e-8, no FEniCSx on the largest meshes, no long
#                   fuzzing): a few minutes instead of about half an hour
#
# Fresh runs of the peers (FEniCSx when /usr/bin/python3 has dolfinx, Tamaas and ContactMechanics
# when .venv-peers has them) and of the pull-off simulations go into DIR/fresh/ and are compared
# with the committed baselines in verify/ (a difference beyond tolerance is a failed check in the
# report). Nothing in the checkout is written, and nothing is installed: the peers' setup scripts
# (scripts/fenicsx/setup.sh, scripts/peers/setup.sh, scripts/install_gmsh.sh) are run by hand.
# Refreshing a baseline is its own step: the peer's script with --out verify/..., reviewed and
# committed.
set -uo pipefail
self="$(cd "$(dirname "$0")" && pwd)/$(basename "$0")"
cd "$(dirname "$0")/.."
source scripts/lib.sh
out=""
history=""
quick=0
while [ $# -gt 0 ]; do
  case $1 in
    --out) out=$2; shift ;;
    --history) history=$2; shift ;;
    --quick) quick=1 ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$self"; exit 0 ;;
    *) echo "nightly.sh: unknown option $1 (see the comment at the top of this script)" >&2; exit 2 ;;
  esac
  shift
done
[ -n "$out" ] || out="reports/$(date -u +%F)"
[ -n "$history" ] || history="$(dirname "$out")/history.jsonl"
# The binary first: nothing is written when it cannot be built.
echo "nightly: building verify (cargo build --release: minutes on a fresh checkout)"
find_verify
mkdir -p "$out/fresh"
echo "nightly: report directory $out (binary $VERIFY, history $history)"
fenicsx=stored
peers=stored
status=0
failed=()
# failed STEP WHERE: a step that failed, named again at the end with the file that says why.
failed() {
  status=1
  failed+=("$1 (see $2)")
}
if /usr/bin/python3 -c "import dolfinx" 2>/dev/null; then
  echo "nightly: FEniCSx on every stored row -> $out/fresh/fenicsx"
  if python3 scripts/fenicsx/run_all.py --out "$out/fresh/fenicsx" > "$out/fenicsx.log" 2>&1; then
    fenicsx=fresh
  else
    failed "fresh FEniCSx runs" "$out/fenicsx.log"
  fi
fi
if [ -x .venv-peers/bin/python ] && .venv-peers/bin/python -c "import tamaas, ContactMechanics" 2>/dev/null; then
  echo "nightly: Tamaas and ContactMechanics -> $out/fresh/peers"
  if PYTHONPATH=scripts/peers .venv-peers/bin/python scripts/peers/run_peers.py \
    --out "$out/fresh/peers" > "$out/peers.log" 2>&1; then
    peers=fresh
  else
    failed "fresh Tamaas and ContactMechanics runs" "$out/peers.log"
  fi
fi
tolerances=1e-3,1e-4,1e-6
if [ $quick = 0 ]; then
  tolerances=1e-3,1e-4,1e-6,1e-8
  # The pull-off simulations (20 s to 3.5 min each, about 16 min; need gmsh).
  echo "nightly: pull-off simulations -> $out/fresh/pulloff"
  python3 scripts/pulloff/run_all.py --out "$out/fresh/pulloff" > "$out/pulloff.log" 2>&1 ||
    failed "pull-off simulations" "$out/pulloff.log"
fi
echo "nightly: the report (verify compare) -> $out"
"$VERIFY" compare --report "$out" --fresh "$out/fresh" --fem-tolerances "$tolerances" \
  > "$out/summary.txt" || failed "the report's checks" "$out/summary.txt"
if [ $quick = 0 ]; then
  # FEniCSx on the largest meshes (6e5-1.4e6 unknowns, verify/fenicsx/large/: about a minute).
  "$VERIFY" fenicsx --large > "$out/fenicsx-large.txt" ||
    failed "FEniCSx on the largest meshes" "$out/fenicsx-large.txt"
fi
echo "nightly: stability probes"
"$VERIFY" stability --json > "$out/stability.json" ||
  failed "stability probes" "$out/stability.json"
"$VERIFY" stability > "$out/stability.txt" || true
if [ $quick = 0 ]; then
  # The long fuzzing run (the default test run makes 20 000 inputs) and the stored results'
  # long reproduce commands (the largest meshes, the pull-off simulations).
  RINGCONTACT_FUZZ_CASES=400000 cargo test --release --quiet --test fuzz_inputs \
    > "$out/fuzz.txt" 2>&1 || failed "long fuzzing" "$out/fuzz.txt"
  cargo test --release --quiet --test reproduce -- --include-ignored \
    > "$out/reproduce.txt" 2>&1 || failed "long reproduce commands" "$out/reproduce.txt"
fi
"$VERIFY" history --report "$out" --history "$history" --fenicsx "$fenicsx" --peers "$peers" \
  || failed "the history's comparison with the previous run" "the lines above"
tail -n 3 "$out/summary.txt"
if [ -f "$out/index.html" ]; then
  echo "report: $out/index.html (trend: $out/trend.md)"
else
  failed "the report" "$out/summary.txt"
fi
if [ ${#failed[@]} -gt 0 ]; then
  echo "nightly: FAILED: ${#failed[@]} step(s):" >&2
  printf '  %s\n' "${failed[@]}" >&2
else
  echo "nightly: every step passed"
fi
exit $status
