#!/usr/bin/env python3
"""Per-pass GPU time of every technique, as a Markdown table for bench/README.md.

    bench/pass_table.py [--bin build/aosuite] [--scene village] [--view street]
                        [--runs 20] [--sizes 1920x1080,3840x2160] [--pipeline fragment]
                        [--techniques gtao,sao] [-- extra render args]

For each size and technique it runs `aosuite render --outputs all --runs N` (one warm-up
frame, then N timed frames) and prints the median GPU time of each pass (GL_TIME_ELAPSED) and
the frame's wall time before read-back. `--pipeline` picks fragment draws or compute dispatches
for the screen-space passes (default: the device's, `aosuite gl-info`); the caption names the
one that ran and the device, whatever `--gl`/`AOSUITE_GL` pick. On a GPU machine:
`AOSUITE_GL=egl bench/pass_table.py --pipeline compute`.
"""
import argparse
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path



def techniques(binary):
    """The registered techniques, as `render --help` lists them ("alchemy|sao|...")."""
    text = subprocess.run([binary, "render", "--help"], check=True, capture_output=True,
                          text=True).stdout
    # CLI11 wraps the choices onto the next line when the option's default is long.
    after = text[text.index("--technique"):]
    return re.search(r"\b[a-z0-9_]+(?:\|[a-z0-9_]+)+", after).group(0).split("|")


def render(args, technique, width, height, out):
    cmd = [args.bin, "render", "--scene", args.scene, "--technique", technique,
           "--width", str(width), "--height", str(height), "--outputs", "all",
           "--runs", str(args.runs), "--out", out] + args.extra
    if args.view:
        cmd += ["--view", args.view]
    if args.pipeline:
        cmd += ["--pipeline", args.pipeline]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.loads(next(Path(out).glob(f"*_{technique}.json")).read_text())


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--bin", default="build/aosuite")
    p.add_argument("--scene", default="village")
    p.add_argument("--view", default="")
    p.add_argument("--runs", type=int, default=20)
    p.add_argument("--sizes", default="1920x1080,3840x2160")
    p.add_argument("--pipeline", choices=["fragment", "compute"],
                   help="the screen-space passes' pipeline (default: the device's)")
    p.add_argument("--techniques", default="",
                   help="comma-separated (default: every registered technique)")
    p.add_argument("extra", nargs="*", help="more `render` arguments, after --")
    args = p.parse_args()
    device = pipeline = None
    names = args.techniques.split(",") if args.techniques else techniques(args.bin)
    for size in args.sizes.split(","):
        width, height = (int(v) for v in size.split("x"))
        rows = []
        for technique in names:
            with tempfile.TemporaryDirectory() as out:
                j = render(args, technique, width, height, out)
            device = f"{j['gl_device']}: {j['gl']}"
            pipeline = f'{j["pipeline"]} pipeline, {j.get("gbuffer", "full")} G-buffer'
            ms = j["median_ms"]
            # The G-buffer is one pass or, depth-only, two (gbuffer, gbuffer_normals).
            gbuffer = sum(v for k, v in ms.items() if k.startswith("gbuffer"))
            ao = sum(v for k, v in ms.items()
                     if not k.startswith("gbuffer") and k not in ("blur", "blend", "frame_wall"))
            rows.append((technique, gbuffer, ao, ms.get("blur", 0),
                         ms.get("blend", 0), ms["frame_wall"],
                         ", ".join(f"{k} {v:.3f}" for k, v in ms.items()
                                   if not k.startswith("gbuffer")
                                   and k not in ("blur", "blend", "frame_wall", "ao"))))
        print(f"\n{args.scene} {width}x{height}, {pipeline}, median of {args.runs} frames, "
              f"{device}\n")
        print("| technique | G-buffer ms | AO ms | blur ms | blend ms | frame wall ms | AO sub-passes |")
        print("| --- | --- | --- | --- | --- | --- | --- |")
        for r in rows:
            print(f"| {r[0]} | {r[1]:.3f} | {r[2]:.3f} | {r[3]:.3f} | {r[4]:.3f} | {r[5]:.3f} | {r[6]} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
