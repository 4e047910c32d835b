#!/usr/bin/env python3
"""docs/results.md's tables of the tuned presets, from `aosuite tune --json` files
(scripts/tune_presets.sh writes them to reports/tune/): per technique and radius the error on
scenes left out of the search, under the defaults and tuned; the ranking that makes, on the
scenes every technique was measured on (PMI leaves out a scene of ground alone); and which
technique is best on each scene. Usage: scripts/tune_tables.py [reports/tune]"""
import json
import statistics
import sys
from pathlib import Path


def scene_name(s):
    return Path(s).stem if s.endswith(".toml") else s


def mean_sd(values):
    return statistics.mean(values), (statistics.stdev(values) if len(values) > 1 else 0.0)


def ranking_table(techniques, scenes, held, radii):
    print(f"{', '.join(techniques)}, ranked on {len(scenes)} scenes ({', '.join(scenes)}):")
    print()
    print("| r | ranking, defaults (held-out mean) | ranking, tuned (held-out mean) | "
          "best tuned vs best default |")
    print("| --- | --- | --- | --- |")
    for k, radius in enumerate(radii):
        def mean(t, kind):
            return statistics.mean(held[(t, kind, k)][s] for s in scenes)

        def ranking(kind):
            return sorted(techniques, key=lambda t: mean(t, kind))
        rd, rt = ranking("default"), ranking("tuned")
        bd, bt = mean(rd[0], "default"), mean(rt[0], "tuned")
        text = lambda order, kind: ", ".join(f"{t} {mean(t, kind):.4f}" for t in order)
        print(f"| {radius:g} | {text(rd, 'default')} | {text(rt, 'tuned')} | "
              f"{rt[0]} {bt:.4f} vs {rd[0]} {bd:.4f}: {100 * (bt / bd - 1):+.1f} % |")
    print()


def main():
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else "reports/tune")
    runs = [json.loads(p.read_text()) for p in sorted(folder.glob("*.json"))
            if not p.name.endswith(".state.json")]
    runs = [r for r in runs if "folds" in r]
    radii = runs[0]["radii"]
    # held[(technique, kind, k)][scene] = the error on that scene left out
    held = {}
    for r in runs:
        for k in range(len(radii)):
            for kind in ("default", "tuned"):
                held[(r["technique"], kind, k)] = {
                    scene_name(f["held_out"]): f[kind][k] for f in r["folds"]}
    print("| technique | r | scenes | default, held out | tuned, held out | change | depth taps | "
          "AO ms at 320×180 |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in runs:
        t = r["technique"]
        for k, radius in enumerate(radii):
            d, u = held[(t, "default", k)], held[(t, "tuned", k)]
            (dm, dsd), (um, usd) = mean_sd(list(d.values())), mean_sd(list(u.values()))
            print(f"| {t} | {radius:g} | {len(d)} | {dm:.4f} ± {dsd:.4f} | {um:.4f} ± {usd:.4f} | "
                  f"{100 * (um / dm - 1):+.1f} % | {r['taps']['default']} → {r['taps']['tuned']} | "
                  f"{r['ao_ms']['default']:.1f} → {r['ao_ms']['tuned']:.1f} |")
    print()
    techniques = [r["technique"] for r in runs]
    scenes = [scene_name(f["held_out"]) for f in max(runs, key=lambda r: len(r["folds"]))["folds"]]
    # The techniques measured on every scene, ranked on all of them; then, when some technique
    # left a scene out (PMI: ground alone), every technique on the scenes they all share.
    full = [t for t in techniques if all(s in held[(t, "default", 0)] for s in scenes)]
    common = [s for s in scenes if all(s in held[(t, "default", 0)] for t in techniques)]
    if full:
        ranking_table(full, scenes, held, radii)
    if len(full) < len(techniques) and common:
        ranking_table(techniques, common, held, radii)
    print("| scene | " + " | ".join(f"best at r = {r:g}: default / tuned" for r in radii) + " |")
    print("| --- |" + " --- |" * len(radii))
    for s in scenes:
        cells = []
        for k in range(len(radii)):
            def best(kind):  # every technique within 5e-5 of the lowest error: a tie
                errors = {t: held[(t, kind, k)][s] for t in techniques
                          if s in held[(t, kind, k)]}
                low = min(errors.values())
                tied = [t for t, e in errors.items() if e - low < 5e-5]
                return f"{'='.join(tied) if len(tied) < 3 else 'tie'} {low:.4f}"
            cells.append(f"{best('default')} / {best('tuned')}")
        print(f"| {s} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
