#!/bin/bash
# A single-node Slurm on this machine for the sweep test: munge, slurmctld and
# slurmd with their configuration, state and logs under DIR, nothing in /etc.
#   local_slurm.sh start DIR   installs slurm-wlm and munge if missing (root),
#                              starts the daemons, waits until the node is idle;
#                              prints the SLURM_CONF to export
#   local_slurm.sh stop DIR    stops the daemons it started (by their pid files)
# Exit 77 from start: Slurm cannot run here (the reason is on stderr).
set -u
cmd=${1:?start or stop}
dir=${2:?state directory}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)

stop() {
  for d in slurmd slurmctld munged; do
    if [ -f "$dir/$d.pid" ]; then
      pid=$(cat "$dir/$d.pid")
      kill "$pid" 2>/dev/null
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null
      rm -f "$dir/$d.pid"
    fi
  done
}
if [ "$cmd" = stop ]; then stop; exit 0; fi

skip() { echo "local Slurm: $*" >&2; exit 77; }
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
  [ "$(id -u)" = 0 ] || skip "slurm-wlm and munge are not installed and this is not root, so they cannot be installed"
  (apt-get install -y --no-install-recommends slurm-wlm munge >"$dir/apt.log" 2>&1 ||
     { apt-get update >>"$dir/apt.log" 2>&1 && apt-get install -y --no-install-recommends slurm-wlm munge >>"$dir/apt.log" 2>&1; }) ||
    skip "apt-get could not install slurm-wlm and munge (see $dir/apt.log)"
fi
[ "$(id -u)" = 0 ] || skip "slurmd must run as root to start jobs as the submitting user; this is not root"

host=$(hostname -s)
# munge: our own key and socket, so a system munged (if any) is left alone.
dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none
chown munge:munge "$dir/munge.key" "$dir" 2>/dev/null; chmod 0400 "$dir/munge.key"
chmod 0755 "$dir"
mkdir -p "$dir/spool" "$dir/state"
munged --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
  --log-file="$dir/munged.log" --seed-file="$dir/munge.seed" --force 2>"$dir/munged.err" ||
  skip "munged did not start: $(cat "$dir/munged.err")"
cpus=$(nproc)
mem=$(awk '/MemTotal/ {print int($2 / 1024 / 2)}' /proc/meminfo)
cat >"$dir/slurm.conf" <<CONF
ClusterName=tumble-sweep-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.socket
SlurmctldPort=$((16817 + RANDOM % 1000))
SlurmdPort=$((17817 + RANDOM % 1000))
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
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=sweep Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
echo "" >"$dir/cgroup.conf"
export SLURM_CONF="$dir/slurm.conf"
slurmctld -c -f "$dir/slurm.conf" 2>"$dir/slurmctld.err" || { stop; skip "slurmctld did not start: $(cat "$dir/slurmctld.err")"; }
slurmd -f "$dir/slurm.conf" 2>"$dir/slurmd.err" || { stop; skip "slurmd did not start: $(cat "$dir/slurmd.err")"; }
for _ in $(seq 150); do
  state=$(sinfo -h -N -o %t 2>/dev/null | head -1)
  [ "$state" = idle ] && { echo "$SLURM_CONF"; exit 0; }
  sleep 0.2
done
echo "local Slurm: the node did not become idle within 30 s (state '${state:-none}'); logs in $dir" >&2
tail -5 "$dir/slurmctld.log" "$dir/slurmd.log" >&2
stop
exit 1
