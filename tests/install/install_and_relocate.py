#!/usr/bin/env python3
"""Installs a shadowbench build with `cmake --install` into a prefix, moves
the prefix, and uses it from there as a user would: --version names the moved
folders, the binaries carry no absolute RUNPATH, configs/quick.json's jobs run
(smaller) and `report` draws its charts; a technique family built against the moved
prefix's plugin API (find_package(shadowbench)) is found through
$SHADOWBENCH_PLUGIN_PATH beside the installed ones; the shadow-map kit's
headers and library are installed, with their reference
(docs/kit_reference.md, generated from them), and the shipped example built on it
(installed_example.py) measures as the built-in it copies. Run by ctest
(tests/install/CMakeLists.txt); prints how long each step took."""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import installed_example


def run(what, *cmd, env=None, cwd=None, expect=0):
    started = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=cwd)
    print(f"{what}: {time.monotonic() - started:.1f} s (exit {r.returncode})")
    if r.returncode != expect:
        sys.exit(f"{what} exited {r.returncode}, expected {expect}:\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def clean_env():
    """The user's environment, without anything that would point shadowbench
    or the loader back at the build tree."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("SHADOWBENCH_") and k != "LD_LIBRARY_PATH"}
    return env


def check_runpaths(prefix, build):
    """Every installed ELF file's RUNPATH is relative ($ORIGIN...)."""
    elves = [os.path.join(prefix, "bin", "shadowbench")]
    elves += glob.glob(os.path.join(prefix, "lib", "shadowbench", "*.so"))
    elves += glob.glob(os.path.join(prefix, "lib", "shadowbench", "plugins", "*.so"))
    if len(elves) < 10:
        sys.exit(f"expected the binary, two libraries and the plugins, found {elves}")
    for elf in elves:
        dynamic = subprocess.run(["readelf", "-d", elf], capture_output=True, text=True).stdout
        for line in dynamic.splitlines():
            if "RUNPATH" in line or "RPATH" in line:
                path = line.split("[", 1)[1].rstrip("]")
                for entry in path.split(":"):
                    if not entry.startswith("$ORIGIN"):
                        sys.exit(f"{elf}: RUNPATH entry {entry!r} is not relative to $ORIGIN")
                if build in path:
                    sys.exit(f"{elf}: RUNPATH names the build folder: {path}")


def check_shadow_kit(prefix, source):
    """The shadow-map kit: its library, and exactly its headers (every
    techniques/common/*.h of the source tree, nothing else) under
    include/shadowbench/common/, where "common/x.h" finds them."""
    library = os.path.join(prefix, "lib", "shadowbench", "libshadowbench_shadow_kit.a")
    if not os.path.isfile(library):
        sys.exit("the install lacks lib/shadowbench/libshadowbench_shadow_kit.a")
    headers = sorted(os.path.basename(h) for h in
                     glob.glob(os.path.join(source, "techniques", "common", "*.h")))
    installed_dir = os.path.join(prefix, "include", "shadowbench", "common")
    installed = sorted(os.listdir(installed_dir)) if os.path.isdir(installed_dir) else []
    if not headers or installed != headers:
        sys.exit(f"include/shadowbench/common holds {installed}, "
                 f"not the kit's headers {headers}")
    config = open(os.path.join(prefix, "lib", "shadowbench", "cmake",
                               "shadowbench-plugin-api-targets.cmake")).read()
    if "shadowbench::shadow_kit" not in config:
        sys.exit("the installed package config does not define shadowbench::shadow_kit")
    # Its reference, installed with the docs, is what the installed headers
    # declare (scripts/kit_reference.py names the first line that differs).
    reference = os.path.join(prefix, "share", "doc", "shadowbench", "kit_reference.md")
    r = subprocess.run([sys.executable, os.path.join(source, "scripts", "kit_reference.py"),
                        installed_dir, "--check", reference], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"the installed kit reference is not the installed headers':\n"
                 f"{r.stdout}{r.stderr}")


def main():
    a = argparse.ArgumentParser()
    for name in ("build", "source", "plugin-source", "cmake", "cxx"):
        a.add_argument("--" + name, required=True)
    # Two ctest entries, each under the 30 s of scripts/check-test-times.py
    # (the whole took 30-33 s in a clean-clone CI run): "run"
    # runs and reports from the moved prefix, "plugins" builds against it.
    a.add_argument("--part", choices=("run", "plugins"), required=True)
    a = a.parse_args()
    # Outside the build folder, so that no path of it can pass for the prefix.
    a.work = tempfile.mkdtemp(prefix="shadowbench-install-test-")
    started = time.monotonic()
    first = os.path.join(a.work, "first-prefix")
    run("cmake --install", a.cmake, "--install", a.build, "--prefix", first)
    prefix = os.path.join(a.work, "moved", "prefix")
    os.makedirs(os.path.dirname(prefix))
    shutil.move(first, prefix)
    exe = os.path.join(prefix, "bin", "shadowbench")
    env = clean_env()

    # Where it looks: the moved prefix, nothing of the build folder.
    version = run("shadowbench --version", exe, "--version", env=env)
    for expected in (f"plugins: {prefix}/lib/shadowbench/plugins\n",
                     f"data: {prefix}/share/shadowbench"):
        if expected not in version:
            sys.exit(f"--version lacks {expected!r}:\n{version}")
    if a.build in version:
        sys.exit(f"--version names the build folder:\n{version}")
    check_runpaths(prefix, a.build)
    # The man page shows the installed layout, never the build tree's folders.
    man = subprocess.run(["zcat", os.path.join(prefix, "share/man/man1/shadowbench.1.gz")],
                         capture_output=True, text=True, check=True).stdout
    if a.build in man or "<prefix>/lib/shadowbench/plugins" not in man:
        sys.exit("the man page names the build folder, or not the installed plugin folder:\n" +
                 "\n".join(line for line in man.splitlines() if "plugins" in line or "data:" in line))
    for path in ("share/shadowbench/plot_charts.py", "share/shadowbench/configs/quick.json",
                 "share/shadowbench/configs/models/jeep.glb", "share/man/man1/shadowbench.1.gz",
                 "share/bash-completion/completions/shadowbench",
                 "share/doc/shadowbench/README.md", "share/doc/shadowbench/cli.md",
                 "include/shadowbench/plugin/registry.h", "include/shadowbench/glad/gl.h",
                 "lib/shadowbench/cmake/shadowbenchConfig.cmake"):
        if not os.path.isfile(os.path.join(prefix, path)):
            sys.exit(f"the install lacks {path}")
    check_shadow_kit(prefix, a.source)
    # A message naming a doc names the moved prefix's copy, which a user of
    # the package has, not the source's docs/.
    out = run("an unknown name", exe, "list", "no_such_technique", env=env, expect=2)
    if f"{prefix}/share/doc/shadowbench/install.md" not in out:
        sys.exit(f"the unknown name's hint does not name the installed install.md:\n{out}")

    if a.part == "run":
        run_from_prefix(a, prefix, exe, env)
    else:
        build_against_prefix(a, prefix, exe, env)
    print(f"install test ({a.part}): {time.monotonic() - started:.1f} s in all")
    shutil.rmtree(a.work)


def run_from_prefix(a, prefix, exe, env):
    # The quick experiment's jobs from the installed configs, then its report:
    # at an eighth of its resolutions, two timed frames and a 16-spp
    # reference, since what is checked here (the moved prefix runs every job
    # and reports) does not depend on sizes: 9 s of CPU instead of 25 s
    # of this test's 33-47 s.
    run_dir = os.path.join(a.work, "quick")
    with open(os.path.join(prefix, "share", "shadowbench", "configs", "quick.json")) as f:
        quick = json.load(f)
    quick["resolutions"] = [[w // 8, h // 8] for w, h in quick["resolutions"]]
    quick["frames"] = {"warmup": 1, "timed": 2}
    quick["reference"]["spp"] = 16
    config = os.path.join(a.work, "quick.json")
    with open(config, "w") as f:
        json.dump(quick, f)
    run("shadowbench run configs/quick.json (smaller)", exe, "run", config, "--out", run_dir,
        "--no-cache", "--quiet", env=env, cwd=a.work)
    records = [json.loads(line) for line in open(os.path.join(run_dir, "results.jsonl"))]
    bad = [(r["job_id"], r["status"], r.get("reason")) for r in records
           if r["status"] not in ("ok", "skipped")]
    if not records or bad:
        sys.exit(f"quick.json from the moved prefix: {len(records)} records, not ok: {bad}")
    report = run("shadowbench report", exe, "report", run_dir, env=env, cwd=a.work)
    charts = glob.glob(os.path.join(run_dir, "report", "*.png"))
    if not charts or not os.path.isfile(os.path.join(run_dir, "report", "index.html")):
        sys.exit(f"report wrote no charts or no index.html:\n{report}")


def build_against_prefix(a, prefix, exe, env):
    # A family built against the moved prefix, found through the plugin path.
    plugin_build = os.path.join(a.work, "receiver_blur")
    run("configuring a plugin against the prefix", a.cmake, "-S", a.plugin_source, "-B",
        plugin_build, "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + a.cxx,
        "-DCMAKE_PREFIX_PATH=" + prefix, env=env)
    run("building it", a.cmake, "--build", plugin_build, env=env)
    env_with_plugin = dict(env, SHADOWBENCH_PLUGIN_PATH=f"/nonexistent-is-an-error:{plugin_build}")
    out = run("a missing plugin path entry", exe, "list", "--names", env=env_with_plugin,
              expect=3)
    if "/nonexistent-is-an-error" not in out or "SHADOWBENCH_PLUGIN_PATH" not in out:
        sys.exit(f"a missing folder in the plugin path is not named:\n{out}")
    env_with_plugin["SHADOWBENCH_PLUGIN_PATH"] = plugin_build
    names = run("list with the plugin path", exe, "list", "--names",
                env=env_with_plugin).split()
    for expected in ("receiver_blur", "shadow_map", "pcss", "sphere_grid"):
        if expected not in names:
            sys.exit(f"list --names lacks {expected}: {names}")
    # The same module twice (the plugin path names an installed folder) loads once.
    env_twice = dict(env, SHADOWBENCH_PLUGIN_PATH=os.path.join(prefix, "lib/shadowbench/plugins"))
    run("the installed folder in the plugin path", exe, "list", "--names", env=env_twice)
    # A second module registering a technique the first did: it fails to
    # load, with a warning naming both; the first keeps its techniques.
    clash = os.path.join(a.work, "clash")
    os.makedirs(clash)
    shutil.copy(os.path.join(prefix, "lib/shadowbench/plugins/shadow_map.so"),
                os.path.join(clash, "copy_of_shadow_map.so"))
    out = run("a technique registered twice", exe, "list", env=dict(
        env, SHADOWBENCH_PLUGIN_PATH=clash))
    if "warning: plugin " not in out or "copy_of_shadow_map.so" not in out or \
            "first by" not in out:
        sys.exit(f"the clash does not name both modules:\n{out}")

    # The shipped example, built from the prefix's copy, beside pcf_box.
    started_example = time.monotonic()
    installed_example.build_and_compare(prefix, a.work, a.cmake, a.cxx, env, run)
    print(f"the installed example my_pcf: {time.monotonic() - started_example:.1f} s")


if __name__ == "__main__":
    main()
