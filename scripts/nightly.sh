#!/usr/bin/env bash
# Nightly verification run: the full suite, the report in reports/<date>/, headline figures
# appended to reports/history.jsonl and compared with the previous run (accuracy beyond its
# tolerance or a time more than 1.5x slower is a regression: exit status 1).
# FEniCSx and the FFT-BEM peers are re-run when installed (scripts/fenicsx/setup.sh,
# scripts/peers/run_peers.sh); otherwise their stored results are used and marked as stored.
set -uo pipefail
cd "$(dirname "$0")/.."
day=$(date -u +%F)
out="reports/$day"
mkdir -p "$out"
cargo build --release --quiet || exit 1
fenicsx=stored
peers=stored
if /usr/bin/python3 -c "import dolfinx" 2>/dev/null; then
  if bash scripts/fenicsx/run_all.sh > "$out/fenicsx.log" 2>&1; then fenicsx=fresh; fi
fi
if [ -x .venv-peers/bin/python ] && .venv-peers/bin/python -c "import tamaas, ContactMechanics" 2>/dev/null; then
  if bash scripts/peers/run_peers.sh > "$out/peers.log" 2>&1; then peers=fresh; fi
fi
status=0
# The pull-off simulations (verify/pulloff/, 20 s to 3.5 min each, ~16 min; need gmsh), shown by the report.
if bash scripts/pulloff/run_all.sh > "$out/pulloff.log" 2>&1; then :; else status=1; fi
# The speed-accuracy charts run the FEM's full solve down to 1e-8 (7-17 s per state with gmsh meshing).
./target/release/verify compare --report "$out" --fem-tolerances 1e-3,1e-4,1e-6,1e-8 > "$out/summary.txt" || status=1
# FEniCSx on the largest meshes (6e5-1.4e6 unknowns, verify/fenicsx/large/: about a minute).
./target/release/verify fenicsx --large > "$out/fenicsx-large.txt" || status=1
./target/release/verify stability --json > "$out/stability.json" || status=1
./target/release/verify stability > "$out/stability.txt" || true
# The long fuzzing run (the default test run makes 20 000 inputs): 400 000 mutated meshes and scenes.
RINGCONTACT_FUZZ_CASES=400000 cargo test --release --quiet --test fuzz_inputs > "$out/fuzz.txt" 2>&1 || status=1
./target/release/verify history --report "$out" --history reports/history.jsonl --fenicsx "$fenicsx" --peers "$peers" || status=1
tail -n 3 "$out/summary.txt"
echo "report: $out/report.md (trend: $out/trend.md)"
exit $status
