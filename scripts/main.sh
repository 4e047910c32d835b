#!/usr/bin/env bash
# Sets up, builds and runs the main job: the default suite (every built-in scene and view,
# the four AO techniques) rendered and gated against goldens/default, with an HTML report.
# Exit status is aosuite check's: 0 all passed, 1 a case failed or is new, 2 error.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build/aosuite check suites/default.toml --report reports/default "$@"
