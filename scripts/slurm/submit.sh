#!/usr/bin/env bash
# Submits a shadowbench run as a Slurm job array of N shards, then a merge
# job that waits for all of them and writes OUT with its report
# (docs/scale_out.md):
#
#   scripts/slurm/submit.sh CONFIG OUT N [run options...]
#
# Shards write OUT-1 ... OUT-N (scripts/slurm/run-array.sh); the merge job
# runs `shadowbench merge OUT OUT-1 ... OUT-N` and `shadowbench report OUT`.
# It runs after the shards whatever their exit codes (a shard with a failed
# job still has records) and fails when a shard left no records.
# Prints the two job ids. $SHADOWBENCH is the driver (default: shadowbench
# on PATH); $SBATCH_OPTIONS adds sbatch options to both jobs (partition,
# time limit, account).
set -euo pipefail
config=${1:?usage: submit.sh CONFIG OUT N [run options...]}
out=${2:?usage: submit.sh CONFIG OUT N [run options...]}
n=${3:?usage: submit.sh CONFIG OUT N [run options...]}
shift 3
here=$(dirname "$(realpath "$0")")
driver=${SHADOWBENCH:-shadowbench}
# Check the config and the shard count before anything is queued.
"$driver" plan "$config" --shards "$n" > /dev/null
# shellcheck disable=SC2086
array=$(sbatch --parsable ${SBATCH_OPTIONS:-} --array="1-$n" \
  --export=ALL,SHADOWBENCH="$driver" "$here/run-array.sh" "$config" "$out" "$@")
array=${array%%;*}
shards=()
for k in $(seq 1 "$n"); do shards+=("$out-$k"); done
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTIONS:-} --job-name=shadowbench-merge \
  --dependency="afterany:$array" --output="$out-merge.out" \
  --wrap="$(printf '%q ' "$driver" merge "$out" "${shards[@]}") && $(printf '%q ' "$driver" report "$out")")
merge=${merge%%;*}
echo "shards: job $array (array 1-$n); merge: job $merge"
