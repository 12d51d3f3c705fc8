#!/usr/bin/env bash
#SBATCH --job-name=shadowbench-shard
#SBATCH --output=shadowbench-%A_%a.out
# One shard of a shadowbench run, as one task of a Slurm job array
# (docs/scale_out.md). Submit it with --array=1-N, one task per shard:
#
#   sbatch --array=1-8 scripts/slurm/run-array.sh CONFIG OUT [run options...]
#
# Task K writes OUT-K with `run --shard K/N`. Run options go through (e.g.
# --cache-dir on a shared disk, so that shards compute each reference once).
# $SHADOWBENCH is the driver (default: shadowbench on PATH). Rerunning a
# task resumes its folder. scripts/slurm/submit.sh submits the array and the
# merge that follows it.
set -euo pipefail
config=${1:?usage: run-array.sh CONFIG OUT [run options...]}
out=${2:?usage: run-array.sh CONFIG OUT [run options...]}
shift 2
if [[ -z ${SLURM_ARRAY_TASK_ID:-} ]]; then
  echo "run-array.sh: not a Slurm array task: submit it with sbatch --array=1-N" >&2
  exit 2
fi
if [[ ${SLURM_ARRAY_TASK_MIN:-1} != 1 || ${SLURM_ARRAY_TASK_MAX} != "${SLURM_ARRAY_TASK_COUNT}" ]]; then
  echo "run-array.sh: expected --array=1-N (shards are numbered 1 to N), found" \
    "${SLURM_ARRAY_TASK_MIN}-${SLURM_ARRAY_TASK_MAX}" >&2
  exit 2
fi
shard="${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}"
echo "shadowbench shard $shard of $config on $(hostname) into $out-${SLURM_ARRAY_TASK_ID}"
exec "${SHADOWBENCH:-shadowbench}" run "$config" --shard "$shard" \
  --out "$out-${SLURM_ARRAY_TASK_ID}" --quiet "$@"
