#!/usr/bin/env bash
# with_open_descriptors.sh FIRST LAST COMMAND...: runs COMMAND with
# descriptors FIRST to LAST open (on /dev/null), as some CI runners and IDEs
# start a process. The take-turns tests run once so (tests/run/CMakeLists.txt):
# compare-builds' pipes then land above 9, and must still reach a build at 3
# and 4.
set -euo pipefail
first=$1 last=$2
shift 2
for ((fd = first; fd <= last; ++fd)); do
  eval "exec $fd</dev/null"
done
exec "$@"
