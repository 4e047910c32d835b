#!/usr/bin/env python3
"""Interleaved whole-process timing of several commands.

    bench/interleaved.py 'NAME=COMMAND' 'NAME=COMMAND' ... [--runs N]

Each round runs every command once, in turn (through the shell, output discarded), so machine
drift hits all alike; two warm-up rounds are dropped. Prints each command's median and
minimum wall time and the ratio of each median to the first command's. A command that fails
stops the run: a timing of an error is no timing.
"""
import statistics
import subprocess
import sys
import time


def time_interleaved(commands, runs):
    """Per command, the wall times in ms of `runs` interleaved rounds after two warm-ups."""
    times = [[] for _ in commands]
    for round_ in range(runs + 2):
        for command, samples in zip(commands, times):
            start = time.perf_counter()
            done = subprocess.run(command, shell=True, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.PIPE, check=False)
            elapsed = (time.perf_counter() - start) * 1000
            if done.returncode not in (0, 1):  # 1: "different", a verdict
                sys.exit(f"{command}: exit status {done.returncode}: {done.stderr.decode()}")
            if round_ >= 2:
                samples.append(elapsed)
    return times


def take_runs(args, default):
    """The value of `--runs N` in `args` (removed from it), else `default`."""
    if "--runs" not in args:
        return default
    i = args.index("--runs")
    runs = int(args[i + 1])
    del args[i : i + 2]
    return runs


def main() -> int:
    args = sys.argv[1:]
    runs = take_runs(args, 15)
    if not args or any("=" not in a for a in args):
        print(__doc__, file=sys.stderr)
        return 2
    names = [a.split("=", 1)[0] for a in args]
    commands = [a.split("=", 1)[1] for a in args]
    times = time_interleaved(commands, runs)
    first = statistics.median(times[0])
    for name, samples in zip(names, times):
        median = statistics.median(samples)
        print(f"{name}: median {median:.1f} ms, min {min(samples):.1f} ms, "
              f"{median / first:.2f}x the first")
    return 0


if __name__ == "__main__":
    sys.exit(main())
