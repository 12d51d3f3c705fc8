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
# clang-tidy gets one command per source: the unity builds' batches
# (tests/CMakeLists.txt) split back into their sources, and without GCC's
# precompiled header, which clang would try to read.
db=$(mktemp -d)
trap 'rm -rf "$db"' EXIT
python3 - build/compile_commands.json "$db/compile_commands.json" << 'EOF'
import json, re, sys
out = []
for c in json.load(open(sys.argv[1])):
    command = re.sub(r" -Winvalid-pch| -include \S*cmake_pch\.hxx", "", c["command"])
    sources = [c["file"]]
    if "/Unity/unity_" in c["file"]:
        sources = re.findall(r'#include "([^"]+)"', open(c["file"]).read())
    for source in sources:
        out.append({"directory": c["directory"], "file": source,
                    "command": command.replace(c["file"], source)})
json.dump(out, open(sys.argv[2], "w"))
EOF
# -Wno-restrict is a GCC-only flag in the compile commands.
printf '%s\n' "${files[@]}" |
  xargs -P "$(nproc)" -n 4 clang-tidy -p "$db" --quiet --extra-arg=-Wno-unknown-warning-option
