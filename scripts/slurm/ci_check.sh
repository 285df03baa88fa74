#!/usr/bin/env bash
# CI's check of the Slurm route: start a one-node cluster on this machine (local_cluster.sh),
# submit the default report's plan through the real sbatch as a 2-task array with the merge as a
# dependent job (submit.sh --wait), and check the merged report: merge exit status 0 (every job
# present, no check failed) and a report.json with the verdicts. Stops the cluster at the end.
set -euo pipefail
cd "$(dirname "$0")/../.."
bash scripts/slurm/local_cluster.sh start
trap 'bash scripts/slurm/local_cluster.sh stop' EXIT
work=$(mktemp -d /tmp/ringcontact-slurm-XXXXXX)
start=$(date +%s)
if ! bash scripts/slurm/submit.sh --shards 2 --work "$work" --wait; then
  echo "slurm check: the merge failed; its log and the shards' logs:" >&2
  tail -n 30 "$work"/logs/*.out >&2 || true
  exit 1
fi
/usr/bin/env python3 - "$work/report/report.json" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
verdicts = report["extras"]["verdicts"]
assert verdicts, "no verdicts in the merged report"
assert len(report["comparison"]["rows"]) > 20, "the comparison is missing"
print(f"slurm check: merged report with {len(verdicts)} verdicts and "
      f"{len(report['comparison']['rows'])} comparison rows")
PY
echo "slurm check: plan, 2 shards and merge through sbatch in $(( $(date +%s) - start )) s ($work)"
