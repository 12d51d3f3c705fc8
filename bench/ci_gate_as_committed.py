#!/usr/bin/python3
"""The CI gate exactly as committed: how often it fails unchanged code, and how
often it catches a job made 20 % or 50 % slower.

Each trial runs scripts/ci-gate.sh (configs/ci.json against the committed
baseline results/baselines/ci, with the script's own compare options) three
times: unchanged, with one gated job's frames 20 % longer, and 50 % longer
(SHADOWBENCH_INJECT_DELAY, a busy-wait at the end of each of that job's
frames: docs/ci.md, "Testing the gate"). The slowed job goes round the gated
jobs, trial by trial. A job is "flagged" when its row's time verdict is
"regression"; the slowed job is "caught" when its own row is flagged.

Unlike bench/ci_gate_trials.py, which recomputes verdicts in Python for a grid
of alphas and thresholds, this reads compare's own table: what CI would
decide, correction across jobs included. Every trial's table is kept in
OUT/trials.json. Usage:
  bench/ci_gate_as_committed.py --build build --out results/ci-gate-committed --trials 20
  bench/ci_gate_as_committed.py --out results/ci-gate-committed --summarise-only
"""
import argparse
import json
import os
import subprocess
from pathlib import Path

SLOWDOWNS = (0.0, 0.20, 0.50)


def verdicts(table):
    """{job_id: time verdict} from compare's table (columns found by the header)."""
    lines = table.splitlines()
    header = next(i for i, l in enumerate(lines) if l.startswith("job "))
    start = lines[header].index(" time ") + 1
    out = {}
    for line in lines[header + 1:]:
        if not line.strip():
            break
        out[line.split()[0]] = line[start:].split()[0].lower()  # "REGRESSION" in capitals
    return out


def gate(build, env_extra):
    env = dict(os.environ)
    env.update(env_extra)
    p = subprocess.run(["scripts/ci-gate.sh", build], env=env, capture_output=True, text=True,
                       check=False)
    if p.returncode not in (0, 4):
        raise SystemExit(f"ci-gate.sh exited {p.returncode}:\n{p.stdout}\n{p.stderr}")
    return p.returncode, p.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="results/ci-gate-committed")
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--summarise-only", action="store_true",
                    help="print the table from OUT/trials.json without running")
    args = ap.parse_args()
    os.chdir(Path(__file__).resolve().parent.parent)
    if args.summarise_only:
        trials = json.loads((Path(args.out) / "trials.json").read_text())
        for t in trials:
            t["verdicts"] = verdicts(t["table"])
        summarise(trials)
        return
    # The gated jobs, as the baseline names them: {technique variant: job id}.
    with open("results/baselines/ci/results.jsonl") as f:
        jobs = {r["technique_variant"]: r["job_id"] for r in map(json.loads, f)}
    variants = list(jobs)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    trials = []
    for t in range(args.trials):
        slowed = variants[t % len(variants)]
        for s in SLOWDOWNS:
            env = {"SHADOWBENCH_INJECT_DELAY": f"{slowed}@{round(100 * s)}%"} if s else {}
            code, table = gate(args.build, env)
            trials.append({"trial": t, "slowdown": s, "slowed": jobs[slowed] if s else None,
                           "exit": code, "verdicts": verdicts(table), "table": table})
            print(f"trial {t} slowdown {s:.0%} {slowed if s else ''}: exit {code}", flush=True)
        (out / "trials.json").write_text(json.dumps(trials, indent=1))
    summarise(trials)


def summarise(trials):
    clean = [t for t in trials if t["slowdown"] == 0]
    flagged_jobs = sum(v == "regression" for t in clean for v in t["verdicts"].values())
    jobs = sum(len(t["verdicts"]) for t in clean)
    failed = sum(t["exit"] != 0 for t in clean)
    print(f"unchanged: {failed}/{len(clean)} gate runs failed, "
          f"{flagged_jobs}/{jobs} jobs flagged")
    for s in SLOWDOWNS[1:]:
        slow = [t for t in trials if t["slowdown"] == s]
        caught = sum(t["verdicts"].get(t["slowed"]) == "regression" for t in slow)
        others = sum(v == "regression" for t in slow for j, v in t["verdicts"].items()
                     if j != t["slowed"])
        print(f"+{s:.0%}: slowed job caught in {caught}/{len(slow)}, "
              f"gate failed in {sum(t['exit'] != 0 for t in slow)}/{len(slow)}, "
              f"other jobs flagged {others}")


if __name__ == "__main__":
    main()
