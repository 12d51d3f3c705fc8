#!/usr/bin/env python3
"""`shadowbench new-technique` from an installed prefix, as a researcher
would use it: install the build into a temporary prefix, write a plugin
folder with the installed binary, build it with the three commands its
README gives (find_package(shadowbench) against the prefix, the plugin
loaded through $SHADOWBENCH_PLUGIN_PATH), run the config it wrote and check
the records: every job ok, and the new technique a real shadow (V under 0.5
where the reference's is). --bare (--family plugin_api, its own frustum
fit) must be within a factor of shadow_map's RMSE; the default (--family
shadow_map, on the shadow-map kit) must equal pcf_box's V and RMSE, since it
is pcf_box's filter on pcf_box's frustum, depth pass and lookup. Run by ctest
(tests/out_of_tree/CMakeLists.txt)."""
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


NAME = "scaffolded_pcf"  # --bare (--family plugin_api)
KIT_NAME = "scaffolded_kit_pcf"  # the default (--family shadow_map)


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


class Scaffolded:
    """The run of one new-technique folder: its records by technique."""

    def __init__(self, run_dir, records):
        self.run_dir = run_dir
        self.records = records
        self.rmse = {t: r["metrics"]["visibility"]["all"]["rmse"] for t, r in records.items()}

    def params(self, technique):
        return self.records[technique]["technique"]["params"]

    def visibility(self, technique, image="visibility"):
        return read_exr(os.path.join(self.run_dir, self.records[technique]["images"][image]))

    def check_casts_shadow(self, name):
        """V < 0.5 on most pixels where the reference's is."""
        v = self.visibility(name)
        v_ref = self.visibility(name, "reference_visibility")
        shadowed = [p for p, value in v_ref.items() if value < 0.5]
        if len(shadowed) < 100:
            sys.exit(f"the reference has only {len(shadowed)} shadowed pixels")
        caught = sum(v[p] < 0.5 for p in shadowed) / len(shadowed)
        print(f"{name} shadows {caught:.3f} of the reference's {len(shadowed)} shadowed pixels")
        if caught < 0.95:
            sys.exit(f"{name} has V < 0.5 on only {caught:.3f} of the pixels the reference "
                     "shadows")


def scaffold(work, exe, env, prefix, family, name):
    """new-technique NAME (with --bare for FAMILY plugin_api), then the
    README's three commands as written (its indented lines, in order); every
    job must be ok."""
    folder = os.path.join(work, name)
    flags = ["--bare"] if family == "plugin_api" else []
    out = run("new-technique", exe, "new-technique", name, *flags, "--dir", folder, env=env)
    for f in (f"{name}.cpp", "CMakeLists.txt", f"{name}.json", "README.md"):
        if not os.path.isfile(os.path.join(folder, f)):
            sys.exit(f"new-technique --family {family} wrote no {f}:\n{out}")
    with open(os.path.join(folder, "README.md")) as f:
        commands = [line[4:] for line in f.read().splitlines() if line.startswith("    ")]
    if len(commands) != 3 or "shadowbench" not in commands[2]:
        sys.exit(f"the {family} README does not give build, load and run: {commands}")
    if prefix not in commands[0]:
        sys.exit(f"the {family} README's build command does not name the installed prefix: "
                 f"{commands[0]}")
    run(f"the {family} README's commands",
        "cd " + shlex.quote(folder) + " && " + " && ".join(commands), env=env, shell=True)
    run_dir = os.path.join(folder, "results", name)
    by_technique = {}
    for p in glob.glob(os.path.join(run_dir, "records", "*.json")):
        r = json.load(open(p))
        if r["status"] != "ok":
            sys.exit(f"{r['job_id']}: {r['status']}: {r.get('reason')}")
        by_technique[r["technique"]["name"]] = r
    for expected in (name, "shadow_map", "pcf_box"):
        if expected not in by_technique:
            sys.exit(f"no record of {expected} in the {family} run: {sorted(by_technique)}")
    result = Scaffolded(run_dir, by_technique)
    print(f"--family {family}: visibility RMSE {result.rmse}")
    return result


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

    plugin_api = scaffold(work, exe, env, prefix, "plugin_api", NAME)
    # Its own frustum fit, not the built-ins': comparable, not equal. (A
    # 3×3 PCF measured 0.053 against shadow_map's 0.059 and pcf_box's 0.052.)
    rmse = plugin_api.rmse
    if not 0 < rmse[NAME] < 1.5 * rmse["shadow_map"]:
        sys.exit(f"{NAME}'s RMSE {rmse[NAME]} is not within 1.5 times shadow_map's "
                 f"{rmse['shadow_map']}")
    plugin_api.check_casts_shadow(NAME)

    # The default (--family shadow_map): on the kit, so pcf_box's frustum,
    # bias and lookup; with pcf_box's filter and parameters, the same V and
    # the same error.
    kit = scaffold(work, exe, env, prefix, "shadow_map", KIT_NAME)
    rmse = kit.rmse
    # pcf_box has more (its filter and receiver-plane bias, at their defaults).
    ours, theirs = kit.params(KIT_NAME), kit.params("pcf_box")
    if any(theirs.get(k) != v for k, v in ours.items()):
        sys.exit(f"{KIT_NAME} and pcf_box ran with different parameters: {ours} vs {theirs}")
    if abs(rmse[KIT_NAME] - rmse["pcf_box"]) > 1e-9 or rmse[KIT_NAME] <= 0:
        sys.exit(f"{KIT_NAME}'s RMSE {rmse[KIT_NAME]} is not pcf_box's {rmse['pcf_box']}")
    v = kit.visibility(KIT_NAME)
    v_pcf = kit.visibility("pcf_box")
    worst = max(abs(v[p] - v_pcf[p]) for p in v)
    print(f"{KIT_NAME} vs pcf_box: RMSE {rmse[KIT_NAME]:.6f} vs {rmse['pcf_box']:.6f}, "
          f"largest |V difference| {worst:.2e} on {len(v)} pixels")
    if len(v) != len(v_pcf) or worst > 1e-6:
        sys.exit(f"{KIT_NAME}'s V differs from pcf_box's by up to {worst}")
    kit.check_casts_shadow(KIT_NAME)
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
