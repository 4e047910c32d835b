#!/usr/bin/env python3
"""Interleaved whole-process timing of two or more builds of the same command.

    bench/ab_time.py BIN_A,BIN_B[,...] ARGS... [--runs N]

Each round runs every binary once with ARGS, in turn, so machine drift hits all alike; two
warm-up rounds are dropped (bench/interleaved.py, which times any commands). Prints the median
and minimum wall time per binary. Use it to measure one change (old and new binary side by
side); peers-bench compares against peers.
"""
import shlex
import statistics
import sys

from interleaved import take_runs, time_interleaved


def main() -> int:
    args = sys.argv[1:]
    runs = take_runs(args, 40)
    if len(args) < 1:
        print(__doc__, file=sys.stderr)
        return 2
    binaries, rest = args[0].split(","), args[1:]
    commands = [shlex.join([b, *rest]) for b in binaries]
    for b, samples in zip(binaries, time_interleaved(commands, runs)):
        print(f"{b}: median {statistics.median(samples):.2f} ms, min {min(samples):.2f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
