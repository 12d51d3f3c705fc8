#!/usr/bin/env python3
"""The guide's walkthrough technique, docs/examples/my_pcss (installed with
the docs; docs/writing_a_technique.md quotes its source), built out of tree
against the build folder (-Dshadowbench_DIR, as for the scaffold) and run
from its own config on the sphere grid and foliage, smaller: my_pcss and
pcss are ok on both scenes, my_pcss casts a real shadow (RMSE under half of
no shadows'), and its penumbra RMSE is finite and within a factor 3 of
pcss's, which takes the same estimate on grids of taps. my_pcss is
measurably worse than pcss on the sphere grid (2.4 times its penumbra error
at the test's size, 1.8 at the config's own) and better on foliage (0.8):
the guide's walkthrough says so. Run by ctest
(tests/out_of_tree/CMakeLists.txt). First, every C++ block the
guide's walkthrough quotes must be in the source built here."""
import argparse
import json
import math
import os
import re
import shutil
import sys

from small_masked_run import build_plugin, small_run

NAME = "my_pcss"
FACTOR = 3.0


def check_guide_quotes_source(guide, source):
    """Every C++ block of the guide's walkthrough is in my_pcss.cpp as it is,
    so that the code a reader copies is the code built here."""
    with open(guide) as f:
        text = f.read()
    start = text.index("## 6. Building a PCSS variant from the kit pieces")
    section = text[start:text.index("\n## 7. ", start)]
    blocks = re.findall(r"```cpp\n(.*?)```", section, re.S)
    if len(blocks) < 2:
        sys.exit(f"{guide}: the walkthrough quotes {len(blocks)} C++ blocks, expected its "
                 "includes and its technique")
    with open(source) as f:
        code = f.read()
    for b in blocks:
        if b not in code:
            sys.exit(f"{guide}: a C++ block of the walkthrough is not in {source}:\n{b}")


def main():
    a = argparse.ArgumentParser()
    for name in ("source", "guide", "build", "exe", "work", "cxx", "cmake"):
        a.add_argument("--" + name, required=True)
    a = a.parse_args()
    check_guide_quotes_source(a.guide, os.path.join(a.source, NAME + ".cpp"))
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    env = {k: v for k, v in os.environ.items() if not k.startswith("SHADOWBENCH_")}
    plugin_build = os.path.join(a.work, "build")
    build_plugin("my_pcss", a.source, plugin_build, a, env)

    with open(os.path.join(a.source, NAME + ".json")) as f:
        config = json.load(f)
    techniques = [t if isinstance(t, str) else t["name"] for t in config["techniques"]]
    for needed in (NAME, "pcss", "none"):
        if needed not in techniques:
            sys.exit(f"{NAME}.json does not run {needed}: {techniques}")
    scene_types = sorted(s["type"] for s in config["scenes"])
    if scene_types != ["foliage", "sphere_grid"]:
        sys.exit(f"{NAME}.json runs {scene_types}, not the sphere grid and foliage")
    # Small, so that the test is short; the config's techniques as written.
    records = small_run(config, a, env, plugin_build, 64, (NAME, "pcss", "none"))
    metrics = {key: r["metrics"]["visibility"] for key, r in records.items()}
    for scene in ("sphere_grid", "foliage"):
        mine = metrics[(scene, NAME)]["penumbra"]["rmse"]
        pcss = metrics[(scene, "pcss")]["penumbra"]["rmse"]
        print(f"{scene}: penumbra RMSE {NAME} {mine:.5f}, pcss {pcss:.5f}")
        if not math.isfinite(mine):
            sys.exit(f"{NAME}'s penumbra RMSE on {scene} is {mine}")
        if not pcss / FACTOR <= mine <= pcss * FACTOR:
            sys.exit(f"{NAME}'s penumbra RMSE on {scene}, {mine}, is not within a factor "
                     f"{FACTOR} of pcss's, {pcss}")
        if not metrics[(scene, NAME)]["all"]["rmse"] < 0.5 * metrics[(scene, "none")]["all"]["rmse"]:
            sys.exit(f"{NAME} casts no real shadow on {scene}: {metrics[(scene, NAME)]['all']}")


if __name__ == "__main__":
    main()
