#!/usr/bin/python3
"""Expected FLIP and SSIM values from the reference implementations.

Writes the pairs of tests/metric_pairs.hpp to files (build/tests/metric_oracle_inputs), runs
  * FLIP: NVlabs/flip v1.6's own code (tests/oracles/flip_oracle_driver.cpp compiled against a
    checkout of https://github.com/NVlabs/flip, given by --flip-source or $FLIP_SOURCE), and,
    with --flip-tool, its FLIP-tool binary on every pair, to check that the driver prints what
    the tool prints (6 decimals);
  * SSIM: scikit-image's structural_similarity (Debian's python3-skimage 0.19),
and writes the numbers as JSON (default tests/data/metric_oracle.json).

Exit status 77 (CTest's skip) when an oracle is missing, with one line on stderr saying why
and how to enable it. The FLIP paths have no defaults but $FLIP_SOURCE and $FLIP_TOOL:
    git clone https://github.com/NVlabs/flip             # version 1.6
    g++ -O3 -fopenmp -std=c++17 flip/src/cpp/tool/FLIP-tool.cpp -o flip-tool
    FLIP_SOURCE=$PWD/flip FLIP_TOOL=$PWD/flip-tool ctest --test-dir build -R metric_oracle_live
or  tests/oracles/metric_oracle.py --build-dir build --flip-source DIR [--flip-tool FILE]
        [--out tests/data/metric_oracle.json]
"""
import argparse
import csv
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
SKIP = 77


def skip(reason):
    print(f"SKIPPED: {reason}", file=sys.stderr)
    sys.exit(SKIP)


HOW_TO_ENABLE = ("set FLIP_SOURCE to a checkout of https://github.com/NVlabs/flip v1.6 and, to "
                 "cross-check its tool too, FLIP_TOOL to its binary (g++ -O3 -fopenmp -std=c++17 "
                 "src/cpp/tool/FLIP-tool.cpp -o flip-tool in the checkout)")


def build_driver(flip_source, work):
    header = flip_source / "src/cpp/FLIP.h"
    if not header.exists():
        skip(f"no NVlabs/flip checkout at {flip_source}: {HOW_TO_ENABLE}")
    versions = (flip_source / "src/cpp/tool/FLIPToolHelpers.h").read_text(errors="replace")
    if "MajorVersion = 1;" not in versions or "MinorVersion = 6;" not in versions:
        skip(f"{flip_source} is not FLIP v1.6: {HOW_TO_ENABLE}")
    exe = work / "flip_oracle_driver"
    subprocess.run(["g++", "-O3", "-fopenmp", "-std=c++17", f"-I{flip_source}/src/cpp",
                    str(ROOT / "tests/oracles/flip_oracle_driver.cpp"), "-o", str(exe)],
                   check=True)
    return exe


def flip_tool_values(tool, ref, test, tone, work):
    """The tool's own CSV line (6 decimals)."""
    out = work / "tool.csv"
    if out.exists():
        out.unlink()
    cmd = [str(tool), "-r", str(ref), "-t", str(test), "--csv", str(out), "--no-error-map",
           "-v", "0", "-d", str(work)]
    if ref.suffix == ".exr":
        cmd += ["--tone-mapper", tone, "--no-exposure-map"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(out) as f:
        row = list(csv.reader(f))[1]
    return [float(v) for v in row[2:8]]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build-dir", default=str(ROOT / "build"))
    ap.add_argument("--flip-source", default=os.environ.get("FLIP_SOURCE") or None)
    ap.add_argument("--flip-tool", default=os.environ.get("FLIP_TOOL") or None)
    ap.add_argument("--out", default=str(ROOT / "tests/data/metric_oracle.json"))
    ap.add_argument("--check", metavar="METRIC_TESTS",
                    help="then run this test binary against the fresh numbers")
    args = ap.parse_args()

    try:
        import numpy as np
        import skimage
        from skimage.metrics import structural_similarity
    except ImportError as e:
        skip(f"scikit-image is not installed ({e}); apt-get install python3-skimage")
    if shutil.which("g++") is None:
        skip("no g++ to build the FLIP reference")

    if not args.flip_source:
        skip(f"FLIP_SOURCE is not set: {HOW_TO_ENABLE}")
    if args.flip_tool and not os.access(args.flip_tool, os.X_OK):
        skip(f"no FLIP tool at {args.flip_tool}: {HOW_TO_ENABLE}")
    inputs = pathlib.Path(args.build_dir) / "tests/metric_oracle_inputs"
    if not inputs.exists():
        skip(f"{inputs} is not built")
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        driver = build_driver(pathlib.Path(args.flip_source), work)
        pairs_dir = work / "pairs"
        subprocess.run([str(inputs), str(pairs_dir), str(ROOT / "tests/data/metric_renders")],
                       check=True)
        manifest = json.loads((pairs_dir / "manifest.json").read_text())
        results = []
        tool_checked = 0
        for p in manifest:
            name, w, h, hdr = p["name"], p["width"], p["height"], p["hdr"]
            ext = ".exr" if hdr else ".png"
            a_file, b_file = pairs_dir / f"{name}_a{ext}", pairs_dir / f"{name}_b{ext}"
            cmd = [str(driver), str(a_file), str(b_file)] + ([p["tone_mapper"]] if hdr else [])
            flip = json.loads(subprocess.run(cmd, check=True, capture_output=True,
                                             text=True).stdout)
            if args.flip_tool:
                tool = flip_tool_values(args.flip_tool, a_file, b_file, p["tone_mapper"], work)
                keys = ["mean", "weighted_median", "first_weighted_quartile",
                        "third_weighted_quartile", "min", "max"]
                for k, v in zip(keys, tool):
                    # The tool prints floats with 6 decimals; FLT_MIN (its max of an all-0 map)
                    # prints as 0.
                    if abs(flip[k] - v) > 5.01e-7:
                        sys.exit(f"{name}: driver {k} {flip[k]} but FLIP-tool says {v}")
                tool_checked += 1
            entry = {"name": name, "flip": flip}
            if hdr:
                a = np.fromfile(pairs_dir / f"{name}_a.raw", dtype=np.float32).reshape(h, w, 3)
                b = np.fromfile(pairs_dir / f"{name}_b.raw", dtype=np.float32).reshape(h, w, 3)
                if min(w, h) >= 11:
                    # One float channel: G mapped to [0, 1) in float32 as v / (1 + v).
                    fa = a[..., 1] / (np.float32(1) + a[..., 1])
                    fb = b[..., 1] / (np.float32(1) + b[..., 1])
                    kw = dict(gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                              data_range=1.0)
                    entry["ssim_float"] = float(structural_similarity(
                        fa.astype(np.float64), fb.astype(np.float64), **kw))
                    # scikit-image on float32 input computes in float32; for information.
                    entry["ssim_float32_skimage"] = float(structural_similarity(fa, fb, **kw))
            else:
                a = np.fromfile(pairs_dir / f"{name}_a.raw", dtype=np.uint8).reshape(h, w, 4)
                b = np.fromfile(pairs_dir / f"{name}_b.raw", dtype=np.uint8).reshape(h, w, 4)
                if min(w, h) >= 11:
                    kw = dict(gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                              data_range=255)
                    entry["ssim_rgb"] = float(structural_similarity(
                        a[..., :3], b[..., :3], channel_axis=2, **kw))
                    entry["ssim_gray8"] = float(structural_similarity(a[..., 0], b[..., 0], **kw))
            results.append(entry)
        doc = {
            "about": "Expected values for tests/metric_oracle_test.cpp, written by "
                     "tests/oracles/metric_oracle.py",
            "flip": "NVlabs/flip v1.6 (C++ tool code, FLIP::evaluate + tool pooling), default "
                    "PPD, HDR automatic exposures",
            "flip_tool_checked_pairs": tool_checked,
            "skimage": skimage.__version__,
            "pairs": results,
        }
        pathlib.Path(args.out).write_text(json.dumps(doc, indent=0) + "\n")
        print(f"{len(results)} pairs -> {args.out} (FLIP tool cross-checked on {tool_checked})")
    if args.check:
        env = dict(os.environ, AOSUITE_METRIC_ORACLE=str(pathlib.Path(args.out).resolve()))
        sys.exit(subprocess.run([args.check, "--gtest_filter=MetricOracle.*"], env=env).returncode)


if __name__ == "__main__":
    main()
