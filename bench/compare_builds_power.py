#!/usr/bin/python3
"""How small a regression does `compare-builds` catch, and how often does it cry wolf?

Runs `shadowbench compare-builds` exactly as a pull request's CI would (its
defaults: ratios to the control, alpha 0.02 after Holm's correction across
the jobs, time threshold 0.10), with the same binary as base and new, and
the new one slowed: a wrapper script sets SHADOWBENCH_INJECT_DELAY so that
every frame of one technique variant is p % longer (a busy-wait at the
frame's end for p % of that frame's own time). Per trial, each slowdown in
--slowdowns (0 is unchanged code) is one compare-builds; the slowed variant
goes round the config's techniques from trial to trial.

Reads compare-builds' own verdicts from its table (the `time` column), so
what is counted is what a user sees:
  false alarm   unchanged code (0 %) with any job flagged (exit code 4);
  caught        the slowed job flagged as a regression;
  other flagged a job other than the slowed one flagged.

--busy N starts N busy-loop processes for the whole measurement (a loaded
CI runner); 0 leaves the machine as it is. Writes trials.json and table.md
under --out, and --analyze-only recomputes the table from trials.json.

Usage:
  bench/compare_builds_power.py --binary build/shadowbench --config configs/ci.json \
      --out results/ab-power --trials 20 [--busy 1]
"""
import argparse
import json
import multiprocessing
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

DEFAULT_SLOWDOWNS = (0.0, 0.05, 0.10, 0.20)


def spin():
    while True:
        pass


def job_variants(run_dir):
    """job_id -> technique variant, from a run folder's records (ok jobs, in order)."""
    out = {}
    with open(Path(run_dir) / "results.jsonl") as f:
        for line in f:
            r = json.loads(line)
            if r["status"] == "ok":
                out[r["job_id"]] = r["technique_variant"]
    return out


def wrapper(path, binary, delay):
    path.write_text(f"#!/bin/sh\nSHADOWBENCH_INJECT_DELAY='{delay}' exec {binary} \"$@\"\n")
    path.chmod(0o755)
    return str(path)


ROW = re.compile(r"^(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(regression|unchanged|"
                 r"improvement|not compared)\b", re.IGNORECASE)


def verdicts(text):
    """job_id -> (change in %, time verdict) from compare's table."""
    out = {}
    in_table = False
    for line in text.splitlines():
        if line.startswith("job "):
            in_table = True
            continue
        if not in_table:
            continue
        if not line.strip():
            break
        m = ROW.match(line)
        if m:
            change = m.group(4).rstrip("%")
            out[m.group(1)] = (float(change) if change != "-" else None, m.group(7).lower())
    return out


def compare_builds(binary, new_binary, config, out_dir, cache):
    start = time.monotonic()
    p = subprocess.run([binary, "compare-builds", "--base", binary, "--new", new_binary, config,
                        "--out", str(out_dir), "--cache-dir", cache],
                       capture_output=True, text=True)
    seconds = time.monotonic() - start
    if p.returncode not in (0, 4):
        sys.exit(f"compare-builds failed (exit {p.returncode}):\n{p.stdout}\n{p.stderr}")
    return p.returncode, verdicts(p.stdout), seconds


def collect(args, out):
    binary = str(Path(args.binary).resolve())
    cache = str(out / "cache")
    slowdowns = sorted(set(args.slowdowns) | {0.0})  # 0 first: it names the jobs
    busy = [multiprocessing.Process(target=spin, daemon=True) for _ in range(args.busy)]
    for b in busy:
        b.start()
    try:
        trials = []
        for t in range(1, args.trials + 1):
            row = {"trial": t, "by_slowdown": {}}
            for s in slowdowns:
                new_binary = binary if s == 0 else wrapper(
                    out / "slow.sh", binary, f"{slowed}@{round(100 * s)}%")
                code, v, seconds = compare_builds(binary, new_binary, args.config,
                                                  out / f"ab/{t}/{s}", cache)
                row["by_slowdown"][str(s)] = {"exit": code, "verdicts": v, "seconds": seconds}
                if s == 0:
                    jobs = job_variants(out / f"ab/{t}/{s}/base")
                    slowed_job = list(jobs)[(t - 1) % len(jobs)]
                    slowed = jobs[slowed_job]
                    row.update({"slowed_job": slowed_job, "slowed_variant": slowed})
            trials.append(row)
            print(f"trial {t}/{args.trials} done", file=sys.stderr, flush=True)
            meta = {"config": args.config, "busy": args.busy, "slowdowns": slowdowns,
                    "cpu": os.cpu_count(), "load_average_end": os.getloadavg()}
            (out / "trials.json").write_text(json.dumps({"meta": meta, "trials": trials},
                                                        indent=1))
    finally:
        for b in busy:
            b.terminate()
    return json.loads((out / "trials.json").read_text())


def table(data):
    meta, trials = data["meta"], data["trials"]
    n = len(trials)
    lines = [f"{n} trials of {meta['config']}, busy loops: {meta['busy']}", "",
             "| injected slowdown | trials failing (exit 4) | slowed job caught | other jobs "
             "flagged | its change: median (min to max) | seconds per compare-builds |",
             "|---:|---:|---:|---:|---:|---:|"]
    for s in meta["slowdowns"]:
        key = str(s)
        failing = caught = others = 0
        changes, seconds = [], []
        for row in trials:
            r = row["by_slowdown"][key]
            failing += r["exit"] == 4
            seconds.append(r["seconds"])
            for job, (change, verdict) in r["verdicts"].items():
                if s > 0 and job == row["slowed_job"]:
                    caught += verdict == "regression"
                    if change is not None:
                        changes.append(change)
                else:
                    others += verdict == "regression"
        change_text = (f"{statistics.median(changes):+.1f} % ({min(changes):+.1f} to "
                       f"{max(changes):+.1f} %)" if changes else "")
        lines.append(f"| {100 * s:.0f} % | {failing}/{n} | {caught if s > 0 else ''}"
                     f"{'/' + str(n) if s > 0 else ''} | {others} | {change_text} | "
                     f"{statistics.median(seconds):.1f} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", default="build/shadowbench")
    ap.add_argument("--config", default="configs/ci.json")
    ap.add_argument("--out", default="results/ab-power")
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--slowdowns", type=lambda s: [float(x) for x in s.split(",")],
                    default=list(DEFAULT_SLOWDOWNS), help="e.g. 0,0.05,0.1,0.2")
    ap.add_argument("--busy", type=int, default=0, help="busy-loop processes beside the trials")
    ap.add_argument("--analyze-only", action="store_true")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    data = (json.loads((out / "trials.json").read_text()) if args.analyze_only
            else collect(args, out))
    report = table(data)
    (out / "table.md").write_text(report + "\n")
    print(report)


if __name__ == "__main__":
    main()
