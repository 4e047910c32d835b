#!/usr/bin/env bash
# Sets up, builds and runs every test (unit tests and the differential test against the real
# Resemble.js in headless Chromium, which installs itself on first use).
# Extra arguments go to ctest, e.g. `scripts/test.sh -L unit` or `-LE oracle`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" "$@"
