#!/usr/bin/env python3
"""`shadowbench check-technique` on techniques of known conduct: a built-in
(pcss) and a plugin's technique that keeps the timing contract pass every
check (exit 0); a plugin's technique that renders its map once in
prepare() fails the light check, and one whose frames do nothing fails the
check that frames write V (exit 1, naming the check); an unknown technique
is bad input (exit 2). The plugin, contract_breaches/, is built out of tree
against the build folder's package as a user's would be. Run by ctest
(tests/out_of_tree/CMakeLists.txt); prints how long each step took."""
import argparse
import os
import shutil
import subprocess
import sys
import time


def run(what, cmd, expect, env=None):
    started = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    print(f"{what}: {time.monotonic() - started:.1f} s (exit {r.returncode})")
    out = r.stdout + r.stderr
    if r.returncode != expect:
        sys.exit(f"{what} exited {r.returncode}, expected {expect}:\n{out}")
    return out


def lines_with(out, status):
    return [l for l in out.splitlines() if l.startswith(status + "  ")]


def main():
    a = argparse.ArgumentParser()
    for name in ("source", "build", "exe", "work", "cxx", "cmake"):
        a.add_argument("--" + name, required=True)
    a = a.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    plugin = os.path.join(a.work, "build")
    run("configure the plugin",
        [a.cmake, "-S", a.source, "-B", plugin, "-DCMAKE_BUILD_TYPE=Release",
         "-DCMAKE_CXX_COMPILER=" + a.cxx, "-Dshadowbench_DIR=" + a.build], 0)
    run("build the plugin", [a.cmake, "--build", plugin], 0)
    # The plugin beside the built-ins, as its author would load it.
    env = dict(os.environ, SHADOWBENCH_PLUGIN_PATH=plugin)

    def check(name, expect):
        out = run(f"check-technique {name}", [a.exe, "check-technique", name], expect, env)
        print(out)
        return out

    for name in ("pcss", "kept_contract"):
        out = check(name, 0)
        if len(lines_with(out, "PASS")) != 5 or lines_with(out, "FAIL"):
            sys.exit(f"{name}: expected 5 checks passed and none failed:\n{out}")

    out = check("stale_map", 1)
    failed = "\n".join(lines_with(out, "FAIL"))
    if "keeps nothing of the light" not in failed or \
            "prepare() keeps something that depends on the light" not in out:
        sys.exit(f"stale_map (its map rendered in prepare()) passed the light check:\n{out}")

    out = check("idle_render", 1)
    failed = "\n".join(lines_with(out, "FAIL"))
    if "every frame writes V" not in failed or "6912 pixels NaN/Inf" not in out:
        sys.exit(f"idle_render (frames that draw nothing) passed the check that frames write "
                 f"V:\n{out}")

    out = run("check-technique no_such_technique",
              [a.exe, "check-technique", "no_such_technique"], 2, env)
    if "unknown technique" not in out:
        sys.exit(f"an unknown technique's error does not say so:\n{out}")
    out = run("check-technique pcss --param size=3",
              [a.exe, "check-technique", "pcss", "--param", "size=3"], 2, env)
    if "/params/size" not in out:
        sys.exit(f"an out-of-range --param's error does not name it:\n{out}")
    shutil.rmtree(a.work)


if __name__ == "__main__":
    main()
