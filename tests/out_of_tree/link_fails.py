#!/usr/bin/env python3
"""A plugin with a symbol nothing defines fails to link with
shadowbench_add_plugin (-Wl,--no-undefined), naming the symbol; with the
symbol defined the same project links. Run by ctest
(tests/out_of_tree/CMakeLists.txt)."""
import argparse
import os
import shutil
import subprocess
import sys


def build(a, work, define_it):
    shutil.rmtree(work, ignore_errors=True)
    configure = subprocess.run(
        [a.cmake, "-S", a.source, "-B", work, "-DCMAKE_BUILD_TYPE=Release",
         "-DCMAKE_CXX_COMPILER=" + a.cxx, "-Dshadowbench_DIR=" + a.build,
         "-DDEFINE_IT=" + ("ON" if define_it else "OFF")], capture_output=True, text=True)
    if configure.returncode != 0:
        sys.exit(f"configuring failed:\n{configure.stdout}\n{configure.stderr}")
    return subprocess.run([a.cmake, "--build", work], capture_output=True, text=True)


def main():
    a = argparse.ArgumentParser()
    for name in ("source", "build", "work", "cxx", "cmake"):
        a.add_argument("--" + name, required=True)
    a = a.parse_args()
    defined = build(a, os.path.join(a.work, "defined"), True)
    if defined.returncode != 0:
        sys.exit(f"the control (symbol defined) does not link:\n{defined.stdout}\n{defined.stderr}")
    undefined = build(a, os.path.join(a.work, "undefined"), False)
    out = undefined.stdout + undefined.stderr
    if undefined.returncode == 0:
        sys.exit(f"a plugin with an undefined symbol linked:\n{out}")
    if "undefined reference" not in out or "sb_test_function_nobody_defines" not in out:
        sys.exit(f"the link failed, but not naming the undefined symbol:\n{out}")
    print("the undefined symbol failed the link, as it should")
    shutil.rmtree(a.work)


if __name__ == "__main__":
    main()
