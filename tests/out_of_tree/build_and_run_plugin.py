#!/usr/bin/env python3
"""Builds tests/out_of_tree/receiver_blur against a shadowbench build
folder's plugin API, as a user would (find_package(shadowbench)), then runs
its config through the driver beside the shipped plugins and checks the plan
and the records. Run by ctest (tests/out_of_tree/CMakeLists.txt)."""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys


def run(what, *cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{what} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def main():
    a = argparse.ArgumentParser()
    for name in ("source", "build", "exe", "shipped", "config", "work", "cxx", "cmake"):
        a.add_argument("--" + name, required=True)
    a = a.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    plugin_build = os.path.join(a.work, "build")
    run("configuring the plugin", a.cmake, "-S", a.source, "-B", plugin_build,
        "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + a.cxx,
        "-Dshadowbench_DIR=" + a.build)
    run("building the plugin", a.cmake, "--build", plugin_build)

    plugins = os.path.join(a.work, "plugins")
    os.makedirs(plugins)
    for so in glob.glob(os.path.join(a.shipped, "*.so")):
        shutil.copy(so, plugins)
    shutil.copy(os.path.join(plugin_build, "receiver_blur.so"), plugins)

    # The plan knows the plugin's own need, and skips what a scene cannot give.
    plan = run("shadowbench plan", a.exe, "plan", a.config, "--plugins", plugins)
    for expected in ("an orthonormal frame over the planar receiver (receiver_blur)"
                     " (built when run)",
                     "skip 96x72  receiver_blur"):
        if expected not in plan:
            sys.exit(f'the plan lacks "{expected}":\n{plan}')

    out = os.path.join(a.work, "run")
    run("shadowbench run", a.exe, "run", a.config, "--out", out, "--plugins", plugins,
        "--no-cache", "--quiet")
    rmse = {}
    for path in glob.glob(os.path.join(out, "records", "*.json")):
        with open(path) as f:
            r = json.load(f)
        tech, status = r["technique"]["name"], r["status"]
        if r["scene"]["type"] == "sphere_grid":
            if status != "ok":
                sys.exit(f"{path}: {status}: {r.get('reason')}")
            v = r["metrics"]["visibility"]
            rmse[tech] = (v["all"]["rmse"], v["penumbra"]["rmse"])
        elif tech == "receiver_blur" and status != "skipped":
            sys.exit(f"{path}: foliage's alpha-tested leaves should skip it, got {status}")
    print("RMSE (all, penumbra):", rmse)
    if "receiver_blur" not in rmse or "none" not in rmse:
        sys.exit("no record of the plugin, or of none, on the sphere grid")
    # A real shadow: far below no shadows at all, over every pixel and the
    # penumbra alike.
    for i, region in enumerate(("all", "penumbra")):
        if not rmse["receiver_blur"][i] < 0.5 * rmse["none"][i]:
            sys.exit(f"receiver_blur's {region} RMSE {rmse['receiver_blur'][i]} is not "
                     f"under half of no shadows' ({rmse['none'][i]})")


if __name__ == "__main__":
    main()
