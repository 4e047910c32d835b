#!/usr/bin/env python3
"""AO error against the ray-traced reference with each G-buffer kind, as a Markdown table:
the accuracy half of issue 44's question whether XeGTAO's depth-only G-buffer (normals
reconstructed from depth) can replace the full one. render_bench's BM_GBuffer measures the cost.

    bench/gbuffer_accuracy.py [--bin build/aosuite] [--size 640x360] [--radius 0.5]
                              [--views village:street,workshop:interior,...]

Each technique at its defaults but the radius, every view, `aosuite error --gbuffer full` and
`--gbuffer depth` over the same reference (traced over the full G-buffer, so one yardstick).
The device does not matter: errors agree across devices to the fourth decimal.
"""
import argparse
import json
import subprocess

VIEWS = "village:street,village:overview,workshop:interior,workshop:exterior,spheres:front,corner:inside"


def rmse(args, scene, view, technique, gbuffer):
    width, height = args.size.split("x")
    out = subprocess.run(
        [args.bin, "error", "--scene", scene, "--view", view, "--technique", technique,
         "--width", width, "--height", height, "--radius", args.radius, "--gbuffer", gbuffer,
         "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)["error"]["all"]["rmse"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--bin", default="build/aosuite")
    p.add_argument("--size", default="640x360")
    p.add_argument("--radius", default="0.5")
    p.add_argument("--views", default=VIEWS)
    p.add_argument("--techniques", default="alchemy,sao,mssao,ue4,gtao,bitmask")
    args = p.parse_args()
    views = [v.split(":") for v in args.views.split(",")]
    print(f"AO RMSE against the reference, {args.size}, radius {args.radius}, mean over "
          f"{len(views)} views ({args.views})\n")
    print("| technique | full G-buffer | depth-only G-buffer | ratio | worst view's ratio |")
    print("| --- | --- | --- | --- | --- |")
    for technique in args.techniques.split(","):
        full = [rmse(args, s, v, technique, "full") for s, v in views]
        depth = [rmse(args, s, v, technique, "depth") for s, v in views]
        worst = max(d / f for f, d in zip(full, depth) if f > 0)
        mf, md = sum(full) / len(full), sum(depth) / len(depth)
        print(f"| {technique} | {mf:.4f} | {md:.4f} | {md / mf:.3f} | {worst:.3f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
