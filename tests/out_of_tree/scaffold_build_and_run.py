#!/usr/bin/env python3
"""`shadowbench new-technique` from an installed prefix, as a researcher
would use it: install the build into a temporary prefix, write a plugin
folder with the installed binary, build it with the three commands its
README gives (find_package(shadowbench) against the prefix, the plugin
loaded through $SHADOWBENCH_PLUGIN_PATH), run the config it wrote and check
the records: every job ok, and the new technique a real shadow, its
visibility RMSE within a factor of shadow_map's and its V under 0.5 where
the reference's is. Run by ctest (tests/out_of_tree/CMakeLists.txt)."""
import argparse
import glob
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile


NAME = "scaffolded_pcf"


def run(what, *cmd, env=None, cwd=None, shell=False):
    r = subprocess.run(cmd[0] if shell else cmd, capture_output=True, text=True, env=env,
                       cwd=cwd, shell=shell)
    if r.returncode != 0:
        sys.exit(f"{what} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r.stdout + r.stderr


def read_exr(path):
    """{(x, y): value} of a one-channel EXR, through oiiotool (openimageio-tools)."""
    text = run("oiiotool --dumpdata", "oiiotool", "--dumpdata", path)
    pixels = {}
    for m in re.finditer(r"Pixel \((\d+), (\d+)\): (\S+)", text):
        pixels[(int(m.group(1)), int(m.group(2)))] = float(m.group(3))
    if not pixels:
        sys.exit(f"no pixels read from {path}:\n{text[:500]}")
    return pixels


def main():
    a = argparse.ArgumentParser()
    for name in ("build", "cmake", "cxx"):
        a.add_argument("--" + name, required=True)
    a = a.parse_args()
    # Outside the build folder, so that nothing of it passes for the prefix.
    work = tempfile.mkdtemp(prefix="shadowbench-scaffold-test-")
    prefix = os.path.join(work, "prefix")
    run("cmake --install", a.cmake, "--install", a.build, "--prefix", prefix)
    exe = os.path.join(prefix, "bin", "shadowbench")
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("SHADOWBENCH_") and k != "LD_LIBRARY_PATH"}
    env["CXX"] = a.cxx
    # What the template must compile clean with (CMake reads CXXFLAGS once).
    env["CXXFLAGS"] = "-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Werror"
    env["PATH"] = os.path.dirname(a.cmake) + os.pathsep + env.get("PATH", "")

    folder = os.path.join(work, NAME)
    out = run("new-technique", exe, "new-technique", NAME, "--dir", folder, env=env)
    for f in (f"{NAME}.cpp", "CMakeLists.txt", f"{NAME}.json", "README.md"):
        if not os.path.isfile(os.path.join(folder, f)):
            sys.exit(f"new-technique wrote no {f}:\n{out}")

    # The README's three commands, as written (indented lines), run in order.
    with open(os.path.join(folder, "README.md")) as f:
        commands = [line[4:] for line in f.read().splitlines() if line.startswith("    ")]
    if len(commands) != 3 or "shadowbench" not in commands[2]:
        sys.exit(f"the README does not give build, load and run: {commands}")
    if prefix not in commands[0]:
        sys.exit(f"the README's build command does not name the installed prefix: {commands[0]}")
    script = " && ".join(commands)
    script += f" && cd results/{NAME} && ls records"
    run("the README's commands", "cd " + shlex.quote(folder) + " && " + script, env=env,
        shell=True)

    records = [json.load(open(p)) for p in
               glob.glob(os.path.join(folder, "results", NAME, "records", "*.json"))]
    by_technique = {}
    for r in records:
        if r["status"] != "ok":
            sys.exit(f"{r['job_id']}: {r['status']}: {r.get('reason')}")
        by_technique[r["technique"]["name"]] = r
    for expected in (NAME, "shadow_map", "pcf_box", "pcss"):
        if expected not in by_technique:
            sys.exit(f"no record of {expected}: {sorted(by_technique)}")
    rmse = {t: r["metrics"]["visibility"]["all"]["rmse"] for t, r in by_technique.items()}
    print("visibility RMSE:", rmse)
    # Its own frustum fit, not the built-ins': comparable, not equal. (A
    # 3×3 PCF measured 0.053 against shadow_map's 0.059 and pcf_box's 0.052.)
    if not 0 < rmse[NAME] < 1.5 * rmse["shadow_map"]:
        sys.exit(f"{NAME}'s RMSE {rmse[NAME]} is not within 1.5 times shadow_map's "
                 f"{rmse['shadow_map']}")

    # It casts a shadow: V < 0.5 on most pixels where the reference's is.
    run_dir = os.path.join(folder, "results", NAME)
    images = by_technique[NAME]["images"]
    v = read_exr(os.path.join(run_dir, images["visibility"]))
    v_ref = read_exr(os.path.join(run_dir, images["reference_visibility"]))
    shadowed = [p for p, value in v_ref.items() if value < 0.5]
    if len(shadowed) < 100:
        sys.exit(f"the reference has only {len(shadowed)} shadowed pixels")
    caught = sum(v[p] < 0.5 for p in shadowed) / len(shadowed)
    print(f"{NAME} shadows {caught:.3f} of the reference's {len(shadowed)} shadowed pixels")
    if caught < 0.95:
        sys.exit(f"{NAME} has V < 0.5 on only {caught:.3f} of the pixels the reference shadows")
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
