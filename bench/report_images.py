#!/usr/bin/env python3
"""What a CI artifact weighs: one folder-mode check of N passing image pairs (half byte-identical,
half one channel level apart) under --report-images all and failures, the report's size each.

  python3 bench/report_images.py [--pairs 200] [--size 512]   # needs build/aosuite, numpy, Pillow
"""
import argparse
import os
import subprocess
import tempfile

import numpy as np
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))


def folder_bytes(path):
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(path) for f in files)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", type=int, default=200)
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--aosuite", default=os.path.join(HERE, "..", "build", "aosuite"))
    a = ap.parse_args()
    rng = np.random.default_rng(1)
    with tempfile.TemporaryDirectory() as tmp:
        for side in ("actual", "expected"):
            os.makedirs(os.path.join(tmp, side))
        for i in range(a.pairs):
            # Noise: a PNG that does not compress, as a rendered frame barely does.
            im = rng.integers(0, 256, (a.size, a.size, 4), dtype=np.uint8)
            im[..., 3] = 255
            Image.fromarray(im).save(os.path.join(tmp, "expected", f"img{i:03}.png"))
            if i % 2:
                im[0, 0, 0] ^= 1  # one level: passes, but not byte-identical
            Image.fromarray(im).save(os.path.join(tmp, "actual", f"img{i:03}.png"))
        print(f"{a.pairs} passing pairs of {a.size}x{a.size} PNGs, "
              f"{folder_bytes(os.path.join(tmp, 'actual')) / 1e6:.1f} MB per side")
        for mode in ("all", "failures"):
            report = os.path.join(tmp, "report-" + mode)
            subprocess.run([a.aosuite, "check", "--actual", "actual", "--expected", "expected",
                            "--report", report, "--report-images", mode],
                           cwd=tmp, check=True, stdout=subprocess.DEVNULL)
            print(f"--report-images {mode:8}: {folder_bytes(report) / 1e6:8.1f} MB")


if __name__ == "__main__":
    main()
