#!/bin/bash
# A private single-node Slurm cluster on this machine, for tests.
#
#   tests/slurm/cluster.sh start DIR   munged, slurmctld and slurmd with all
#                                      state, sockets, logs and the config
#                                      under DIR (ports from DIR's process id
#                                      so parallel test runs do not meet);
#                                      prints `export SLURM_CONF=DIR/slurm.conf`
#   tests/slurm/cluster.sh stop DIR    stops the three daemons (by their pid
#                                      files) and waits for them to go
#
# Needs root (slurmd runs jobs as their user), munge and slurm-wlm (Debian
# packages in the Makefile's APT_PKGS).  start exits 1 naming the daemon
# and its log's last lines when one does not come up.
set -u
cmd=${1:?usage: cluster.sh start|stop DIR}
dir=${2:?usage: cluster.sh start|stop DIR}

stop() {
    for d in slurmd slurmctld munged; do
        [ -f "$dir/$d.pid" ] || continue
        pid=$(cat "$dir/$d.pid")
        kill "$pid" 2>/dev/null
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2>/dev/null
        rm -f "$dir/$d.pid"
    done
}

fail() {
    echo "cluster.sh: $1 did not start; last lines of $2:" >&2
    tail -n 5 "$2" >&2 2>/dev/null
    stop
    exit 1
}

if [ "$cmd" = stop ]; then
    stop
    exit 0
fi
[ "$cmd" = start ] || { echo "usage: cluster.sh start|stop DIR" >&2; exit 2; }
for b in munged slurmctld slurmd sbatch squeue; do
    command -v "$b" >/dev/null || { echo "cluster.sh: $b not installed (make deps)" >&2; exit 1; }
done
mkdir -p "$dir/state" "$dir/spool" "$dir/log"
chmod 700 "$dir"
host=$(hostname)
base=$((20000 + ($$ % 10000) * 2))
dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$dir/munge.key"
# the node's memory (90% of MemTotal, in MB: slurmd drains a node that has
# less than it is said to have), so that a job's --mem fits
mem=$(awk '/^MemTotal:/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)
cat > "$dir/slurm.conf" <<CONF
ClusterName=dflabtest
SlurmctldHost=$host
SlurmctldPort=$base
SlurmdPort=$((base + 1))
AuthType=auth/munge
AuthInfo=socket=$dir/munge.sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
MessageTimeout=30
NodeName=$host CPUs=$(nproc) RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
munged --socket="$dir/munge.sock" --key-file="$dir/munge.key" --pid-file="$dir/munged.pid" \
    --log-file="$dir/log/munged.log" --seed-file="$dir/munge.seed" -f \
    || fail munged "$dir/log/munged.log"
export SLURM_CONF=$dir/slurm.conf
slurmctld || fail slurmctld "$dir/log/slurmctld.log"
slurmd -N "$host" || fail slurmd "$dir/log/slurmd.log"
for _ in $(seq 100); do
    if sinfo -h -o '%t' 2>/dev/null | grep -q idle; then
        echo "export SLURM_CONF=$dir/slurm.conf"
        exit 0
    fi
    sleep 0.2
done
fail "slurmd (node not idle after 20 s)" "$dir/log/slurmd.log"
