#!/usr/bin/env python3
"""docs/results.md's tables of the tuned presets, from `aosuite tune --json` files
(scripts/tune_presets.sh writes them to reports/tune/): per technique and radius the error on
scenes left out of the search, under the defaults and tuned; the ranking that makes; and which
technique is best on each scene. Usage: scripts/tune_tables.py [reports/tune]"""
import json
import statistics
import sys
from pathlib import Path


def scene_name(s):
    return Path(s).stem if s.endswith(".toml") else s


def mean_sd(values):
    return statistics.mean(values), (statistics.stdev(values) if len(values) > 1 else 0.0)


def main():
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else "reports/tune")
    runs = [json.loads(p.read_text()) for p in sorted(folder.glob("*.json"))
            if not p.name.endswith(".state.json")]
    runs = [r for r in runs if "folds" in r]
    radii = runs[0]["radii"]
    print("| technique | r | default, held out | tuned, held out | change | depth taps | "
          "AO ms at 320×180 |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    held = {}  # (technique, kind, k) -> per-scene errors
    for r in runs:
        t = r["technique"]
        for k, radius in enumerate(radii):
            d = [f["default"][k] for f in r["folds"]]
            u = [f["tuned"][k] for f in r["folds"]]
            held[(t, "default", k)], held[(t, "tuned", k)] = d, u
            (dm, dsd), (um, usd) = mean_sd(d), mean_sd(u)
            print(f"| {t} | {radius:g} | {dm:.4f} ± {dsd:.4f} | {um:.4f} ± {usd:.4f} | "
                  f"{100 * (um / dm - 1):+.1f} % | {r['taps']['default']} → {r['taps']['tuned']} | "
                  f"{r['ao_ms']['default']:.1f} → {r['ao_ms']['tuned']:.1f} |")
    print()
    print("| r | ranking, defaults (held-out mean) | ranking, tuned (held-out mean) | "
          "best tuned vs best default |")
    print("| --- | --- | --- | --- |")
    techniques = [r["technique"] for r in runs]
    for k, radius in enumerate(radii):
        def ranking(kind):
            return sorted(techniques, key=lambda t: statistics.mean(held[(t, kind, k)]))
        rd, rt = ranking("default"), ranking("tuned")
        bd = statistics.mean(held[(rd[0], "default", k)])
        bt = statistics.mean(held[(rt[0], "tuned", k)])
        text = lambda order, kind: ", ".join(
            f"{t} {statistics.mean(held[(t, kind, k)]):.4f}" for t in order)
        print(f"| {radius:g} | {text(rd, 'default')} | {text(rt, 'tuned')} | "
              f"{rt[0]} {bt:.4f} vs {rd[0]} {bd:.4f}: {100 * (bt / bd - 1):+.1f} % |")
    print()
    scenes = [scene_name(f["held_out"]) for f in runs[0]["folds"]]
    print("| scene | " + " | ".join(f"best at r = {r:g}: default / tuned" for r in radii) + " |")
    print("| --- |" + " --- |" * len(radii))
    for i, s in enumerate(scenes):
        cells = []
        for k in range(len(radii)):
            def best(kind):  # every technique within 5e-5 of the lowest error: a tie
                low = min(held[(t, kind, k)][i] for t in techniques)
                tied = [t for t in techniques if held[(t, kind, k)][i] - low < 5e-5]
                return f"{'='.join(tied) if len(tied) < 3 else 'tie'} {low:.4f}"
            cells.append(f"{best('default')} / {best('tuned')}")
        print(f"| {s} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
