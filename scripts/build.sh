#!/usr/bin/env bash
# Configures (once) and builds shadowbench into build/ (Release): the one
# build folder of both README commands. run-quick.sh builds the driver and
# its plugins only; test.sh then builds the rest and reuses what is there.
#   scripts/build.sh [--target TARGET]... [-DVAR=VALUE]...
# --target: what to build (default: everything); -D: configure options.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=()
configure=()
while (($#)); do
  case "$1" in
    --target) targets+=(--target "$2"); shift 2 ;;
    *) configure+=("$1"); shift ;;
  esac
done
# Every test runs once (scripts/test.sh): the ones that drive Mesa ("gl") in
# this build, the others in the sanitizer build, or all of them here when
# SHADOWBENCH_SKIP_SANITIZERS=1. Decided here, so that both README commands
# configure build/ alike and neither rebuilds the other's work.
non_gl_tests=OFF
if [[ "${SHADOWBENCH_SKIP_SANITIZERS:-0}" == 1 ]]; then non_gl_tests=ON; fi
configure=(-DSHADOWBENCH_NON_GL_TESTS=$non_gl_tests "${configure[@]}")
generator=()
if command -v ninja > /dev/null; then generator=(-G Ninja); fi
if [[ ! -f build/CMakeCache.txt ]]; then
  cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${configure[@]}"
elif ! grep -qx "SHADOWBENCH_NON_GL_TESTS:BOOL=$non_gl_tests" build/CMakeCache.txt || ((${#configure[@]} > 1)); then
  cmake -S . -B build "${configure[@]}"
fi
cmake --build build -j"$(nproc)" "${targets[@]}"
