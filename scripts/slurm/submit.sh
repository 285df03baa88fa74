#!/usr/bin/env bash
# Submit a `verify` plan to Slurm: its shards as a job array (one shard per task) and the merge as
# a job that starts when every shard has ended (afterany: a shard whose jobs fail still leaves
# their error records, and the merge names them and exits 1).
#
# Usage: bash scripts/slurm/submit.sh [--nightly | --convergence ARGS...] [--shards N]
#                                      [--work DIR] [--wait] [-- SBATCH OPTIONS...]
#   --nightly        the nightly suite (`verify plan --nightly`); default: the default report
#   --shards N       tasks of the array (default 8; more than the plan's jobs leaves some idle)
#   --work DIR       directory for plan.tsv, results/, logs/ and report/ (default
#                    slurm-runs/<UTC date-time>); must be on a filesystem every node sees
#   --wait           block until the merge has ended and exit with its status (CI uses this)
#   -- OPTIONS       passed to every sbatch call, e.g. -- --partition=short --time=00:30:00
#                    --account=mylab --cpus-per-task=2
# On a real cluster: put the project (with target/release/verify, built on a node of the same
# architecture) on a shared filesystem, and install gmsh there too (bash scripts/install_gmsh.sh)
# if the plan's FEM jobs should use meshes made for the scene. Nothing else is needed on the nodes.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
plan_args=()
shards=8
work=""
wait_flag=()
extra=()
while [ $# -gt 0 ]; do
  case $1 in
    --nightly) plan_args+=(--nightly) ;;
    --convergence) plan_args+=(--convergence) ;;
    --punch|--method|--levels|--eps|--depth|--tol|--fem-tolerances) plan_args+=("$1" "$2"); shift ;;
    --shards) shards=$2; shift ;;
    --work) work=$2; shift ;;
    --wait) wait_flag=(--wait) ;;
    --) shift; extra=("$@"); break ;;
    *) echo "submit.sh: unknown option $1 (see the comment at the top of this script)" >&2; exit 2 ;;
  esac
  shift
done
case $shards in ''|*[!0-9]*|0) echo "submit.sh: --shards needs a positive whole number" >&2; exit 2 ;; esac
command -v sbatch >/dev/null || { echo "submit.sh: sbatch not found (no Slurm here; bash scripts/slurm/local_cluster.sh starts a one-node cluster)" >&2; exit 1; }
[ -n "$work" ] || work="slurm-runs/$(date -u +%Y%m%dT%H%M%S)"
mkdir -p "$work/logs" "$work/results"
work=$(cd "$work" && pwd)
cargo build --release --quiet --bin verify
verify="$root/target/release/verify"
"$verify" plan "${plan_args[@]}" --out "$work/plan.tsv"
export VERIFY="$verify" PLAN="$work/plan.tsv" RESULTS="$work/results" SHARDS="$shards" REPORT="$work/report"
array=$(sbatch --parsable --job-name=ringcontact-shard --array="1-$shards" --cpus-per-task=1 \
  --chdir="$root" --output="$work/logs/shard-%a.out" --export=ALL "${extra[@]}" \
  scripts/slurm/shard.sbatch)
array=${array%%;*}
echo "submitted shards: job array $array ($shards tasks), results in $work/results"
set +e
merge=$(sbatch --parsable --job-name=ringcontact-merge --dependency="afterany:$array" \
  --chdir="$root" --output="$work/logs/merge.out" --export=ALL "${extra[@]}" "${wait_flag[@]}" \
  scripts/slurm/merge.sbatch)
status=$?
set -e
echo "submitted merge: job ${merge%%;*} (after the array), report in $work/report, log $work/logs/merge.out"
if [ ${#wait_flag[@]} -gt 0 ]; then
  echo "merge ended with exit status $status"
  exit $status
fi
