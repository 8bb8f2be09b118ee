#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for testing the sbatch scripts: munged, slurmctld
# and slurmd from Debian's slurm-wlm and munge, with every file (key, sockets, state, logs)
# under one folder and ports of their own, so nothing of the machine's is touched.
#   local_cluster.sh start DIR   starts the daemons; prints the SLURM_CONF to export
#   local_cluster.sh stop DIR    stops them (the folder stays, with the logs)
# Needs root (slurmd starts jobs as their users).
set -euo pipefail

action=${1:?usage: local_cluster.sh start|stop DIR}
dir=$(realpath -m "${2:?usage: local_cluster.sh start|stop DIR}")
host=$(hostname -s)
cpus=${LOCAL_CLUSTER_CPUS:-2}

stop_daemons() {
  for daemon in slurmd slurmctld munged; do
    if [ -f "$dir/$daemon.pid" ]; then
      pid=$(cat "$dir/$daemon.pid")
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null || true
      rm -f "$dir/$daemon.pid"
    fi
  done
}

case "$action" in
  stop)
    stop_daemons
    exit 0
    ;;
  start) ;;
  *)
    echo "local_cluster.sh: unknown action '$action' (start or stop)" >&2
    exit 2
    ;;
esac

mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
chmod 700 "$dir/munge"
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge/munge.key"
munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed" \
  --force

# Ports of our own, chosen by this shell's PID, away from Slurm's default 6817/6818.
port=$((20000 + ($$ % 20000)))
cat > "$dir/slurm.conf" <<CONF
ClusterName=markerbench
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SlurmdTimeout=60
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF" -i
slurmd -f "$SLURM_CONF" -N "$host"
# Ready once the node takes jobs.
for _ in $(seq 150); do
  state=$(sinfo -h -n "$host" -o %t 2>/dev/null || true)
  case "$state" in idle*|mix*|alloc*) echo "$SLURM_CONF"; exit 0 ;; esac
  sleep 0.2
done
echo "local_cluster.sh: the node did not come up (state '${state:-none}'); logs in $dir" >&2
stop_daemons
exit 1
