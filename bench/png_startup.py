#!/usr/bin/env python3
"""Whole-process time of `aosuite compare` on PNG pairs, two builds interleaved: what a change
to the readers costs a PNG comparison. Medians of N runs each, and their ratio.
    bench/png_startup.py BEFORE_BIN AFTER_BIN [RUNS]
"""
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
from PIL import Image


def main():
    bins = {"before": sys.argv[1], "after": sys.argv[2]}
    runs = int(sys.argv[3]) if len(sys.argv) > 3 else 40
    with tempfile.TemporaryDirectory() as tmp:
        rng = np.random.RandomState(1)
        a = (rng.rand(1080, 1920, 4) * 255).astype("uint8")
        a[:, :, 3] = 255
        b = a.copy()
        b[500:600, 500:600, 0] ^= 7
        pairs = []
        for name, (x, y) in (("64x64", (a[:64, :64], b[:64, :64])), ("1920x1080", (a, b))):
            pa, pb = pathlib.Path(tmp, name + "_a.png"), pathlib.Path(tmp, name + "_b.png")
            Image.fromarray(x).save(pa)
            Image.fromarray(y).save(pb)
            pairs.append((name, pa, pb))
        for name, pa, pb in pairs:
            times = {k: [] for k in bins}
            for _ in range(runs):
                for k, binary in bins.items():
                    start = time.perf_counter()
                    subprocess.run([binary, "compare", pa, pb], capture_output=True, check=False)
                    times[k].append(time.perf_counter() - start)
            med = {k: statistics.median(v) * 1000 for k, v in times.items()}
            print(f"{name}: before {med['before']:.2f} ms, after {med['after']:.2f} ms, "
                  f"ratio {med['after'] / med['before']:.3f}")


if __name__ == "__main__":
    main()
