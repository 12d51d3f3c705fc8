#!/usr/bin/env python3
"""Recomputes every job's visibility errors from the files its run wrote.

usage: recompute_metrics.py RUN_DIR [--rtol R]

For each record of RUN_DIR/results.jsonl that has metrics and images, reads
the job's visibility.exr, the reference's visibility.exr and the region
masks the record names under images.masks (8-bit PNGs, 255 = measured),
recomputes metrics.visibility.<region> for every region, each figure as
docs/results.md ("Recomputing the errors") defines it, and compares it with
the record: each figure to R relative (1e-6), mean_signed relative to mae
(a mean of signed values can cancel to ~0), counts and max_pixel exactly.
Prints every mismatch. Exit status 0 when all match, 1 when any figure
differs, 2 when a file is missing or OpenImageIO cannot be imported.
Only OpenImageIO's Python bindings (python3-openimageio) and numpy.
"""
import argparse
import json
import math
import os
import sys

import numpy as np



def fail(message):
    print(f"recompute_metrics: {message}", file=sys.stderr)
    sys.exit(2)


try:
    import OpenImageIO as oiio
except ImportError as e:
    fail(f"cannot import OpenImageIO ({e}): apt-get install python3-openimageio")

SSIM_RADIUS, SSIM_SIGMA, SSIM_K1, SSIM_K2 = 5, 1.5, 0.01, 0.03
THRESHOLDS = {"frac_over_0.01": 0.01, "frac_over_0.05": 0.05, "frac_over_0.1": 0.1}


def read(path):
    """An image as float32 (height, width, channels): 8-bit values as v/255."""
    buf = oiio.ImageBuf(path)
    pixels = buf.get_pixels(oiio.FLOAT)
    if buf.has_error or pixels is None:
        fail(f"cannot read {path}: {buf.geterror()}")
    return np.asarray(pixels, dtype=np.float32).reshape(buf.spec().height, buf.spec().width, -1)


def read_mask(path):
    return read(path)[:, :, 0] > 0.5


def gaussian_filter(img):
    """scipy.ndimage.gaussian_filter(sigma 1.5, truncate 3.5, mode 'reflect'), per channel."""
    x = np.arange(-SSIM_RADIUS, SSIM_RADIUS + 1, dtype=np.float64)
    w = np.exp(-0.5 * x * x / (SSIM_SIGMA * SSIM_SIGMA))
    w /= w.sum()
    r = SSIM_RADIUS
    p = np.pad(img, ((r, r), (r, r), (0, 0)), mode="symmetric")  # scipy's 'reflect'
    h, wd = img.shape[:2]
    rows = sum(w[k] * p[k:k + h, :, :] for k in range(2 * r + 1))
    return sum(w[k] * rows[:, k:k + wd, :] for k in range(2 * r + 1))


def ssim_map(a, b):
    """Wang et al. 2004 as scikit-image (gaussian_weights, population covariance, range 1)."""
    a, b = a.astype(np.float64), b.astype(np.float64)
    ua, ub = gaussian_filter(a), gaussian_filter(b)
    vaa = gaussian_filter(a * a) - ua * ua
    vbb = gaussian_filter(b * b) - ub * ub
    vab = gaussian_filter(a * b) - ua * ub
    c1, c2 = SSIM_K1 ** 2, SSIM_K2 ** 2
    return ((2 * ua * ub + c1) * (2 * vab + c2)) / ((ua * ua + ub * ub + c1) * (vaa + vbb + c2))


def mean_ssim(test, ref, region, outside_from_ref):
    """The map of test (ref's values outside `outside_from_ref`) against ref,
    averaged over the region's pixels at least 5 from every border."""
    h, w = region.shape
    if h < 2 * SSIM_RADIUS + 1 or w < 2 * SSIM_RADIUS + 1:
        return math.nan
    t = np.where(outside_from_ref[:, :, None], test, ref)
    s = ssim_map(t, ref)
    r = SSIM_RADIUS
    inner = np.zeros_like(region)
    inner[r:h - r, r:w - r] = True
    picked = s[region & inner]
    return float(picked.mean()) if picked.size else math.nan


def errors(test, ref, region):
    """The record's figures but SSIM over one region (finite values, as ok jobs have)."""
    d = np.abs(test - ref).astype(np.float64)  # subtracted in float32, as OIIO's compare
    values = d[region]                          # (pixels, channels)
    n = values.size
    out = {"pixel_count": int(region.sum()), "nonfinite_count": 0}
    if n == 0:
        return out
    out["rmse"] = math.sqrt(float((values ** 2).sum()) / n)
    out["mae"] = float(values.sum()) / n
    out["mean_signed"] = float((test.astype(np.float64) - ref.astype(np.float64))[region].sum()) / n
    out["psnr"] = math.inf if out["rmse"] == 0 else 20 * math.log10(1 / out["rmse"])
    per_pixel = values.max(axis=1)
    for key, threshold in THRESHOLDS.items():
        out[key] = float((per_pixel > threshold).sum()) / region.sum()
    most = float(values.max())
    out["max_error"] = most
    if most > 0:  # the first pixel in row-major order with the largest error
        y, x = np.argwhere(region & (d.max(axis=2) == most))[0]
        out["max_pixel"] = [int(x), int(y)]
    else:
        out["max_pixel"] = [-1, -1]
    return out


def as_number(v):
    return {"nan": math.nan, "inf": math.inf, "-inf": -math.inf}.get(v, v) if isinstance(v, str) else v


def agrees(key, got, want, figures, rtol):
    if isinstance(want, list) or key.endswith("_count"):
        return got == want
    got, want = float(got), float(as_number(want))
    if math.isnan(got) or math.isnan(want):
        return math.isnan(got) and math.isnan(want)
    if math.isinf(got) or math.isinf(want):
        return got == want
    scale = max(abs(got), abs(want))
    if key == "mean_signed":
        scale = max(scale, float(as_number(figures.get("mae", 0.0))))
    return abs(got - want) <= rtol * scale + 1e-15


def check_record(run_dir, record, rtol):
    images = record.get("images", {})
    metrics = record.get("metrics", {}).get("visibility")
    if not metrics or "visibility" not in images:
        return 0, []
    path = lambda rel: os.path.join(run_dir, rel)
    test = read(path(images["visibility"]))
    ref = read(path(images["reference_visibility"]))
    masks = {region: read_mask(path(rel)) for region, rel in images.get("masks", {}).items()}
    problems, checked = [], 0
    for region, figures in metrics.items():
        if region not in masks:
            problems.append(f"{record['job_id']}: no mask for region {region} in images.masks")
            continue
        got = errors(test, ref, masks[region])
        # geometry's and terminator's SSIM windows see the reference's values
        # outside them, every other region's outside the measured pixels
        # (docs/results.md "Regions").
        outside = masks[region] if region in ("geometry", "terminator") else masks["all"]
        got["ssim"] = mean_ssim(test, ref, masks[region], outside)
        for key, want in figures.items():
            if key not in got:
                continue
            checked += 1
            if not agrees(key, got[key], want, figures, rtol):
                problems.append(f"{record['job_id']}: visibility.{region}.{key}: "
                                f"record {want}, files {got[key]}")
    return checked, problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir")
    parser.add_argument("--rtol", type=float, default=1e-6)
    args = parser.parse_args()
    jsonl = os.path.join(args.run_dir, "results.jsonl")
    if not os.path.exists(jsonl):
        fail(f"no {jsonl}")
    records = [json.loads(line) for line in open(jsonl, encoding="utf-8") if line.strip()]
    jobs = figures = 0
    problems = []
    for record in records:
        checked, found = check_record(args.run_dir, record, args.rtol)
        jobs += checked > 0 or bool(found)
        figures += checked
        problems += found
    for p in problems:
        print(p)
    print(f"{jobs} jobs, {figures} figures recomputed, {len(problems)} mismatches")
    return 1 if problems or jobs == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
