#!/usr/bin/python3
"""How often does the CI gate cry wolf, and how often does it catch a wolf?

Runs unchanged code against itself N times in each of three modes, and with a
known slowdown injected into one job (SHADOWBENCH_INJECT_DELAY, a busy-wait
at the end of each of its frames for 10 % or 20 % of that frame's own time),
then reports per mode the
share of trials that flag a timing regression:

  absolute           two `run`s one after the other, absolute frame times;
  ratio              the same runs, each job's frame time over the control's
                     frame timed next to it (`compare --normalize control`);
  interleaved        `compare-builds`: both builds at once, taking turns;
  interleaved+ratio  the same runs, compared on the ratios.

Every trial's (change, p) per job is kept in trials.json, so the table can be
made for any (alpha, threshold) without running again (--analyze-only).
A last phase, --proxies, runs the config under two stand-ins for another
machine (LP_NATIVE_VECTOR_WIDTH=128: llvmpipe's 4-wide instead of 8-wide
SIMD; LP_NUM_THREADS=1: one rasteriser thread) and reports how far the
absolute times and the ratios move.

Needs python3-scipy (Debian). Takes about 40 minutes for 20 trials of
configs/ci.json on a 2-core machine. Usage:
  bench/ci_gate_trials.py --binary build/shadowbench --config configs/ci.json \
      --out results/ci-gate --trials 20 [--proxies]
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
from pathlib import Path

from scipy.stats import mannwhitneyu

SLOWDOWNS = (0.10, 0.20)
ALPHAS = (0.05, 0.02, 0.01, 0.001)
THRESHOLDS = (0.05, 0.10, 0.15, 0.20)


def records(run_dir):
    out = {}
    with open(Path(run_dir) / "results.jsonl") as f:
        for line in f:
            r = json.loads(line)
            if r["status"] == "ok":
                out[r["job_id"]] = r
    return out


def samples(record, mode):
    t = record["timing"]
    if mode == "ratio":
        return t["control"]["frame_ratio"]["samples"]
    return t["frame"]["samples_ms"]


def compare_pair(base_dir, new_dir, mode):
    """Per job: (change of the medians, two-sided Mann-Whitney p)."""
    base, new = records(base_dir), records(new_dir)
    out = {}
    for job in base:
        if job not in new:
            continue
        a, b = samples(base[job], mode), samples(new[job], mode)
        change = statistics.median(b) / statistics.median(a) - 1
        p = mannwhitneyu(a, b, alternative="two-sided").pvalue
        out[job] = {"change": change, "p": float(p)}
    return out


def run(binary, config, out_dir, cache, env_extra=None):
    env = dict(os.environ)
    env.update(env_extra or {})
    shutil.rmtree(out_dir, ignore_errors=True)
    subprocess.run([binary, "run", config, "--out", str(out_dir), "--quiet", "--no-images",
                    "--cache-dir", cache], check=True, env=env, stdout=subprocess.DEVNULL)


def compare_builds(binary, new_binary, config, out_dir, cache, turn_block):
    shutil.rmtree(out_dir, ignore_errors=True)
    # The verdict is recomputed from the records; a huge threshold keeps the
    # exit code 0 so that check=True only catches real failures.
    subprocess.run([binary, "compare-builds", "--base", binary, "--new", new_binary, config,
                    "--out", str(out_dir), "--cache-dir", cache, "--time-threshold", "100",
                    "--turn-block", str(turn_block)],
                   check=True, stdout=subprocess.DEVNULL)


def wrapper(path, binary, delay):
    path.write_text(f"#!/bin/sh\nSHADOWBENCH_INJECT_DELAY='{delay}' exec {binary} \"$@\"\n")
    path.chmod(0o755)
    return str(path)


def evaluate_trial(out, t, slowdowns):
    """One trial's (change, p) per job, per mode and slowdown, from its folders."""
    row = {"trial": t}
    seq, ab = out / "seq", out / f"ab/{t}"
    if (seq / f"base{t}").exists():
        for mode in ("absolute", "ratio"):
            # Unchanged: two consecutive runs of the same build.
            row[f"{mode}/0"] = compare_pair(seq / f"base{t - 1}", seq / f"base{t}", mode)
            for s in slowdowns:
                row[f"{mode}/{s}"] = compare_pair(seq / f"base{t}", seq / f"slow{s}_{t}", mode)
    for mode, samples_of in (("interleaved", "absolute"), ("interleaved+ratio", "ratio")):
        row[f"{mode}/0"] = compare_pair(ab / "same/base", ab / "same/new", samples_of)
        for s in slowdowns:
            row[f"{mode}/{s}"] = compare_pair(ab / f"slow{s}/base", ab / f"slow{s}/new",
                                               samples_of)
    return row


def collect(args, out):
    binary = str(Path(args.binary).resolve())
    cache = str(out / "cache")
    # A first run fills the reference cache and names the slowed job. The
    # delays are shares of each frame's own time: the slowdown stays what
    # it says however loaded the machine is.
    run(binary, args.config, out / "calibration", cache)
    cal = records(out / "calibration")
    slow_job = next(j for j, r in cal.items() if r["technique_variant"] == args.slow)
    median = cal[slow_job]["timing"]["frame"]["median_ms"]
    delays = {s: f"{args.slow}@{round(100 * s)}%" for s in SLOWDOWNS}
    meta = {"slow_job": slow_job, "slow_variant": args.slow, "calibration_median_ms": median,
            "delays": {str(s): d for s, d in delays.items()}, "trials": args.trials,
            "config": args.config, "turn_block": args.turn_block,
            "interleaved_only": args.interleaved_only}
    trials = []
    for t in range(args.trials + 1):
        if not args.interleaved_only:
            run(binary, args.config, out / f"seq/base{t}", cache)
        if t == 0:
            continue
        if not args.interleaved_only:
            for s, d in delays.items():
                run(binary, args.config, out / f"seq/slow{s}_{t}", cache,
                    {"SHADOWBENCH_INJECT_DELAY": d})
        ab = out / f"ab/{t}"
        compare_builds(binary, binary, args.config, ab / "same", cache, args.turn_block)
        for s, d in delays.items():
            new_binary = wrapper(out / f"slow{s}.sh", binary, d)
            compare_builds(binary, new_binary, args.config, ab / f"slow{s}", cache,
                           args.turn_block)
        trials.append(evaluate_trial(out, t, SLOWDOWNS))
        print(f"trial {t}/{args.trials} done", file=sys.stderr, flush=True)
        (out / "trials.json").write_text(json.dumps({"meta": meta, "trials": trials}, indent=1))
    return meta, trials


def proxies(args, out):
    """Absolute times and ratios under two stand-ins for another machine."""
    binary = str(Path(args.binary).resolve())
    cache = str(out / "cache")
    settings = {"default": {}, "LP_NATIVE_VECTOR_WIDTH=128": {"LP_NATIVE_VECTOR_WIDTH": "128"},
                "LP_NUM_THREADS=1": {"LP_NUM_THREADS": "1"}}
    medians = {}
    for name, env in settings.items():
        for k in range(args.proxy_runs):
            d = out / f"proxy/{name.replace('=', '_')}_{k}"
            run(binary, args.config, d, cache, env)
            for job, r in records(d).items():
                m = medians.setdefault(job, {}).setdefault(name, {"absolute": [], "ratio": []})
                m["absolute"].append(r["timing"]["frame"]["median_ms"])
                m["ratio"].append(r["timing"]["control"]["frame_ratio"]["median"])
    (out / "proxies.json").write_text(json.dumps(medians, indent=1))
    return medians


def flagged(c, alpha, threshold):
    return c["p"] < alpha and c["change"] > threshold


def table(meta, trials):
    modes = [m for m in ("absolute", "ratio", "interleaved", "interleaved+ratio")
             if f"{m}/0" in trials[0]]
    n = len(trials)
    lines = [f"{n} trials of {meta['config']} (turn block {meta.get('turn_block', 5)} frames)"
             f"; slowed job: `{meta['slow_variant']}` "
             f"(median frame {meta['calibration_median_ms']:.1f} ms in the first run)", "",
             "| mode | alpha | threshold | false alarms per job (unchanged) | any job flagged "
             "(unchanged) | +10 % caught | +20 % caught |", "|---|---:|---:|---:|---:|---:|---:|"]
    for mode in modes:
        for alpha in ALPHAS:
            for th in THRESHOLDS:
                per_job = [flagged(c, alpha, th) for row in trials
                           for c in row[f"{mode}/0"].values()]
                any_job = [any(flagged(c, alpha, th) for c in row[f"{mode}/0"].values())
                           for row in trials]
                caught = {s: [flagged(row[f"{mode}/{s}"][meta["slow_job"]], alpha, th)
                              for row in trials] for s in SLOWDOWNS}
                share = lambda v: f"{100 * sum(v) / max(1, len(v)):.0f} %"  # noqa: E731
                lines.append(f"| {mode} | {alpha} | {th:.2f} | {share(per_job)} "
                             f"({sum(per_job)}/{len(per_job)}) | {share(any_job)} | "
                             f"{share(caught[0.1])} | {share(caught[0.2])} |")
    # The spread of the unchanged changes: what a threshold must clear.
    lines += ["", "| mode | median abs. change (unchanged) | 95th percentile | max |",
              "|---|---:|---:|---:|"]
    for mode in modes:
        ch = sorted(abs(c["change"]) for row in trials for c in row[f"{mode}/0"].values())
        p95 = ch[min(len(ch) - 1, int(0.95 * len(ch)))]
        lines.append(f"| {mode} | {100 * statistics.median(ch):.1f} % | {100 * p95:.1f} % | "
                     f"{100 * ch[-1]:.1f} % |")
    return "\n".join(lines)


def proxy_table(medians):
    lines = ["| job | setting | median frame ms (change) | median ratio (change) |",
             "|---|---|---:|---:|"]
    for job, by in medians.items():
        base_abs = statistics.median(by["default"]["absolute"])
        base_ratio = statistics.median(by["default"]["ratio"])
        for name, m in by.items():
            a, r = statistics.median(m["absolute"]), statistics.median(m["ratio"])
            lines.append(f"| {job.split('__')[-1]} | {name} | {a:.1f} ({100 * (a / base_abs - 1):+.0f} %)"
                         f" | {r:.2f} ({100 * (r / base_ratio - 1):+.0f} %) |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", default="build/shadowbench")
    ap.add_argument("--config", default="configs/ci.json")
    ap.add_argument("--out", default="results/ci-gate")
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--slow", default="pcf_box/k=3,size=1024",
                    help="the technique variant that the injected delay slows")
    ap.add_argument("--turn-block", type=int, default=5, help="compare-builds --turn-block")
    ap.add_argument("--interleaved-only", action="store_true",
                    help="run only the compare-builds trials")
    ap.add_argument("--analyze-only", action="store_true",
                    help="recompute the table from the run folders (or trials.json)")
    ap.add_argument("--proxies", action="store_true", help="also run the machine stand-ins")
    ap.add_argument("--proxy-runs", type=int, default=3)
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.analyze_only:
        data = json.loads((out / "trials.json").read_text())
        meta, trials = data["meta"], data["trials"]
        if (out / "ab").exists():  # the folders are there: every mode, afresh
            trials = [evaluate_trial(out, row["trial"], SLOWDOWNS) for row in trials]
    else:
        meta, trials = collect(args, out)
    report = table(meta, trials)
    if args.proxies or (args.analyze_only and (out / "proxies.json").exists()):
        medians = (json.loads((out / "proxies.json").read_text()) if args.analyze_only
                   else proxies(args, out))
        report += "\n\n" + proxy_table(medians)
    (out / "table.md").write_text(report + "\n")
    print(report)


if __name__ == "__main__":
    main()
