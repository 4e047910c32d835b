#!/usr/bin/env python3
"""Interleaved whole-process timing of two or more builds of the same command.

    bench/ab_time.py BIN_A,BIN_B[,...] ARGS... [--runs N]

Each round runs every binary once with ARGS, in turn, so machine drift hits all alike; two
warm-up rounds are dropped. Prints the median and minimum wall time per binary. Use it to
measure one change (old and new binary side by side); peers-bench compares against peers.
"""
import statistics
import subprocess
import sys
import time


def main() -> int:
    args = sys.argv[1:]
    runs = 40
    if "--runs" in args:
        i = args.index("--runs")
        runs = int(args[i + 1])
        del args[i : i + 2]
    if len(args) < 1:
        print(__doc__, file=sys.stderr)
        return 2
    binaries, rest = args[0].split(","), args[1:]
    times = [[] for _ in binaries]
    for round_ in range(runs + 2):
        for b, samples in zip(binaries, times):
            start = time.perf_counter()
            subprocess.run([b, *rest], stdout=subprocess.DEVNULL, check=False)
            if round_ >= 2:
                samples.append((time.perf_counter() - start) * 1000)
    for b, samples in zip(binaries, times):
        print(f"{b}: median {statistics.median(samples):.2f} ms, min {min(samples):.2f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
