#!/usr/bin/python3
"""Signed error of penumbra_wedges and penumbra_wedges_blend where silhouettes
overlap, from a shadowbench run folder (docs/penumbra_wedges.md).

The overlap region of a scene is the ground's pixels (the sphere grid's
plane y = 0, from the G-buffer positions) where the two techniques differ by
more than 1e-3: on the ground, blending
changes a pixel only where two or more silhouettes hide part of the light,
and plain wedges there add their occlusion. On the spheres themselves the
two also differ where one silhouette's terms leave a quadrant's range (near
a caster's own terminator), which blending clamps per quadrant; those pixels
are counted apart. Per scene, the script prints each technique's mean signed
and mean absolute error against the run's reference there (V − V_ref;
negative = too dark).

Usage: tools/wedge_overlap.py RUN_DIR   (a run made with --gbuffer; needs
oiiotool, numpy and PIL)
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image


def read_exr(path, channel=0):
    with tempfile.TemporaryDirectory() as tmp:
        tif = os.path.join(tmp, "v.tif")
        subprocess.run(["oiiotool", path, "-ch", str(channel), "-d", "float", "-o", tif],
                       check=True)
        return np.array(Image.open(tif), dtype=np.float64)


def main(run):
    jobs = os.path.join(run, "jobs")
    scenes = sorted({d.split("__")[0] + "__" + d.split("__")[1] for d in os.listdir(jobs)
                     if d.endswith("__penumbra_wedges")})
    print("| scene | overlap px | wedges signed | wedges abs | blend signed | blend abs "
          "| other px differing |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for scene in scenes:
        wedges = os.path.join(jobs, scene + "__penumbra_wedges", "visibility.exr")
        blend = os.path.join(jobs, scene + "__penumbra_wedges_blend", "visibility.exr")
        ref = os.path.join(run, "reference", scene, "visibility.exr")
        positions = os.path.join(run, "reference", scene, "positions.exr")
        if not os.path.exists(positions):
            sys.exit(f"{positions}: missing; run shadowbench with --gbuffer")
        if not all(os.path.exists(p) for p in (wedges, blend, ref)):
            continue
        w, b, r = read_exr(wedges), read_exr(blend), read_exr(ref)
        caster = np.abs(read_exr(positions, 1)) > 1e-4  # off the ground y = 0
        differ = np.abs(w - b) > 1e-3
        overlap = differ & ~caster
        n = int(overlap.sum())
        on_casters = int((differ & caster).sum())
        if n == 0:
            print(f"| {scene} | 0 | | | | | {on_casters} |")
            continue
        ew, eb = (w - r)[overlap], (b - r)[overlap]
        print(f"| {scene} | {n} | {ew.mean():.4f} | {np.abs(ew).mean():.4f} | "
              f"{eb.mean():.4f} | {np.abs(eb).mean():.4f} | {on_casters} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
