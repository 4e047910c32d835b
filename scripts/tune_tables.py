#!/usr/bin/env python3
"""docs/results.md's tables of the tuned presets, from `aosuite tune --json` files
(scripts/tune_presets.sh writes them to reports/tune/). Everything here is measured on held-out
families: each family of scenes left out in turn, the preset's search run on the others.

1. Per technique, issue 45's bar: the share of the way from the defaults the tune chose, and at
   that share the held-out (scene, radius) pairs, how many got worse than the defaults, the
   worst ratio and the geometric mean ratio; and whether the preset (the all-scenes search moved
   by that share) differs from the defaults at all.
2. Per family and radius: the techniques ranked at their defaults and tuned (the chosen share of
   each fold's search), and the best tuned technique against the best default one. A technique
   that left a scene of the family out (PMI: the plane, ground alone) is ranked only where its
   scenes are the others'.

Usage: scripts/tune_tables.py [reports/tune]"""
import json
import math
import sys
from pathlib import Path


def chosen(run):
    """The shrink trial the tune chose, and the one at share 0 (the defaults)."""
    trials = run["shrink"]["trials"]
    pick = next(t for t in trials if t["shrink"] == run["shrink"]["chosen"])
    return pick, next(t for t in trials if t["shrink"] == 0)


def bar_table(runs):
    bar = runs[0]["shrink"]["bar"]
    print(f"Bar: at most {100 * bar['worse_share']:g} % of held-out pairs worse, none by more "
          f"than {100 * (bar['worst_ratio'] - 1):g} %.")
    print()
    print("| technique | share chosen | held-out pairs | worse | worst ratio | geometric mean "
          "ratio | per family (geometric mean) | preset | depth taps |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in runs:
        pick, _ = chosen(r)
        families = ", ".join(f"{f['held_out']} {x:.3f}"
                             for f, x in zip(r["folds"], pick["fold_ratio"]))
        print(f"| {r['technique']} | {pick['shrink']:g} | {pick['pairs']} | {pick['worse']} | "
              f"{pick['worst_ratio']:.3f} | {pick['mean_ratio']:.3f} | {families} | "
              f"{'the defaults' if r['preset'] == r['default'] else 'moved'} | "
              f"{r['taps']['default']} → {r['taps']['tuned']} |")
    print()


def family_table(runs, radii):
    # errors[(family, k)][technique] = (default, tuned), where the technique's scenes are all
    # of the family's (the most scenes any technique measured there).
    scenes = {}
    for r in runs:
        for f in r["folds"]:
            names = tuple(s["scene"] for s in f["scenes"])
            if len(names) > len(scenes.get(f["held_out"], ())):
                scenes[f["held_out"]] = names
    errors = {}
    for r in runs:
        pick, zero = chosen(r)
        for i, f in enumerate(r["folds"]):
            if tuple(s["scene"] for s in f["scenes"]) != scenes[f["held_out"]]:
                continue
            for k in range(len(radii)):
                errors.setdefault((f["held_out"], k), {})[r["technique"]] = (
                    zero["fold_error"][i][k], pick["fold_error"][i][k])
    print("| family (scenes) | r | ranking, defaults | ranking, tuned | best tuned vs best "
          "default |")
    print("| --- | --- | --- | --- | --- |")
    margins = []
    for family, names in scenes.items():
        for k, radius in enumerate(radii):
            e = errors[(family, k)]
            rd = sorted(e, key=lambda t: e[t][0])
            rt = sorted(e, key=lambda t: e[t][1])
            bd, bt = e[rd[0]][0], e[rt[0]][1]
            margins.append(bt / bd)
            text = lambda order, i: ", ".join(f"{t} {e[t][i]:.4f}" for t in order)
            print(f"| {family} ({', '.join(names)}) | {radius:g} | {text(rd, 0)} | {text(rt, 1)} "
                  f"| {rt[0]} {bt:.4f} vs {rd[0]} {bd:.4f}: {100 * (bt / bd - 1):+.1f} % |")
    print()
    print(f"Best tuned over best default: worst {max(margins):.3f}, geometric mean "
          f"{math.exp(sum(map(math.log, margins)) / len(margins)):.3f} over {len(margins)} "
          f"(family, radius) pairs.")


def main():
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else "reports/tune")
    runs = [json.loads(p.read_text()) for p in sorted(folder.glob("*.json"))
            if not p.name.endswith(".state.json")]
    runs = [r for r in runs if r.get("folds") and r["shrink"]["trials"]]
    if not runs:
        sys.exit(f"{folder}: no tune --json with folds")
    bar_table(runs)
    family_table(runs, runs[0]["radii"])


if __name__ == "__main__":
    main()
