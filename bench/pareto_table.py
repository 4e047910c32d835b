#!/usr/bin/env python3
"""Run time against error from a sweep: per radius, each technique's best configuration (mean
RMSE over the sweep's views), its mean AO time, and whether any of its configurations is on
that radius's Pareto front (no other configuration both faster and more accurate). Markdown,
for docs/results.md.

    bench/pareto_table.py reports/sweep_equal_radius/sweep.json [--label "H200, compute"]
"""
import argparse
import json
from collections import defaultdict


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("sweep")
    ap.add_argument("--label", default="")
    args = ap.parse_args()
    doc = json.load(open(args.sweep))
    configs = defaultdict(list)  # (radius, technique, samples, intensity) -> rows
    for r in doc["rows"]:
        configs[(r["radius"], r["technique"], r["samples"], r["intensity"])].append(r)
    means = {}
    for key, rows in configs.items():
        rmse = sum(r["error"]["all"]["rmse"] for r in rows) / len(rows)
        ms = sum(r["ao_gl_ms"] for r in rows) / len(rows)
        means[key] = (rmse, ms)
    print(f"{args.label}: {doc.get('gl_device', '')}, pipeline {doc.get('pipeline', '')}, "
          f"{len(doc['rows'])} rows\n")
    print("| radius | technique | best configuration (s, k) | mean RMSE | mean AO ms | on the Pareto front |")
    print("| --- | --- | --- | --- | --- | --- |")
    for radius in sorted({k[0] for k in means}):
        here = {k: v for k, v in means.items() if k[0] == radius}
        front = {k for k, (e, t) in here.items()
                 if not any(e2 <= e and t2 <= t and (e2, t2) != (e, t) for e2, t2 in here.values())}
        best = {}
        for k, (e, t) in here.items():
            if k[1] not in best or e < here[best[k[1]]][0]:
                best[k[1]] = k
        for tech, k in sorted(best.items(), key=lambda kv: here[kv[1]][0]):
            e, t = here[k]
            conf = (f"s={k[2]}, " if k[2] else "") + f"k={k[3]:g}"
            on = "yes" if any(f[1] == tech for f in front) else "no"
            print(f"| {radius:g} | {tech} | {conf} | {e:.4f} | {t:.3f} | {on} |")


if __name__ == "__main__":
    main()
