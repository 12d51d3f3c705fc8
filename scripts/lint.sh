#!/usr/bin/env bash
# clang-tidy (.clang-tidy: bug-finding checks, warnings are errors) on the
# given sources, or on every project .cpp; needs build/compile_commands.json.
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -f build/compile_commands.json ]] || scripts/build.sh
if (($# == 0)); then
  mapfile -t files < <(git ls-files '*.cpp')
else
  files=("$@")
fi
# -Wno-restrict is a GCC-only flag in the compile commands.
printf '%s\n' "${files[@]}" |
  xargs -P "$(nproc)" -n 4 clang-tidy -p build --quiet --extra-arg=-Wno-unknown-warning-option
