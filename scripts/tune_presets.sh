#!/usr/bin/env bash
# Regenerates the built-in `tuned` presets (ao/presets/tuned-TECHNIQUE.toml): each technique
# searched against the ray-traced reference at r = 0.25, 0.5 and 1 on the built-in
# scenes, on the meshes scripts/fetch_assets.sh fetches (suites/scenes/*.toml, the dragon) and on
# the architecture scenes (Sponza, Sibenik: scripts/import_assets.sh),
# each candidate within GTAO High's 18 depth taps (a preset left at its defaults keeps their cost), and validated by leaving one family of scenes out at a time. The results (JSON,
# and the printed tables) go to ${OUT:-reports/tune}; docs/results.md quotes them.
# PMI has no depth taps: it is searched for the map from its visibility to AO, on the scenes with
# an object (plane, ground alone, is left out).
# Usage: scripts/tune_presets.sh [TECHNIQUE...]   (default: every technique)
# AOSUITE: the binary (default build/aosuite), e.g. a copy that a rebuild cannot replace midway.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-reports/tune}
mkdir -p "$out"
scenes=plane,corner,spheres,village,workshop,suites/scenes/bunny.toml,suites/scenes/teapot.toml,suites/scenes/effector.toml,suites/scenes/ship.toml,dragon,suites/scenes/sponza.toml,suites/scenes/sibenik.toml
techniques=("$@")
[ ${#techniques[@]} -gt 0 ] || techniques=(alchemy sao mssao ue4 gtao bitmask pmi)
for t in "${techniques[@]}"; do
  "${AOSUITE:-build/aosuite}" tune --technique "$t" --radius 0.25 --radius 0.5 --radius 1 --scenes "$scenes" \
    --trials 96 --out "ao/presets/tuned-$t.toml" --state "$out/$t.state.json" \
    --json "$out/$t.json" | tee "$out/$t.txt"
done
