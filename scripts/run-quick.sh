#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the quick
# experiment on OSMesa. Results land in results/<run-id>/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
exec build/shadowbench run configs/quick.json --backend osmesa "$@"
