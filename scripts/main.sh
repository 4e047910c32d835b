#!/usr/bin/env bash
# Sets up, builds and runs the main job. Until the harness lands (suites/, goldens/), the
# job renders the built-in village's street view with each AO technique at the thesis's
# defaults and measures, as the thesis's Tables 11-14 do, how much of the image AO changes:
# Resemble.js ignoreLess and ignoreNothing mismatch between the no-AO and with-AO images.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
out=reports/main
mkdir -p "$out"
for technique in alchemy sao mssao ue4; do
  build/aosuite render --scene village --technique "$technique" --width 640 --height 360 \
    --out "$out" >/dev/null
  for mode in less nothing; do
    set +e
    pct=$(build/aosuite compare "$out/village_street_${technique}_no_ao.png" \
      "$out/village_street_${technique}_with_ao.png" --mode "$mode" --json \
      | sed -E 's/.*"misMatchPercentage":"([^"]*)".*/\1/')
    set -e
    echo "$technique ignore-$mode: ${pct}% of pixels changed by AO"
  done
done
echo "images, AO terms (EXR) and per-pass times: $out/"
