#!/usr/bin/python3
"""Fixed frame counts against `frames.timed: "auto"`: what a run costs and how
stable its rankings are, on this machine as it is and beside busy loops.

For each config, each mode (the config's own frames, then "timed": "auto"
with the config's other frame settings) and each load (none, then --busy N
busy-loop processes for the whole run), runs the config --repeats times into
fresh folders (a shared reference cache, made once beforehand, so that only
the frames differ) and reports:
  run time      the median wall time of a run;
  frames        the median timed frames per job;
  noisy         the share of jobs marked noisy (timing.noise.noisy);
  rank agreement  over every pair of repeats and every (scene, resolution),
                the share of technique pairs ordered the same by their median
                frame ratio to the control (1: identical rankings; 0.5: coin
                flips); the control is left out.

Usage:
  bench/auto_frames_trials.py --binary build/shadowbench --configs configs/ci.json \\
      configs/quick.json --out results/auto-frames [--repeats 3] [--busy 2]
"""
import argparse
import itertools
import json
import multiprocessing
import statistics
import subprocess
import sys
import time
from pathlib import Path


def spin():
    while True:
        pass


def records(run_dir):
    with open(Path(run_dir) / "results.jsonl") as f:
        return [json.loads(line) for line in f if line.strip()]


def rankings(recs):
    """(scene, resolution) -> technique variants ordered by median frame ratio."""
    groups = {}
    for r in recs:
        if r.get("status") != "ok" or "control" not in r.get("timing", {}):
            continue
        if r["technique_variant"] == r["timing"]["control"]["technique"]:
            continue
        key = (r["scene_variant"], r["resolution"])
        groups.setdefault(key, []).append(
            (r["timing"]["control"]["frame_ratio"]["median"], r["technique_variant"]))
    return {k: [t for _, t in sorted(v)] for k, v in groups.items()}


def agreement(a, b):
    same = total = 0
    for key in a.keys() & b.keys():
        pos_a = {t: i for i, t in enumerate(a[key])}
        pos_b = {t: i for i, t in enumerate(b[key])}
        common = sorted(pos_a.keys() & pos_b.keys())
        for x, y in itertools.combinations(common, 2):
            total += 1
            same += (pos_a[x] < pos_a[y]) == (pos_b[x] < pos_b[y])
    return same / total if total else float("nan")


def run_once(args, config, out, cache):
    start = time.monotonic()
    subprocess.run([args.binary, "run", str(config), "--out", str(out), "--quiet", "--no-images",
                    "--cache-dir", str(cache)], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    return time.monotonic() - start


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--binary", required=True)
    p.add_argument("--configs", nargs="+", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--busy", type=int, default=2, help="busy loops in the loaded condition")
    args = p.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for config_path in args.configs:
        config = json.loads(Path(config_path).read_text())
        name = Path(config_path).stem
        auto = json.loads(json.dumps(config))
        frames = auto.setdefault("frames", {})
        frames["auto_block"] = frames.get("timed", 10)
        frames["timed"] = "auto"
        variants = {"fixed": Path(config_path).resolve(), "auto": out / f"{name}-auto.json"}
        variants["auto"].write_text(json.dumps(auto, indent=2))
        cache = out / "cache"
        run_once(args, variants["fixed"], out / f"{name}-warm", cache)  # references, once
        for load in ("none", f"{args.busy} busy loops"):
            spinners = []
            if load != "none":
                spinners = [multiprocessing.Process(target=spin, daemon=True) for _ in range(args.busy)]
                for s in spinners:
                    s.start()
            try:
                for mode, path in variants.items():
                    times, frames_per_job, noisy, ranks = [], [], [], []
                    for k in range(args.repeats):
                        folder = out / f"{name}-{mode}-{'idle' if load == 'none' else 'busy'}-{k}"
                        subprocess.run(["rm", "-rf", str(folder)], check=True)
                        times.append(run_once(args, path, folder, cache))
                        recs = [r for r in records(folder) if r.get("status") == "ok"]
                        frames_per_job += [r["timing"]["timed_frames"] for r in recs]
                        noisy += [bool(r["timing"].get("noise", {}).get("noisy")) for r in recs]
                        ranks.append(rankings(recs))
                        print(f"{name} {mode} load={load} repeat {k + 1}: {times[-1]:.1f} s",
                              file=sys.stderr)
                    pairs = [agreement(a, b) for a, b in itertools.combinations(ranks, 2)]
                    rows.append({"config": name, "mode": mode, "load": load,
                                 "run_time_s": statistics.median(times),
                                 "frames_per_job": statistics.median(frames_per_job),
                                 "noisy": sum(noisy) / len(noisy),
                                 "rank_agreement": statistics.mean(pairs)})
            finally:
                for s in spinners:
                    s.terminate()
    (out / "rows.json").write_text(json.dumps(rows, indent=2))
    lines = ["| config | frames | load | run time | timed frames per job (median) | noisy jobs | "
             "rank agreement |", "|---|---|---|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['config']} | {r['mode']} | {r['load']} | {r['run_time_s']:.1f} s | "
                     f"{r['frames_per_job']:g} | {100 * r['noisy']:.0f} % | "
                     f"{100 * r['rank_agreement']:.0f} % |")
    (out / "table.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
