#!/usr/bin/python3
"""How often does `shadowbench history report` flag a step that is not there,
and how often does it find the one that is?

Real runs, not synthetic series: N runs of a config as it is ("plain") and N
with one technique variant slowed by SHADOWBENCH_INJECT_DELAY ("slow", by
default pcss/size=1024 at 30 % of each of its frames), taken in turns so that
both see the same machine. Each trial then builds a history of K plain runs
followed by K slow runs (drawn at random, each side kept in the order it
ran), writes its report and reads steps.json:

  found   the slowed series' time has a step at run K + 1 (the first slow
          run), the commit the delay came in with;
  false   any other step: in another series, in an error, or in the slowed
          series at another run.

Usage (the driver must be able to find its plugins and plot_charts.py, as an
installed or a build tree's driver can):
  bench/history_step_trials.py --binary build/shadowbench --config configs/ci.json \\
      --runs results/history-trials --generate 30 --trials 60
--generate N makes the runs (about 10 s per pair for configs/ci.json on a
2-core machine); without it, the runs already in --runs/plain and
--runs/slow are used.
"""
import argparse
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path


def run(binary, config, out, cache, env=None):
    subprocess.run([binary, "run", config, "--out", str(out), "--quiet", "--no-images",
                    "--cache-dir", str(cache)], check=True, env=env, stdout=subprocess.DEVNULL)


def generate(args, runs):
    env = dict(os.environ, SHADOWBENCH_INJECT_DELAY=f"{args.slowed}@{args.delay}%")
    for i in range(1, args.generate + 1):
        name = f"r{i:03d}"
        run(args.binary, args.config, runs / "plain" / name, runs / "cache")
        run(args.binary, args.config, runs / "slow" / name, runs / "cache", env)
        print(f"generated pair {i} of {args.generate}", file=sys.stderr)


def trial(args, plain, slow, rng, work):
    chosen = sorted(rng.sample(plain, args.per_side)) + sorted(rng.sample(slow, args.per_side))
    db = work / "h.sqlite"
    if db.exists():
        db.unlink()
    for i, folder in enumerate(chosen, start=1):
        subprocess.run([args.binary, "history", "add", str(folder), "--db", str(db),
                        "--commit", f"{i:040x}"], check=True, stdout=subprocess.DEVNULL)
    site = work / "site"
    shutil.rmtree(site, ignore_errors=True)
    subprocess.run([args.binary, "history", "report", "--db", str(db), "--out", str(site)],
                   check=True, stdout=subprocess.DEVNULL)
    steps = json.loads((site / "steps.json").read_text())
    found, false = False, []
    for s in steps["steps"]:
        at_delay = s["run_order"] == args.per_side + 1 and s["quantity"] == steps["time_quantity"]
        if at_delay and s["series"].endswith("/ " + args.slowed):
            found = True
        else:
            false.append(s)
    return found, false, steps["series"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--binary", required=True)
    p.add_argument("--config", default="configs/ci.json")
    p.add_argument("--runs", required=True, type=Path)
    p.add_argument("--generate", type=int, default=0)
    p.add_argument("--slowed", default="pcss/size=1024")
    p.add_argument("--delay", type=float, default=30)
    p.add_argument("--trials", type=int, default=60)
    p.add_argument("--per-side", type=int, default=5)
    p.add_argument("--seed", type=int, default=44)
    args = p.parse_args()
    if args.generate:
        generate(args, args.runs)
    plain = sorted((args.runs / "plain").iterdir())
    slow = sorted((args.runs / "slow").iterdir())
    if len(plain) < args.per_side or len(slow) < args.per_side:
        sys.exit(f"need at least {args.per_side} runs in {args.runs}/plain and /slow")
    rng = random.Random(args.seed)
    found = 0
    with_false = 0
    false_steps = 0
    series = 0
    examples = []
    with tempfile.TemporaryDirectory(prefix="history_trials_") as tmp:
        for t in range(args.trials):
            f, false, n = trial(args, plain, slow, rng, Path(tmp))
            found += f
            with_false += bool(false)
            false_steps += len(false)
            series = n
            examples += [(t, s["series"], s["quantity"], s["run_order"], s["relative_change"]) for s in false]
    checked = args.trials * series * 2 - found  # series x (time, error), the found step aside
    print(f"{len(plain)} plain and {len(slow)} slow runs; {args.trials} histories of "
          f"{args.per_side} + {args.per_side} runs, {series} series each, time and error")
    print(f"  step found at the right run: {found} of {args.trials} ({100.0 * found / args.trials:.1f} %)")
    print(f"  histories with a false step: {with_false} of {args.trials} "
          f"({100.0 * with_false / args.trials:.1f} %)")
    print(f"  false steps per series and quantity: {false_steps} of {checked} "
          f"({100.0 * false_steps / max(checked, 1):.2f} %)")
    for e in examples[:20]:
        print(f"    trial {e[0]}: {e[1]} {e[2]} at run {e[3]} ({e[4]})")


if __name__ == "__main__":
    main()
