#!/usr/bin/env python3
"""A rebuilt plugin never resumes its stale records (issue 41): builds a
copy of tests/out_of_tree/receiver_blur against a shadowbench build folder,
runs it into an --out through $SHADOWBENCH_PLUGIN_PATH, reruns unchanged
(the job resumes), then changes its filter in the source, rebuilds and
reruns into the same --out: the job must run again, the message must name
the plugin with both hashes, and the record's numbers and sha256 must be
the new plugin's. Run by ctest (tests/out_of_tree/CMakeLists.txt)."""
import argparse
import glob
import hashlib
import json
import os
import shutil
import subprocess
import sys

# One job, as small as receiver_blur gets: it shades the ground of a 2×2 grid.
CONFIG = {
    "name": "rebuilt_plugin",
    "scenes": [{"type": "sphere_grid", "params": {"grid": 2, "light_size": 2.0}}],
    "techniques": [{"name": "receiver_blur", "params": {"size": 64, "blur": 0.3}}],
    "resolutions": [[48, 36]],
    "frames": {"warmup": 0, "timed": 1, "control": None},
    "reference": {"spp": 16, "seed": 1, "cache": False},
}
# The tent's normalisation in the lookup shader: halving it darkens every
# blurred shadow, so the numbers must change.
FILTER_BEFORE = "clamp(sum / 16.0, 0.0, 1.0)"
FILTER_AFTER = "clamp(sum / 8.0, 0.0, 1.0)"


def run(what, *cmd, env=None):
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"{what} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def the_record(out):
    files = glob.glob(os.path.join(out, "records", "*.json"))
    if len(files) != 1:
        sys.exit(f"expected one record in {out}, found {files}")
    with open(files[0]) as f:
        r = json.load(f)
    if r["status"] != "ok":
        sys.exit(f"{files[0]}: {r['status']}: {r.get('reason')}")
    return r


def expect(text, output, what):
    if text not in output:
        sys.exit(f'{what}: expected "{text}" in:\n{output}')


def main():
    a = argparse.ArgumentParser()
    for name in ("source", "build", "exe", "work", "cxx", "cmake"):
        a.add_argument("--" + name, required=True)
    a = a.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    source = os.path.join(a.work, "receiver_blur")
    shutil.copytree(a.source, source)
    plugin_build = os.path.join(a.work, "build")
    run("configuring the plugin", a.cmake, "-S", source, "-B", plugin_build,
        "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + a.cxx,
        "-Dshadowbench_DIR=" + a.build)

    def build():
        run("building the plugin", a.cmake, "--build", plugin_build)
        return os.path.join(plugin_build, "receiver_blur.so")

    config = os.path.join(a.work, "config.json")
    with open(config, "w") as f:
        json.dump(CONFIG, f)
    out = os.path.join(a.work, "run")
    env = dict(os.environ, SHADOWBENCH_PLUGIN_PATH=plugin_build)

    def run_into_out():
        return run("shadowbench run", a.exe, "run", config, "--out", out, "--no-images",
                   "--quiet", env=env)

    so = build()
    first_hash = sha256(so)
    expect("1 ok, 0 skipped, 0 failed, 0 resumed", run_into_out(), "the first run")
    first = the_record(out)
    plugin = first["technique"]["plugin"]
    if plugin["file"] != "receiver_blur.so" or plugin["sha256"] != first_hash or \
            plugin["size"] != os.path.getsize(so):
        sys.exit(f"the record's plugin {plugin} is not {so} (sha256 {first_hash})")

    # Unchanged: resumed, nothing rerun.
    again = run_into_out()
    expect("0 ok, 0 skipped, 0 failed, 1 resumed", again, "an unchanged rerun")
    if "rerun" in again:
        sys.exit(f"an unchanged rerun reran something:\n{again}")

    # The filter changed, rebuilt: the job runs again, naming the plugin.
    path = os.path.join(source, "receiver_blur.cpp")
    with open(path) as f:
        text = f.read()
    if FILTER_BEFORE not in text:
        sys.exit(f"{path} no longer has {FILTER_BEFORE}: update this test")
    with open(path, "w") as f:
        f.write(text.replace(FILTER_BEFORE, FILTER_AFTER))
    so = build()
    second_hash = sha256(so)
    if second_hash == first_hash:
        sys.exit("the rebuilt plugin has the same bytes")
    rerun = run_into_out()
    expect("1 ok, 0 skipped, 0 failed, 0 resumed", rerun, "the rerun after the rebuild")
    expect(f"1 job rerun: plugin receiver_blur.so changed (sha256 {first_hash[:12]}.. -> "
           f"{second_hash[:12]}..)", rerun, "the rerun after the rebuild")
    second = the_record(out)
    if second["technique"]["plugin"]["sha256"] != second_hash:
        sys.exit(f"the record's sha256 {second['technique']['plugin']['sha256']} is not the "
                 f"rebuilt plugin's {second_hash}")
    before = first["metrics"]["visibility"]["all"]["rmse"]
    after = second["metrics"]["visibility"]["all"]["rmse"]
    print(f"visibility.all.rmse {before} -> {after}")
    if before == after:
        sys.exit(f"the rebuilt plugin's record kept the old numbers (rmse {before})")


if __name__ == "__main__":
    main()
