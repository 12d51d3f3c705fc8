#!/usr/bin/env python3
"""The Slurm workflow of docs/scale_out.md on a single-node Slurm started
here (scripts/slurm/start-local-slurm.sh): scripts/slurm/submit.sh submits a
three-shard job array and its merge job; the merged folder must hold every
job once, ok, each from its shard, in plan order, with the report written.

Skipped (exit 77, which ctest reports as skipped, with the reason) where
Slurm cannot start: not root, or slurm-wlm and munge not installed. CI
installs them (scripts/install-deps.sh --test)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

SKIP = 77


def skip(why):
    print(f"SKIPPED: {why}")
    sys.exit(SKIP)


def main(build, source):
    shadowbench = os.path.join(build, "shadowbench")
    slurm = os.path.join(source, "scripts", "slurm")
    if os.geteuid() != 0:
        skip("starting slurmctld and slurmd needs root")
    for tool in ("slurmctld", "slurmd", "sbatch", "munged"):
        if shutil.which(tool) is None and not os.path.exists(f"/usr/sbin/{tool}"):
            skip(f"{tool} is not installed (Debian: slurm-wlm, munge)")
    work = tempfile.mkdtemp(prefix="sb_slurm_")
    state = os.path.join(work, "slurm")
    started = subprocess.run([os.path.join(slurm, "start-local-slurm.sh"), state],
                             capture_output=True, text=True)
    if started.returncode != 0:
        skip("Slurm did not start here: " + started.stderr.strip()[-500:])
    env = dict(os.environ, SLURM_CONF=os.path.join(state, "slurm.conf"), SHADOWBENCH=shadowbench)
    try:
        config = os.path.join(work, "tiny.json")
        with open(config, "w") as f:
            json.dump({"name": "tiny",
                       "scenes": [{"type": "sphere_grid", "params": {"grid": 2}}],
                       "techniques": ["none", "shadow_map", "pcf_box", "pcss", "vsm"],
                       "resolutions": ["64x48"],
                       "frames": {"warmup": 0, "timed": 2, "control": None},
                       "reference": {"spp": 4}}, f)
        out = os.path.join(work, "tiny")
        submitted = subprocess.run(
            [os.path.join(slurm, "submit.sh"), config, out, "3", "--cache-dir",
             os.path.join(work, "cache")],
            capture_output=True, text=True, env=env, cwd=work)
        print(submitted.stdout, submitted.stderr)
        assert submitted.returncode == 0, "submit.sh failed"
        merge_job = submitted.stdout.split("merge: job ")[1].split()[0]
        deadline = time.time() + 300
        while time.time() < deadline:
            q = subprocess.run(["squeue", "-h", "-o", "%i %T"], capture_output=True, text=True,
                               env=env)
            if q.stdout.strip() == "":
                break
            time.sleep(1)
        else:
            raise AssertionError("jobs still queued after 300 s:\n" + q.stdout)
        log = os.path.join(out + "-merge.out")
        print(open(log).read() if os.path.exists(log) else "(no merge log)")
        for k in (1, 2, 3):
            shard_log = [p for p in os.listdir(work) if p.endswith(f"_{k}.out")]
            assert shard_log, f"no log of shard {k} in {work}: {os.listdir(work)}"
        with open(os.path.join(out, "results.jsonl")) as f:
            records = [json.loads(line) for line in f if line.strip()]
        assert len(records) == 5, f"{len(records)} records, expected 5"
        assert len({r["job_id"] for r in records}) == 5, "a job twice"
        assert all(r["status"] == "ok" for r in records), [r.get("reason") for r in records]
        assert sorted(r["shard"] for r in records)[0] == "1/3"
        assert {r["shard"] for r in records} == {"1/3", "2/3", "3/3"}
        assert [r["job_index"] for r in records] == list(range(5)), "not in plan order"
        assert os.path.exists(os.path.join(out, "report", "index.html")), "no report"
        print(f"ok: 3 shards and the merge job {merge_job} on a local Slurm, 5 records merged")
    finally:
        subprocess.run([os.path.join(slurm, "stop-local-slurm.sh"), state])
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main(os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]))
