#!/usr/bin/env python3
"""The share of a view's pixels in each third of its distances.

usage: distance_shares.py POSITIONS.exr EYE_X EYE_Y EYE_Z
       distance_shares.py --self-test

POSITIONS.exr is the G-buffer's positions that `run --gbuffer` writes
beside the reference's images (reference/<scene>__<WxH>/positions.exr):
RGBA world positions, w = 0 on the background. The eye is the scene
camera's (`scene info` prints it). Splits the covered pixels (w != 0) as
harness/metrics/distance_thirds.h does: the near, middle and far third of
the range of their distances from the eye (equal distance intervals; a
pixel on a boundary goes to the nearer third), and prints each third's
distance interval and its share of the covered pixels, the covered share
of the image, and the shares by decade of distance (under 10 m, 10 to
100 m, ...), which show more of a long view than its thirds do. Reads the EXR through `oiiotool --dumpdata` (nine
decimals), so needs nothing but OpenImageIO's command-line tools.
"""
import math
import re
import subprocess
import sys

PIXEL = re.compile(r"^\s*Pixel \((\d+), (\d+)\):\s+(\S+) (\S+) (\S+) (\S+)\s*$")
SIZE = re.compile(r":\s+(\d+) x\s+(\d+), 4 channel")


def fail(message):
    print(f"distance_shares: {message}", file=sys.stderr)
    sys.exit(2)


def covered_distances(dump, eye, name):
    """(pixel count, distances of the covered pixels) of `oiiotool --dumpdata` text."""
    size = SIZE.search(dump)
    if not size:
        fail(f"{name}: not an RGBA image")
    width, height = int(size.group(1)), int(size.group(2))
    distances = []
    pixels = 0
    for line in dump.splitlines():
        m = PIXEL.match(line)
        if not m:
            continue
        pixels += 1
        x, y, z, w = (float(v) for v in m.groups()[2:])
        if w != 0.0:
            distances.append(math.dist((x, y, z), eye))
    if pixels != width * height:
        fail(f"{name}: read {pixels} pixels of {width}x{height}")
    if not distances:
        fail(f"{name}: no covered pixel")
    return pixels, distances


def thirds(distances):
    """(lo, third's width, pixel count per third), as metrics/distance_thirds.cpp splits them."""
    lo, hi = min(distances), max(distances)
    third = (hi - lo) / 3.0
    counts = [0, 0, 0]
    for d in distances:
        counts[0 if d <= lo + third else 1 if d <= lo + 2.0 * third else 2] += 1
    return lo, third, counts


def decades(distances):
    """{k: pixels at distances in [10^k, 10^(k+1))}, k = 0 from 0 m."""
    counts = {}
    for d in distances:
        k = max(0, math.floor(math.log10(d))) if d > 0.0 else 0
        counts[k] = counts.get(k, 0) + 1
    return counts


def self_test():
    """The split of five covered pixels at known distances and a background one."""
    dump = """x.exr :    3 x    2, 4 channel, float openexr
    Pixel (0, 0): 1.000000000 0.000000000 0.000000000 1.000000000
    Pixel (1, 0): 0.000000000 2.000000000 0.000000000 1.000000000
    Pixel (2, 0): 0.000000000 0.000000000 -4.000000000 1.000000000
    Pixel (0, 1): 3.000000000 0.000000000 0.000000000 0.000000000
    Pixel (1, 1): 0.000000000 7.000000000 0.000000000 1.000000000
    Pixel (2, 1): 6.000000000 8.000000000 0.000000000 1.000000000
"""
    pixels, distances = covered_distances(dump, (0.0, 0.0, 0.0), "x.exr")
    assert pixels == 6 and sorted(distances) == [1.0, 2.0, 4.0, 7.0, 10.0], distances
    # Thirds of [1, 10]: [1, 4], (4, 7], (7, 10]; 4 and 7 on a boundary go nearer.
    assert thirds(distances) == (1.0, 3.0, [3, 1, 1]), thirds(distances)
    assert decades(distances) == {0: 4, 1: 1}, decades(distances)
    print("distance_shares: self-test passed")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return
    if len(sys.argv) != 5:
        fail("usage: distance_shares.py POSITIONS.exr EYE_X EYE_Y EYE_Z | --self-test")
    exr = sys.argv[1]
    eye = [float(v) for v in sys.argv[2:5]]
    r = subprocess.run(["oiiotool", "--dumpdata", exr], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"oiiotool could not read {exr}: {r.stderr.strip()}")
    pixels, distances = covered_distances(r.stdout, eye, exr)
    lo, third, counts = thirds(distances)
    n = len(distances)
    print(f"{n} covered pixels of {pixels} ({100.0 * n / pixels:.1f} % of the image)")
    for k, name in enumerate(("near", "middle", "far")):
        print(f"{name:6} {lo + k * third:9.2f} .. {lo + (k + 1) * third:9.2f} m: "
              f"{counts[k]:7} pixels, {100.0 * counts[k] / n:5.1f} % of the covered")
    by_decade = decades(distances)
    for k in sorted(by_decade):
        lower = 0 if k == 0 else 10 ** k
        print(f"{lower:>6} .. {10 ** (k + 1):>6} m: {by_decade[k]:7} pixels, "
              f"{100.0 * by_decade[k] / n:5.1f} % of the covered")


if __name__ == "__main__":
    main()
