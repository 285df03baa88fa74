#!/usr/bin/env bash
# Refresh the stored pull-off simulations (verify/pulloff/*.json): `verify pulloff --json` on the
# flat punch, two flat annuli and the concave punches at d0/h = 0.3, 1, 3, 10 (pressed until the
# hole closes; a range whose hole reopens is replaced by a smaller one), and the annular branch
# of both at d0/h = 0.3 and 1 and of the cone at 3 (--branch annular). Needs gmsh (bash
# scripts/install_gmsh.sh): each range of the closed branch runs on its own mesh (level 1 of the
# adapted family with a band at the rim refined to the cohesive zone; the check at level 0), each
# of the annular branch on level 3 with a uniform contact line. Each file holds the result, the
# date and the command. About 16 minutes on 2 cores.
# Cases the simulation declines are recorded with the reason.
# Usage: run_all.sh [NAME ...]   (e.g. cone-d0h0.3; default: every case)
set -uo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --quiet || exit 1
mkdir -p verify/pulloff
status=0
wanted=("$@")
run() {
  local name=$1; shift
  if [ ${#wanted[@]} -gt 0 ] && [[ ! " ${wanted[*]} " == *" $name "* ]]; then return; fi
  local cmd="verify pulloff $* --json"
  echo "== $name: $cmd"
  local out err
  err=$(mktemp)
  if out=$(./target/release/verify pulloff "$@" --json 2> "$err"); then
    RESULT="$out" CMD="$cmd" /usr/bin/env python3 - "verify/pulloff/$name.json" <<'PY'
import datetime, json, os, sys
record = {
    "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
    "command": os.environ["CMD"],
    "result": json.loads(os.environ["RESULT"]),
}
with open(sys.argv[1], "w") as f:
    json.dump(record, f, indent=1)
    f.write("\n")
PY
  else
    echo "declined or failed: $(tail -n 1 "$err")"
    CMD="$cmd" REASON="$(tail -n 1 "$err")" /usr/bin/env python3 - "verify/pulloff/$name.json" <<'PY'
import datetime, json, os, sys
record = {
    "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
    "command": os.environ["CMD"],
    "declined": os.environ["REASON"],
}
with open(sys.argv[1], "w") as f:
    json.dump(record, f, indent=1)
    f.write("\n")
PY
  fi
  rm -f "$err"
}
run flat --punch flat
run flat-annulus-0.5 --punch flat-annulus --eps 0.5
run flat-annulus-0.9 --punch flat-annulus --eps 0.9
for x in 0.3 1 3 10; do
  run "cone-d0h$x" --punch cone --d0h "$x"
  run "sphere-d0h$x" --punch sphere --d0h "$x"
done
# The annular branch (touched with the hole open, then pulled) where the JKR route has a stable
# annular contact (d0/h = 1), and where it has none (d0/h = 3: the hole closes, declined).
run cone-d0h1-annular --punch cone --d0h 1 --branch annular
run sphere-d0h1-annular --punch sphere --d0h 1 --branch annular
run cone-d0h3-annular --punch cone --d0h 3 --branch annular
# d0/h = 0.3: the annulus at pull-off is a few hundredths of a wide, narrower than the zone.
run cone-d0h0.3-annular --punch cone --d0h 0.3 --branch annular
run sphere-d0h0.3-annular --punch sphere --d0h 0.3 --branch annular
exit $status
