#!/usr/bin/env python3
"""The harness at scale: a synthetic suite of N image cases (small PNGs on disk, N/100 of them
changed), checked cold, its report written, and the page opened in headless Chromium.

    python3 bench/report_scale.py [--cases 2000] [--size 64x48] [--jobs 2] [--dir DIR]

Prints the check's wall time, the report's size, and when the page became interactive: the
page's own mark (performance.now() at the end of its start-up script, i.e. from navigation
start) and Chromium's whole process (browser start-up included)."""
import argparse
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib


def png(width, height, seed):
    rows = []
    for y in range(height):
        row = bytearray([0])
        for x in range(width):
            row += bytes(((x * 4 + seed) & 255, (y * 5 + seed * 7) & 255, (seed * 13) & 255, 255))
        rows.append(bytes(row))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(b"".join(rows), 6)) + chunk(b"IEND", b""))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--cases", type=int, default=2000)
    p.add_argument("--size", default="64x48")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--dir")
    p.add_argument("--aosuite", default=os.path.abspath("build/aosuite"))
    a = p.parse_args()
    width, height = map(int, a.size.split("x"))
    work = a.dir or tempfile.mkdtemp(prefix="aosuite-scale-")
    shutil.rmtree(os.path.join(work, "img"), ignore_errors=True)
    os.makedirs(os.path.join(work, "img"), exist_ok=True)
    with open(os.path.join(work, "scale.toml"), "w") as suite:
        suite.write("[defaults.tolerance]\nmax_mismatch_percent = 1\n")
        for i in range(a.cases):
            name = f"c{i:05d}"
            with open(os.path.join(work, "img", name + ".png"), "wb") as f:
                f.write(png(width, height, i))
            suite.write(f'[[case]]\nname = "{name}"\nfiles = ["img/{name}.png"]\n')
    run = lambda *args: subprocess.run([a.aosuite, *args], cwd=work, capture_output=True, text=True)
    for d in ("goldens", "reports"):
        shutil.rmtree(os.path.join(work, d), ignore_errors=True)
    blessed = run("bless", "scale.toml", "--jobs", str(a.jobs))
    assert blessed.returncode == 0, blessed.stdout[-2000:] + blessed.stderr
    for i in range(0, a.cases, 100):  # one in a hundred changes
        with open(os.path.join(work, "img", f"c{i:05d}.png"), "wb") as f:
            f.write(png(width, height, i + 64))
    def timed_check(*extra):
        t0 = time.monotonic()
        out = run("check", "scale.toml", "--jobs", str(a.jobs), *extra)
        assert out.returncode == 1, out.stdout[-2000:] + out.stderr
        return time.monotonic() - t0, out

    shutil.rmtree(os.path.join(work, "reports"), ignore_errors=True)
    cold_s, _ = timed_check()  # a fresh report folder: every file created
    check_s, checked = timed_check("--no-reuse")  # the folder of the last run, nothing reused
    summary = checked.stdout.strip().splitlines()
    summary = next(line for line in summary if line.startswith(f"{a.cases} cases"))
    rerun_s, _ = timed_check()
    report = os.path.join(work, "reports", "scale")
    index = os.path.getsize(os.path.join(report, "index.html"))
    total = sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(report) for f in fs)
    ready, wall = [], []
    for _ in range(3):
        t0 = time.monotonic()
        dom = subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--dump-dom",
                              "file://" + os.path.join(report, "index.html")],
                             capture_output=True, text=True).stdout
        wall.append(time.monotonic() - t0)
        m = re.search(r'data-ready-ms="(\d+)"', dom)
        assert m, "the page never became ready"
        ready.append(int(m.group(1)))
    print(f"{a.cases} cases of {width}x{height}, --jobs {a.jobs}: {summary}")
    print(f"check, report included: fresh report folder {cold_s:.2f} s; --no-reuse over the last "
          f"report {check_s:.2f} s; unchanged re-run {rerun_s:.2f} s")
    print(f"report: index.html {index / 1e6:.2f} MB, folder {total / 1e6:.1f} MB")
    print(f"page interactive (its own mark, from navigation start): median {sorted(ready)[1]} ms of {ready}")
    print(f"chromium --dump-dom, whole process: median {sorted(wall)[1]:.2f} s")
    print(f"check (--no-reuse) + page interactive: {check_s + sorted(ready)[1] / 1000:.2f} s; "
          f"fresh folder: {cold_s + sorted(ready)[1] / 1000:.2f} s")
    with open("/proc/loadavg") as f:
        print("load average:", f.read().split()[0])


if __name__ == "__main__":
    sys.exit(main())
