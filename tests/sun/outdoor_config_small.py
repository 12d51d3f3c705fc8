#!/usr/bin/env python3
"""configs/outdoor.json end to end at a small size.

The config's scenes, techniques, reference method and metrics as they are;
only the resolutions, the frames, the Monte Carlo fallback's samples and the
flicker frames shrink. Checks what the config promises: every technique runs
under the sun on both streets (none skipped, none failed); the leafless
street gets the exact reference and the leafy one the Monte Carlo fallback
with its reason; every record has the log-distance thirds and the flicker
under the turning sun; each technique's GPU memory is recorded.

    outdoor_config_small.py SHADOWBENCH CONFIG K/N

K/N: run shard K of N (`run --shard`), so that each ctest entry stays
well under the 30 s a CI entry may take; together the shards run every job.
"""
import json
import math
import os
import subprocess
import sys
import tempfile


def main():
    exe, config_path, shard = sys.argv[1], sys.argv[2], sys.argv[3]
    with open(config_path, encoding="utf-8") as f:
        config = json.load(f)
    config["resolutions"] = [[96, 54]]
    config["frames"] = {"warmup": 0, "timed": 1, "control": None}
    config["reference"]["spp"] = 16
    config["stability"]["flicker_frames"] = 2
    failures = []
    with tempfile.TemporaryDirectory(prefix="sb_outdoor_small_") as tmp:
        small = os.path.join(tmp, "outdoor_small.json")
        with open(small, "w", encoding="utf-8") as f:
            json.dump(config, f)
        out = os.path.join(tmp, "run")
        run = subprocess.run([exe, "run", small, "--out", out, "--quiet", "--no-images",
                              "--shard", shard, "--cache-dir", os.path.join(tmp, "cache")],
                             capture_output=True, text=True, check=False)
        if run.returncode != 0:
            print(run.stdout, run.stderr)
            failures.append(f"run exited {run.returncode}")
        with open(os.path.join(out, "results.jsonl"), encoding="utf-8") as f:
            records = [json.loads(line) for line in f if line.strip()]
        with open(os.path.join(out, "plan.json"), encoding="utf-8") as f:
            plan = json.load(f)
    # Every job of the plan runs (none skipped under the sun); this shard's
    # have records.
    if plan["counts"] != {"fail": 0, "run": len(plan["jobs"]), "skip": 0}:
        failures.append(f"plan counts {plan['counts']}: every job should run")
    mine = {j["id"] for j in plan["jobs"] if str(j["shard"]) == shard.split("/")[0]}
    got = {r["job_id"] for r in records}
    if not mine or got != mine:
        failures.append(f"records for {sorted(got ^ mine)[:5]}: expected exactly this shard's jobs")
    for r in records:
        name = f"{r['scene_variant']} {r['technique_variant']}"
        if r["status"] != "ok":
            failures.append(f"{name}: {r['status']}: {r.get('reason', '')}")
            continue
        if not r["scene"]["light"].get("angular_diameter"):
            failures.append(f"{name}: the light is not the sun")
        method = r["reference"]["method"]
        if r["scene_variant"] == "street_bare" and method != "exact_clipper":
            failures.append(f"{name}: reference {method}, expected the exact one")
        if r["scene_variant"] == "street":
            if method == "exact_clipper" or "alpha-masked" not in r["reference"].get(
                    "exact_fallback", ""):
                failures.append(f"{name}: expected the Monte Carlo fallback for the leaves' masks")
        vis = r["metrics"]["visibility"]
        for third in ("near_third", "middle_third", "far_third"):
            if third not in vis:
                failures.append(f"{name}: no {third}")
        if not math.isfinite(vis["all"]["rmse"]):
            failures.append(f"{name}: RMSE {vis['all']['rmse']}")
        if "flicker" not in r.get("stability", {}):
            failures.append(f"{name}: no flicker figures")
        if not r["technique"].get("gpu_bytes", 0) > 0:
            failures.append(f"{name}: no GPU memory recorded")
    # The log thirds split a street seen from eye height: each holds pixels
    # (the linear thirds leave the middle and far ones nearly empty).
    for r in records:
        if r["status"] == "ok":
            counts = [r["metrics"]["visibility"][t]["pixel_count"]
                      for t in ("near_third", "middle_third", "far_third")]
            if min(counts) < 0.01 * sum(counts):
                failures.append(f"{r['scene_variant']}: log thirds hold {counts} pixels")
            break
    for f in failures:
        print("FAIL:", f)
    print(f"{len(records)} records checked")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
