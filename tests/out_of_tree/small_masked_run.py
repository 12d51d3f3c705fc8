"""What the out-of-tree tests that build a plugin and run it on the sphere
grid and on foliage share: building it against the build folder, and a
small run of a config's techniques on those two scenes, read back."""
import glob
import json
import os
import subprocess
import sys


def run(what, *cmd, env=None):
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"{what} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def build_plugin(what, source, plugin_build, a, env):
    """Configures and builds the plugin in `source` against the build folder
    a.build (find_package(shadowbench) through -Dshadowbench_DIR)."""
    run("configuring " + what, a.cmake, "-S", source, "-B", plugin_build,
        "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + a.cxx,
        "-Dshadowbench_DIR=" + a.build, env=env)
    run("building " + what, a.cmake, "--build", plugin_build, env=env)


def small_run(config, a, env, plugin_build, spp, names):
    """Runs `config`'s techniques on a 2x2 sphere grid and one tree at 96x72
    (two timed frames, an `spp` reference) with the plugin folder
    `plugin_build` loaded; returns {(scene type, technique): record} of the
    techniques in `names`, every one of which must be ok."""
    config = dict(config)
    config["scenes"] = [{"type": "sphere_grid", "params": {"grid": 2, "light_size": 2.0}},
                        {"type": "foliage", "params": {"trees": 1}}]
    config["resolutions"] = [[96, 72]]
    config["frames"] = {"warmup": 0, "timed": 2}
    config["reference"] = {"spp": spp, "seed": 1, "cache": False}
    path = os.path.join(a.work, "small.json")
    with open(path, "w") as f:
        json.dump(config, f)
    env = dict(env, SHADOWBENCH_PLUGIN_PATH=plugin_build)
    out = os.path.join(a.work, "run")
    run("shadowbench run", a.exe, "run", path, "--out", out, "--no-cache", "--quiet", env=env)
    records = {}
    for p in glob.glob(os.path.join(out, "records", "*.json")):
        with open(p) as f:
            r = json.load(f)
        key = (r["scene"]["type"], r["technique"]["name"])
        if key[1] not in names:
            continue
        if r["status"] != "ok":
            sys.exit(f"{p}: {key[1]} on {key[0]} is {r['status']}: {r.get('reason')}")
        records[key] = r
    for scene in ("sphere_grid", "foliage"):
        for t in names:
            if (scene, t) not in records:
                sys.exit(f"no record of {t} on {scene}: {sorted(records)}")
    return records
