#!/usr/bin/python3
"""SSIM oracle for test_metrics: scikit-image's structural_similarity with the
Wang et al. 2004 settings, on two raw float dumps written by the C++ test.

Dump format: b"SBF1", uint32 LE width, height, channels, then width*height*
channels float32 LE values (row-major, row 0 on top, interleaved channels).

Usage: ssim_oracle.py [--float32] A B [--map OUT] [--region MASK]
Prints the mean SSIM (repr). --map writes skimage's full SSIM map as a dump.
--region MASK (a one-channel dump, nonzero inside) prints the SSIM of a region
as docs/results.md defines it: every pixel of A outside the region takes B's
value, then the mean of skimage's map over the region's pixels at least 5
pixels from every border (skimage's own crop).
--float32 keeps the inputs float32 (skimage then filters in float32);
otherwise they are promoted to float64, the most exact reference.
Exit code 3 means scikit-image is missing.
"""
import struct
import sys

try:
    import numpy as np
    from skimage.metrics import structural_similarity
except ImportError as e:
    print(f"ERROR: cannot import scikit-image ({e}); install python3-skimage "
          "(apt-get install python3-skimage) for /usr/bin/python3", file=sys.stderr)
    sys.exit(3)

MAGIC = b"SBF1"


def read_dump(path):
    with open(path, "rb") as f:
        head = f.read(16)
        if len(head) != 16 or head[:4] != MAGIC:
            sys.exit(f"{path}: not an SBF1 dump")
        w, h, c = struct.unpack("<3I", head[4:])
        data = np.frombuffer(f.read(), dtype="<f4")
    if data.size != w * h * c:
        sys.exit(f"{path}: expected {w * h * c} floats, found {data.size}")
    return data.reshape(h, w, c)


def write_dump(path, img):
    h, w, c = img.shape
    with open(path, "wb") as f:
        f.write(MAGIC + struct.pack("<3I", w, h, c))
        f.write(np.ascontiguousarray(img, dtype="<f4").tobytes())


def main(argv):
    args = list(argv)
    as_f32 = "--float32" in args
    if as_f32:
        args.remove("--float32")
    map_out = None
    if "--map" in args:
        i = args.index("--map")
        map_out = args[i + 1]
        del args[i:i + 2]
    region = None
    if "--region" in args:
        i = args.index("--region")
        region = read_dump(args[i + 1])[:, :, 0] != 0
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    a, b = (read_dump(p) for p in args)
    if not as_f32:
        a, b = a.astype(np.float64), b.astype(np.float64)
    if region is not None:
        a = np.where(region[:, :, np.newaxis], a, b)
    kw = dict(gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
              data_range=1.0, full=True)
    if a.shape[2] == 1:
        mssim, smap = structural_similarity(a[:, :, 0], b[:, :, 0], **kw)
        smap = smap[:, :, np.newaxis]
    else:
        mssim, smap = structural_similarity(a, b, channel_axis=-1, **kw)
    if map_out:
        write_dump(map_out, smap)
    if region is not None:
        pad = 5  # skimage's crop: (win_size - 1) // 2 for the 11x11 window
        inside = np.zeros_like(region)
        inside[pad:-pad, pad:-pad] = region[pad:-pad, pad:-pad]
        mssim = smap[inside].mean() if inside.any() else float("nan")
    print(repr(float(mssim)))


if __name__ == "__main__":
    main(sys.argv[1:])
