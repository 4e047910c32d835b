#!/usr/bin/env bash
# Sets up, builds and runs the tests, in two tiers:
#   scripts/test.sh          every behavioural test: unit, renderer, harness, suite, sweep, bench
#                            smoke runs, and the differential tests against the real Resemble.js
#                            (headless Chromium, installs itself on first use) and the metric
#                            oracles; everything but the `build` label.
#   scripts/test.sh --all    adds the `build` label: the second builds (without OSMesa; ASan +
#                            UBSan) and the deterministic fuzz smoke. CI (.ci/run) runs this.
# Other arguments go to ctest, e.g. `scripts/test.sh -L unit` or `scripts/test.sh --all -R fuzz`.
set -euo pipefail
cd "$(dirname "$0")/.."
tier=(-LE '^build$')
args=()
for a in "$@"; do
  if [ "$a" = --all ]; then tier=(); else args+=("$a"); fi
done
scripts/setup.sh
start=$SECONDS
# The tests set the CI variables they test: the caller's CI (CI=true here under .ci/run) must
# not change the defaults they check (--report-images, --annotations).
env -u CI -u GITHUB_ACTIONS -u GITHUB_STEP_SUMMARY \
  ctest --test-dir build --output-on-failure -j "$(nproc)" "${tier[@]}" "${args[@]}"
echo "[test] ctest took $((SECONDS - start)) s"
