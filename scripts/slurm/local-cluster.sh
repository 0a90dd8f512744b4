#!/usr/bin/env bash
# A single-node Slurm cluster on localhost for the sweep's job-array test: munged, slurmctld
# and slurmd, all run from DIR (configuration, sockets, state, logs), as the current user.
#
#   scripts/slurm/local-cluster.sh start DIR   # prints `export SLURM_CONF=DIR/slurm.conf`
#   scripts/slurm/local-cluster.sh stop DIR
#
# `start` exits non-zero with the daemons' own error lines when the cluster cannot come up.
set -euo pipefail
action=${1:?start or stop}
dir=$(realpath -m "${2:?a folder for the cluster}")
port=${SLURM_TEST_PORT:-16817}

stop() {
  local pids=()
  for file in "$dir"/slurmd.pid "$dir"/slurmctld.pid "$dir"/munged.pid; do
    [ -s "$file" ] && pids+=("$(cat "$file")")
  done
  [ ${#pids[@]} -gt 0 ] || return 0
  kill "${pids[@]}" 2>/dev/null || true
  # Wait until they are gone, so that the ports are free for the next cluster.
  for _ in $(seq 1 50); do
    kill -0 "${pids[@]}" 2>/dev/null || return 0
    sleep 0.2
  done
}

if [ "$action" = stop ]; then
  stop
  exit 0
fi

mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
user=$(id -un)
cpus=$(nproc)
key="$dir/munge/munge.key"
[ -s "$key" ] || { dd if=/dev/urandom of="$key" bs=1024 count=1 status=none; chmod 600 "$key"; }
cat > "$dir/slurm.conf" <<CONF
ClusterName=millimpact-local
SlurmctldHost=localhost
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
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
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
NodeName=localhost NodeHostname=localhost CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF

munged --force --socket="$dir/munge/munge.socket" --key-file="$key" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed" \
  2>>"$dir/munged.log" || { echo "munged cannot start:"; tail -n 5 "$dir/munged.log"; exit 1; }
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF" 2>>"$dir/slurmctld.log" || true
slurmd -N localhost -f "$SLURM_CONF" 2>>"$dir/slurmd.log" || true
# Up to 30 s for the node to be idle. Each query has a time limit (a controller that cannot
# answer makes sinfo wait for its message time-out), and a daemon that logged a fatal error
# will not come up: waiting stops there.
deadline=$((SECONDS + 30))
while [ "$SECONDS" -lt "$deadline" ]; do
  if timeout 3 sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then
    echo "export SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  if grep -qs 'fatal' "$dir/slurmctld.log" "$dir/slurmd.log"; then
    break
  fi
  sleep 0.5
done
echo "the single-node Slurm did not come up; the daemons said:"
grep -hiE 'error|fatal' "$dir/slurmctld.log" "$dir/slurmd.log" | tail -n 10
stop
exit 1
