#!/usr/bin/env bash
# Stops what scripts/slurm/start-local-slurm.sh STATE_DIR started (munged is
# left running: other users of the machine may need it).
set -uo pipefail
state=$(realpath -m "${1:?usage: stop-local-slurm.sh STATE_DIR}")
for daemon in slurmd slurmctld; do
  pid=$(cat "$state/$daemon.pid" 2> /dev/null) || continue
  kill "$pid" 2> /dev/null
  for _ in $(seq 1 20); do
    kill -0 "$pid" 2> /dev/null || break
    sleep 0.25
  done
done
exit 0
