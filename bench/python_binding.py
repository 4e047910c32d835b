#!/usr/bin/env python3
"""The Python binding's overhead on a 1080p pair: aosuite.compare on NumPy arrays, on the PNG
files, and the `aosuite compare` command on the same files, interleaved round by round (a
noisy machine slows all three alike); prints each one's median and the ratios.

    PYTHONPATH=build/python AOSUITE_BIN=build/aosuite python3 bench/python_binding.py [ROUNDS]
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import aosuite


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 15
    rng = np.random.default_rng(5)
    y, x = np.mgrid[0:1080, 0:1920]
    expected = np.stack([(x // 8) % 256, (y // 5) % 256, (x + y) // 12 % 256], -1).astype(np.uint8)
    expected = np.clip(expected + rng.integers(-3, 4, expected.shape), 0, 255).astype(np.uint8)
    actual = expected.copy()
    actual[500:540, 900:980] //= 2  # a small change, as a regression looks
    cli = os.environ.get("AOSUITE_BIN", "aosuite")
    with tempfile.TemporaryDirectory() as tmp:
        a, e = os.path.join(tmp, "a.png"), os.path.join(tmp, "e.png")
        aosuite.write_image(a, actual)
        aosuite.write_image(e, expected)
        ways = {
            "python, arrays": lambda: aosuite.compare(actual, expected),
            "python, files": lambda: aosuite.compare(a, e),
            "aosuite compare": lambda: subprocess.run([cli, "compare", e, a],
                                                      capture_output=True, check=False),
        }
        times = {name: [] for name in ways}
        for _ in range(rounds):
            for name, run in ways.items():
                t0 = time.perf_counter()
                run()
                times[name].append(time.perf_counter() - t0)
    base = statistics.median(times["aosuite compare"])
    print(f"1920x1080 RGB pair, {rounds} interleaved rounds, median ms (ratio to the command):")
    for name, t in times.items():
        m = statistics.median(t)
        print(f"  {name:16s} {m * 1000:8.2f} ms  {m / base:5.2f}x")


if __name__ == "__main__":
    main()
