#!/usr/bin/env python3
"""Do the built-in tuned presets transfer to scenes the tuner never saw? For each technique,
scene view and radius: AO RMSE against the ray-traced reference (`aosuite error`) with the
technique's defaults and with `--preset tuned`, and their ratio (tuned / defaults; < 1 is better).
`--preset half` measures what the half-resolution AO costs in error the same way.

  python3 bench/transfer_check.py --scene suites/scenes/snowden.toml
      [--preset tuned] [--technique gtao ...] [--radius 0.25 --radius 0.5 --radius 1]
      [--width 320 --height 180] [--rays 256] [--json out.json]

Prints one row per (technique, view, radius), then per technique: how many pairs got worse, the
worst ratio, and the geometric mean ratio. Needs build/aosuite (and the scenes' meshes).
"""
import argparse
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
AOSUITE = os.path.join(HERE, "..", "build", "aosuite")


def views_of(scene):
    """The view names of a built-in scene or a scene file, as `aosuite scenes --json` lists them."""
    files = [scene] if scene.endswith(".toml") else []
    out = subprocess.run([AOSUITE, "scenes", "--json"] + files, check=True, capture_output=True,
                         text=True).stdout
    for s in json.loads(out)["scenes"]:
        if files or s["name"] == scene:
            return [v["name"] for v in s["views"]]
    sys.exit(f"no scene {scene}")


def rmse(args, scene, view, technique, radius, preset):
    cmd = [AOSUITE, "error", "--scene", scene, "--view", view, "--technique", technique,
           "--width", str(args.width), "--height", str(args.height), "--rays", str(args.rays),
           "--json"] + (["--preset", preset] if preset else []) + ["--radius", str(radius)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)["error"]["all"]["rmse"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", action="append", required=True)
    ap.add_argument("--preset", default="tuned", help="the built-in preset or file to measure")
    ap.add_argument("--technique", action="append")
    ap.add_argument("--radius", action="append", type=float)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--rays", type=int, default=256)
    ap.add_argument("--json")
    args = ap.parse_args()
    techniques = args.technique or ["alchemy", "sao", "mssao", "ue4", "gtao", "bitmask"]
    radii = args.radius or [0.25, 0.5, 1.0]
    rows = []
    for scene in args.scene:
        for view in views_of(scene):
            for r in radii:
                for t in techniques:
                    d = rmse(args, scene, view, t, r, None)
                    p = rmse(args, scene, view, t, r, args.preset)
                    rows.append({"technique": t, "scene": scene, "view": view, "radius": r,
                                 "defaults": d, args.preset: p, "ratio": p / d if d > 0 else 1.0})
                    print(f"{t:8} {os.path.basename(scene):14} {view:20} r={r:<5} "
                          f"defaults {d:.4f} {args.preset} {p:.4f} ratio {rows[-1]['ratio']:.3f}",
                          flush=True)
    print()
    print(f"{'technique':10} pairs  worse  worse>5%  worst ratio  geo-mean ratio")
    for t in techniques:
        mine = [x["ratio"] for x in rows if x["technique"] == t]
        worse = sum(x > 1 for x in mine)
        print(f"{t:10} {len(mine):5} {worse:6} {sum(x > 1.05 for x in mine):9} {max(mine):12.3f} "
              f"{math.exp(sum(map(math.log, mine)) / len(mine)):15.3f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
