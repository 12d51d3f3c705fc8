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
import json
import os
import shutil
import sys

from small_masked_run import build_plugin, run, small_run

NAME = "default_scaffold"


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
    build_plugin("the scaffold", folder, plugin_build, a, env)

    with open(os.path.join(folder, NAME + ".json")) as f:
        config = json.load(f)
    techniques = [t if isinstance(t, str) else t["name"] for t in config["techniques"]]
    if NAME not in techniques:
        sys.exit(f"the scaffold's config does not run {NAME}: {techniques}")
    if "none" not in techniques:  # the scale of "a real shadow" below
        config["techniques"].append("none")
    # Small, so that the test is short; the scaffold's techniques as written.
    records = small_run(config, a, env, plugin_build, 32, (NAME, "none"))
    rmse = {key: r["metrics"]["visibility"]["all"]["rmse"] for key, r in records.items()}
    print("visibility RMSE:", rmse)
    for scene in ("sphere_grid", "foliage"):
        # A real shadow: far below no shadows at all.
        if not rmse[(scene, NAME)] < 0.5 * rmse[(scene, "none")]:
            sys.exit(f"{NAME}'s RMSE on {scene}, {rmse[(scene, NAME)]}, is not under half of "
                     f"no shadows' ({rmse[(scene, 'none')]})")


if __name__ == "__main__":
    main()
