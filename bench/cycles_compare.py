#!/usr/bin/python3
"""Blender Cycles against the Monte Carlo reference on the sphere grid, back to back.

The comparison of docs/performance.md ("The adaptive Monte Carlo reference",
Against Blender Cycles), rerunnable: per round, bench_reference's uniform
64-spp reference (BM_Reference/spp:64) and its adaptive reference at the
uniform 1024-spp reference's noise (BM_AdaptiveAtUniformNoise/pilot:4),
then Cycles (bench/cycles_sphere_grid.py) at each of --samples, all on the
same 800x600 sphere grid, the order kept within a round so that a slower
stretch of a shared machine meets both. Prints each round and the medians.

  equal samples   Cycles at 64 samples over the uniform 64-spp reference.
  equal noise     Cycles' time at the samples that bring its penumbra noise
                  to the adaptive reference's, over the adaptive reference.
                  Cycles' noise falls as 0.0342 * (64 / N)^0.54 (measured
                  from two seeds at 64 and 256 samples, docs/performance.md;
                  noise does not depend on the machine), its time as the
                  line through the medians at the smallest and largest
                  --samples (with one count, in proportion to the samples,
                  which also scales its fixed scene sync: an overstatement). The
                  adaptive reference's noise is its penumbra RMS standard
                  error (the bench's penumbra_rms_std_error), which
                  overstates its true error (docs/results.md: 0.66-0.70 of
                  it), so Cycles is asked for less than equal noise.

Needs blender on PATH (Debian 12: `apt-get install blender`, 3.4.1) and a
build with bench_reference. Run it as below, with the system Python of its
first line: started from a pyenv Python, Blender's own Python found no
numpy. Usage:
  bench/cycles_compare.py [--build build] [--rounds 3] [--samples 64 256]
(with 64 among the samples for the equal-samples ratio).
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

CYCLES_NOISE_64 = 0.0342  # docs/performance.md, two seeds at 64 samples
CYCLES_NOISE_EXPONENT = 0.54  # its fall between 64 and 256 samples


def bench_reference(build):
    out = subprocess.run(
        [os.path.join(build, "bench", "bench_reference"),
         "--benchmark_filter=BM_Reference/spp:64/|BM_AdaptiveAtUniformNoise/pilot:4/",
         "--benchmark_format=json"],
        check=True, capture_output=True, text=True).stdout
    rows = {b["name"].split("/")[0]: b for b in json.loads(out)["benchmarks"]}
    return rows["BM_Reference"], rows["BM_AdaptiveAtUniformNoise"]


def cycles(glb, samples, seed, folder):
    here = os.path.dirname(os.path.abspath(__file__))
    out = subprocess.run(
        ["blender", "-b", "-noaudio", "--python", os.path.join(here, "cycles_sphere_grid.py"),
         "--", glb, str(samples), os.path.join(folder, "cycles.png"), str(seed)],
        check=True, capture_output=True, text=True).stdout
    m = re.search(r"SHADOWBENCH_CYCLES samples=(\d+) wall_s=([0-9.]+) threads=\d+ cpu_s=([0-9.]+)",
                  out)
    if not m:
        sys.exit("no SHADOWBENCH_CYCLES line in Blender's output:\n" + out[-2000:])
    return float(m.group(2)), float(m.group(3))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--samples", type=int, nargs="+", default=[64, 256])
    args = ap.parse_args()
    folder = tempfile.mkdtemp(prefix="cycles_compare_")
    glb = os.path.join(folder, "grid.glb")
    subprocess.run([os.path.join(args.build, "shadowbench"), "scene", "export", "sphere_grid", glb],
                   check=True, capture_output=True)
    uniform, adaptive, adaptive_noise = [], [], []
    uniform_cpu, adaptive_cpu = [], []
    times = {n: [] for n in args.samples}
    cpus = {n: [] for n in args.samples}
    for r in range(args.rounds):
        u, a = bench_reference(args.build)
        uniform.append(u["trace_s"])
        uniform_cpu.append(u.get("cpu_s", float("nan")))
        adaptive.append(a["trace_s"])
        adaptive_cpu.append(a.get("cpu_s", float("nan")))
        adaptive_noise.append(a["penumbra_rms_std_error"])
        line = "round %d: uniform 64 spp %.3f s (cpu %.3f), adaptive %.3f s (cpu %.3f, noise %.5f)" % (
            r + 1, uniform[-1], uniform_cpu[-1], adaptive[-1], adaptive_cpu[-1], adaptive_noise[-1])
        for n in args.samples:
            wall, cpu = cycles(glb, n, r, folder)
            times[n].append(wall)
            cpus[n].append(cpu)
            line += ", Cycles %d: %.2f s (cpu %.2f)" % (n, wall, cpu)
        print(line, flush=True)

    med = statistics.median
    print("\nmedians of %d rounds:" % args.rounds)
    print("  uniform 64 spp   %.3f s wall, %.3f s cpu" % (med(uniform), med(uniform_cpu)))
    print("  adaptive         %.3f s wall, %.3f s cpu, penumbra noise %.5f" % (
        med(adaptive), med(adaptive_cpu), med(adaptive_noise)))
    for n in args.samples:
        print("  Cycles %4d      %.2f s wall, %.2f s cpu" % (n, med(times[n]), med(cpus[n])))
    if 64 in times:
        print("equal samples (64): Cycles %.1fx the uniform reference's time (%.1fx its cpu)" % (
            med(times[64]) / med(uniform), med(cpus[64]) / med(uniform_cpu)))
    noise = med(adaptive_noise)
    n_eq = 64.0 * (CYCLES_NOISE_64 / noise) ** (1.0 / CYCLES_NOISE_EXPONENT)
    counts = sorted(args.samples)

    def at_equal_noise(t):
        if len(counts) >= 2:
            lo, hi = counts[0], counts[-1]
            return med(t[lo]) + (med(t[hi]) - med(t[lo])) / (hi - lo) * (n_eq - lo)
        return med(t[counts[0]]) * n_eq / counts[0]

    t_eq, c_eq = at_equal_noise(times), at_equal_noise(cpus)
    print("equal noise (%.5f): Cycles needs about %.0f samples, about %.0f s: %.0fx the adaptive "
          "reference's time (%.0f cpu s: %.0fx its cpu)" % (
              noise, n_eq, t_eq, t_eq / med(adaptive), c_eq, c_eq / med(adaptive_cpu)))


if __name__ == "__main__":
    main()
