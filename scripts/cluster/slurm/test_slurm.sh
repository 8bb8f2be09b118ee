#!/usr/bin/env bash
# The Slurm route, for real: starts a one-node cluster on this machine (local_cluster.sh),
# submits scenarios/smoke.yaml as N = 4 shards with its merge job (submit.sh), waits, and
# compares the merged frames.csv with a local sweep byte for byte; then stops the daemons
# and removes everything it made.
#   test_slurm.sh MARKERBENCH_BINARY
# Exit 77 (ctest: skipped) when not root or without slurm-wlm and munge.
set -euo pipefail

markerbench=$(realpath "${1:?usage: test_slurm.sh MARKERBENCH_BINARY}")
here=$(dirname "$(realpath "$0")")
root=$(realpath "$here/../../..")
if [ "$(id -u)" -ne 0 ] || ! command -v slurmctld > /dev/null || ! command -v munged > /dev/null; then
  echo "test_slurm: skipped: needs root, slurm-wlm and munge (scripts/install-deps.sh)"
  exit 77
fi

work=$(mktemp -d /tmp/markerbench_slurm.XXXXXX)
cleanup() {
  bash "$here/local_cluster.sh" stop "$work/cluster" || true
  rm -rf "$work"
}
trap cleanup EXIT

SLURM_CONF=$(bash "$here/local_cluster.sh" start "$work/cluster")
export SLURM_CONF MARKERBENCH=$markerbench
scenario=$root/scenarios/smoke.yaml
"$markerbench" sweep "$scenario" --out "$work/local" --threads 2 2> "$work/local.log"

ids=$(bash "$here/submit.sh" 4 "$work/cluster_run" "$scenario")
merge=$(echo "$ids" | awk '$1 == "merge" {print $2}')
state=""
for _ in $(seq 1200); do  # up to 10 minutes
  state=$(scontrol show job "$merge" -o 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
  case "$state" in COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY) break ;; esac
  sleep 0.5
done
if [ "$state" != "COMPLETED" ]; then
  echo "test_slurm: the merge job ended as '${state:-unknown}'" >&2
  tail -n 20 "$work"/cluster_run/*.log "$work/cluster/slurmctld.log" >&2 || true
  exit 1
fi
for i in 0 1 2 3; do
  test -f "$work/cluster_run/shard-$i/smoke/run.json"
done
if ! cmp "$work/cluster_run/merged/smoke/frames.csv" "$work/local/smoke/frames.csv"; then
  echo "test_slurm: the merged frames.csv differs from the local sweep's" >&2
  exit 1
fi
"$markerbench" report "$work/cluster_run/merged" --no-plots
echo "test_slurm: 4 shards on Slurm merged to the local sweep's bytes" \
  "($(($(wc -l < "$work/local/smoke/frames.csv") - 1)) rows)"
