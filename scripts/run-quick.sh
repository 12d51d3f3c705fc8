#!/usr/bin/env bash
# README command 1: install what is missing, build the driver and its
# plugins (not the tests nor the benchmarks: scripts/test.sh builds those in
# the same build/ later), and run the quick experiment on OSMesa. Results
# land in results/<run-id>/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh --target shadowbench
exec build/shadowbench run configs/quick.json --backend osmesa "$@"
