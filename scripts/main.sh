#!/usr/bin/env bash
# Sets up, builds and runs the main job. Until the harness lands this compares the sample
# images without and with ambient occlusion, as Resemble.js's ignoreLess would, and writes
# the diff image into reports/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
mkdir -p reports
set +e
build/aosuite compare tests/data/sample_no_ao.png tests/data/sample_ao.png --mode less \
  --diff reports/sample-diff.png
rc=$?
set -e
echo "diff image: reports/sample-diff.png (exit status $rc: 0 same, 1 different, 2 error)"
[ "$rc" -le 1 ]
