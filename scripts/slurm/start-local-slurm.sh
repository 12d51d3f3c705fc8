#!/usr/bin/env bash
# A single-node Slurm on this machine, for tests and for trying the
# job-array workflow (docs/scale_out.md): munged, slurmctld and slurmd, all
# on localhost, with their config, state and logs in STATE_DIR. Needs root
# and Debian's slurm-wlm and munge. Prints the SLURM_CONF to export; stop it
# with scripts/slurm/stop-local-slurm.sh STATE_DIR.
set -euo pipefail
state=$(realpath -m "${1:?usage: start-local-slurm.sh STATE_DIR}")
mkdir -p "$state"/{spool,ctld,log}
host=$(hostname -s)
cpus=$(nproc)
mem_mb=$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)
cat > "$state/slurm.conf" <<CONF
ClusterName=shadowbench
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmdSpoolDir=$state/spool
StateSaveLocation=$state/ctld
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
NodeName=$host CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
CONF
# munged: Debian's package made /etc/munge/munge.key; start it unless one runs.
if ! pgrep -x munged > /dev/null; then
  mkdir -p /run/munge
  chown munge:munge /run/munge 2> /dev/null || true
  if id munge > /dev/null 2>&1; then
    runuser -u munge -- /usr/sbin/munged
  else
    /usr/sbin/munged --force
  fi
fi
export SLURM_CONF="$state/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
# Up when the node takes jobs.
for _ in $(seq 1 60); do
  if sinfo -h -o '%t' 2> /dev/null | grep -qE '^(idle|mix|alloc)'; then
    echo "SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.5
done
echo "start-local-slurm.sh: the node did not come up; see $state/log/" >&2
sinfo >&2 || true
exit 1
