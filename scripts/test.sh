#!/usr/bin/env bash
# README command 2: install what is missing, build, and pass every test:
#   1. clang-format check of the project's sources,
#   2. the Release build and its tests that drive Mesa (label "gl"), then
#      the performance gate (scripts/ci-gate.sh),
#   3. an ASan/UBSan build of the tests that do not drive Mesa's JIT
#      (every test without the label "gl").
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
phase_start=$SECONDS
# "== NAME" at each phase's start, and what the one before took, so that a
# slow CI names its slow part.
phase() {
  if [[ -n ${phase_name:-} ]]; then
    echo "== $phase_name took $((SECONDS - phase_start)) s"
  fi
  phase_name=$1
  phase_start=$SECONDS
  [[ -z $phase_name ]] || echo "== $phase_name"
}

phase "install what building needs"
scripts/install-deps.sh
# What only the tests need (Chromium, Slurm, scipy, ...) installs while the
# build runs: the first test starts after both.
extras_log=$(mktemp)
(
  scripts/install-deps.sh --test-only
  # The Khronos glTF validator for tests/gltf (skipped by the tests when absent).
  if command -v npm > /dev/null && [[ ! -f tools/gltf-validator/node_modules/gltf-validator/package.json ]]; then
    npm install --prefix tools/gltf-validator --no-save --no-audit --no-fund gltf-validator@2.0.0-dev.3.10 ||
      echo "warning: could not install gltf-validator; its test will be skipped"
  fi
) > "$extras_log" 2>&1 &
extras_pid=$!
wait_for_extras() {
  local rc=0
  wait "$extras_pid" || rc=$?
  echo "== what the tests need (installed during the build):"
  cat "$extras_log"
  if ((rc != 0)); then
    echo "test.sh: installing what the tests need failed (exit code $rc)" >&2
    exit "$rc"
  fi
}

phase "clang-format"
mapfile -t sources < <(git ls-files '*.cpp' '*.h' 2>/dev/null || find harness scenes techniques tests bench -name '*.cpp' -o -name '*.h')
clang-format --dry-run -Werror "${sources[@]}"

# Every test runs once: the ones that drive Mesa ("gl") in the Release build,
# the others under ASan/UBSan below (with SHADOWBENCH_SKIP_SANITIZERS=1, all
# in the Release build; scripts/build.sh configures build/ accordingly).
sanitize=1
if [[ "${SHADOWBENCH_SKIP_SANITIZERS:-0}" == 1 ]]; then sanitize=0; fi
phase "Release build"
scripts/build.sh
wait_for_extras
phase "Release tests"
ctest --test-dir build --output-on-failure -j2 --output-junit "$PWD/build/ctest-junit.xml"
# Names every entry slower than 30 s (run again alone first: the script's
# docstring says why), and prints the five slowest.
scripts/check-test-times.py build/ctest-junit.xml --test-dir build

# configs/ci.json against the committed baseline, as ratios to the control
# job, so that it holds on any CPU (docs/ci.md, "The gate in this repository").
phase "performance gate"
scripts/ci-gate.sh build

if [[ $sanitize == 1 ]]; then
  phase "ASan/UBSan build"
  generator=()
  if command -v ninja > /dev/null; then generator=(-G Ninja); fi
  if [[ ! -f build-asan/CMakeCache.txt ]]; then
    # -g1 (line tables): the sanitizers' reports keep file and line, and a
    # heavy file compiles in 28 s instead of 36 s (harness/run/runner.cpp).
    # -O1, the level ASan's documentation suggests: tests/gltf/test_gltf_import.cpp
    # compiles in 25 s instead of 40 s at -O2 (2-core VM), and
    # this build is most of CI's time.
    cmake -S . -B build-asan "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
      -DSHADOWBENCH_SANITIZE=ON -DSHADOWBENCH_BUILD_BENCHMARKS=OFF
  fi
  cmake --build build-asan -j"$(nproc)"
  phase "ASan/UBSan tests (those without the label 'gl')"
  export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
  ctest --test-dir build-asan --output-on-failure -LE gl -j2 \
    --output-junit "$PWD/build-asan/ctest-junit.xml"
  scripts/check-test-times.py build-asan/ctest-junit.xml --test-dir build-asan
fi
phase ""
echo "== test.sh: every phase passed in $((SECONDS - start)) s"
