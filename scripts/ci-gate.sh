#!/usr/bin/env bash
# The performance gate of `scripts/test.sh` (docs/ci.md, "The gate in this
# repository's CI"): run configs/ci.json and compare it with the committed
# baseline, whichever machine recorded it. Times are compared as ratios to
# the control job measured in the same run (--normalize control), so another
# CPU is not a regression; errors are compared as they are.
#   scripts/ci-gate.sh [BUILD_DIR] [extra compare options]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
# From docs/ci.md, "What the gate catches" (fixed_workload
# control): the largest shift of a job's ratio under the stand-ins for
# another machine (15.2 %) plus the 95th percentile of its run-to-run change
# (6.1 %), with margin. As committed: 0 of 20 unchanged runs failed, 20 of 20
# +50 % slowdowns caught, 0 of 20 +20 % ones.
threshold=${SHADOWBENCH_GATE_THRESHOLD:-0.30}
out=$(mktemp -d)/ci
"$build/shadowbench" run configs/ci.json --out "$out" --no-images --no-cache --quiet
"$build/shadowbench" compare results/baselines/ci "$out" --normalize control \
  --time-threshold "$threshold" "$@"
