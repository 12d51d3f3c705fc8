#!/usr/bin/env python3
"""`shadowbench new-technique NAME` with no template option, built out of
tree against the build folder (find_package(shadowbench) through
-Dshadowbench_DIR, as its README says for a build folder) and run on the
sphere grid and on foliage, whose leaves are alpha-masked casters. A
technique that declares opaque_casters is skipped on foliage; the default
template must not be: every job of the new technique is run and ok on both
scenes, and casts a real shadow (its RMSE well under no shadows'). The
techniques are the scaffold's own config's; only its scenes and sizes are
the test's. Run by ctest (tests/out_of_tree/CMakeLists.txt)."""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys

NAME = "default_scaffold"


def run(what, *cmd, env=None):
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"{what} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def main():
    a = argparse.ArgumentParser()
    for name in ("build", "exe", "work", "cxx", "cmake"):
        a.add_argument("--" + name, required=True)
    a = a.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    env = {k: v for k, v in os.environ.items() if not k.startswith("SHADOWBENCH_")}
    folder = os.path.join(a.work, NAME)
    run("new-technique", a.exe, "new-technique", NAME, "--dir", folder, env=env)
    plugin_build = os.path.join(folder, "build")
    run("configuring the scaffold", a.cmake, "-S", folder, "-B", plugin_build,
        "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + a.cxx,
        "-Dshadowbench_DIR=" + a.build, env=env)
    run("building the scaffold", a.cmake, "--build", plugin_build, env=env)

    with open(os.path.join(folder, NAME + ".json")) as f:
        config = json.load(f)
    techniques = [t if isinstance(t, str) else t["name"] for t in config["techniques"]]
    if NAME not in techniques:
        sys.exit(f"the scaffold's config does not run {NAME}: {techniques}")
    if "none" not in techniques:  # the scale of "a real shadow" below
        config["techniques"].append("none")
    # Small, so that the test is short; the scaffold's techniques as written.
    config["scenes"] = [{"type": "sphere_grid", "params": {"grid": 2, "light_size": 2.0}},
                        {"type": "foliage", "params": {"trees": 1}}]
    config["resolutions"] = [[96, 72]]
    config["frames"] = {"warmup": 0, "timed": 2}
    config["reference"] = {"spp": 32, "seed": 1, "cache": False}
    path = os.path.join(a.work, "masked.json")
    with open(path, "w") as f:
        json.dump(config, f)

    env["SHADOWBENCH_PLUGIN_PATH"] = plugin_build
    out = os.path.join(a.work, "run")
    run("shadowbench run", a.exe, "run", path, "--out", out, "--no-cache", "--quiet", env=env)
    rmse = {}  # (scene type, technique) -> visibility RMSE
    for p in glob.glob(os.path.join(out, "records", "*.json")):
        with open(p) as f:
            r = json.load(f)
        key = (r["scene"]["type"], r["technique"]["name"])
        if key[1] in (NAME, "none"):
            if r["status"] != "ok":
                sys.exit(f"{p}: {key[1]} on {key[0]} is {r['status']}: {r.get('reason')}")
            rmse[key] = r["metrics"]["visibility"]["all"]["rmse"]
    print("visibility RMSE:", rmse)
    for scene in ("sphere_grid", "foliage"):
        if (scene, NAME) not in rmse or (scene, "none") not in rmse:
            sys.exit(f"no record of {NAME} or none on {scene}: {sorted(rmse)}")
        # A real shadow: far below no shadows at all.
        if not rmse[(scene, NAME)] < 0.5 * rmse[(scene, "none")]:
            sys.exit(f"{NAME}'s RMSE on {scene}, {rmse[(scene, NAME)]}, is not under half of "
                     f"no shadows' ({rmse[(scene, 'none')]})")


if __name__ == "__main__":
    main()
