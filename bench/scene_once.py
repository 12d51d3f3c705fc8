#!/usr/bin/env python3
# What building a scene costs a run (issue 65, "each scene built once"): a
# 1,000,002-triangle glTF (a 10×10 grid of 10,000-triangle spheres, written
# by `shadowbench scene export`, not committed) through a tiny config (one
# technique unless --techniques, 160×120, 4 spp, two timed frames, no
# control), run by two builds in turn,
# alternated, each `--runs` times:
#   bench/scene_once.py --before /work/main/build/shadowbench \
#       --after build/shadowbench [--runs 3] [--isolation group] \
#       [--techniques shadow_map,pcf_box] [--work /tmp/scene_once]
# Per run it prints, in seconds from the process's start:
#   plan    the parent's plan written (config read, every scene built and
#           its jobs decided): the "plan" span of SHADOWBENCH_IO_TRACE;
#   scene   from the GL backend's line to the scene's first line: what the
#           run does to the scene before rendering (before: build it again
#           with all its data; after: derive the Run needs of the plan's);
#   total   the whole run's wall time;
#   cpu     its CPU time (user and system, of every process of the run):
#           less sensitive than wall time to a loaded machine;
#   rss     the largest resident set of the run's processes, in MB.
# and the medians per build. The machine's load is not controlled: say it.
import argparse
import json
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import time

SPEC = "sphere_grid:grid=10,slices=100,stacks=51"  # 100 × 2·100·50 + the ground's 2


def heavy_glb(work, exe):
    glb = work / "heavy.glb"
    if not glb.exists():
        subprocess.run([exe, "scene", "export", SPEC, str(glb)], check=True)
    return glb


def write_config(work, techniques):
    config = {
        "name": "scene_once",
        "scenes": [{"type": "gltf", "label": "heavy", "params": {"file": "heavy.glb"}}],
        "techniques": techniques,
        "resolutions": ["160x120"],
        "frames": {"warmup": 0, "timed": 2, "control": None},
        "reference": {"spp": 4},
    }
    path = work / "config.json"
    path.write_text(json.dumps(config, indent=2))
    return path


def one_run(exe, config, out, isolation):
    shutil.rmtree(out, ignore_errors=True)
    trace = out.with_suffix(".trace")
    trace.unlink(missing_ok=True)
    env = dict(os.environ, SHADOWBENCH_IO_TRACE=str(trace))
    start = time.monotonic_ns()
    p = subprocess.Popen([exe, "run", str(config), "--out", str(out), "--no-cache", "--no-images",
                          "--isolation", isolation], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True, env=env)
    backend = scene = None
    for line in p.stdout:
        now = time.monotonic_ns()
        if backend is None and line.startswith("backend "):
            backend = now
        elif backend is not None and scene is None and line.startswith("scene "):
            scene = now
    _, status, usage = os.wait4(p.pid, 0)
    end = time.monotonic_ns()
    if status != 0:
        sys.exit(f"{exe}: run failed ({status})")
    plan = None
    for line in trace.read_text().splitlines():
        pid, _, kind, begin, _, what = line.split(" ", 5)
        if int(pid) == p.pid and kind == "parent-io" and what == "plan":
            plan = int(begin)
    return {"plan": (plan - start) / 1e9, "scene": (scene - backend) / 1e9,
            "total": (end - start) / 1e9, "cpu": usage.ru_utime + usage.ru_stime,
            "rss": usage.ru_maxrss / 1024}


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--before", required=True)
    ap.add_argument("--after", required=True)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--isolation", default="group", choices=["none", "group", "job"])
    ap.add_argument("--techniques", default="shadow_map", help="comma-separated")
    ap.add_argument("--work", default="/tmp/scene_once")
    a = ap.parse_args()
    work = pathlib.Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    heavy_glb(work, a.after)
    config = write_config(work, a.techniques.split(","))
    results = {"before": [], "after": []}
    for i in range(a.runs):
        # Alternated, and each pair in the other order than the last.
        order = ["before", "after"] if i % 2 == 0 else ["after", "before"]
        for which in order:
            exe = a.before if which == "before" else a.after
            r = one_run(exe, config, work / f"run_{which}", a.isolation)
            results[which].append(r)
            print(f"{which:6} run {i + 1}: plan {r['plan']:6.2f} s  scene {r['scene']:6.2f} s  "
                  f"total {r['total']:6.2f} s  cpu {r['cpu']:6.2f} s  rss {r['rss']:6.0f} MB",
                  flush=True)
    for which, rs in results.items():
        med = {k: statistics.median(r[k] for r in rs) for k in rs[0]}
        print(f"{which:6} median: plan {med['plan']:6.2f} s  scene {med['scene']:6.2f} s  "
              f"total {med['total']:6.2f} s  cpu {med['cpu']:6.2f} s  rss {med['rss']:6.0f} MB")


if __name__ == "__main__":
    main()
