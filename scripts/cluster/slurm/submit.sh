#!/usr/bin/env bash
# Submits a sharded markerbench sweep to Slurm: an array job of N shards (sweep.sbatch) and a
# merge job that runs once all of them succeeded (merge.sbatch, --dependency=afterok).
#   submit.sh N OUT SCENARIO.yaml... [-- MERGE_ARGS...]
# OUT must be on a file system every node sees. Prints the two job ids. sbatch's own
# variables (SBATCH_PARTITION, SBATCH_ACCOUNT, SBATCH_TIMELIMIT, ...) choose where they run;
# MARKERBENCH names the binary. Resume a failed shard I:
#   MARKERBENCH_SHARDS=N MARKERBENCH_OUT=OUT sbatch --array=I sweep.sbatch SCENARIO.yaml...
# then submit merge.sbatch again (with the same two variables).
set -euo pipefail

if [ "$#" -lt 3 ]; then
  echo "usage: submit.sh N OUT SCENARIO.yaml... [-- MERGE_ARGS...]" >&2
  exit 2
fi
shards=$1
out=$(realpath -m "$2")
shift 2
if ! [[ "$shards" =~ ^[1-9][0-9]*$ ]]; then
  echo "submit.sh: N: expected a whole number >= 1, got '$shards'" >&2
  exit 2
fi
scenarios=()
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  scenarios+=("$(realpath "$1")")
  shift
done
[ "${1:-}" = "--" ] && shift
here=$(dirname "$(realpath "$0")")
mkdir -p "$out"
export MARKERBENCH_SHARDS=$shards MARKERBENCH_OUT=$out
sweep=$(sbatch --parsable --array="0-$((shards - 1))" --chdir="$out" --export=ALL \
  "$here/sweep.sbatch" "${scenarios[@]}")
sweep=${sweep%%;*}  # "id;cluster" on federated clusters
merge=$(sbatch --parsable --dependency="afterok:$sweep" --kill-on-invalid-dep=yes \
  --chdir="$out" --export=ALL "$here/merge.sbatch" "$@")
echo "sweep $sweep"
echo "merge ${merge%%;*}"
