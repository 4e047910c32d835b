#!/usr/bin/env bash
# Configures and builds aosuite without its OSMesa backend (as on Mesa >= 25.1), then runs the
# default suite against its goldens through EGL and checks that OSMesa is refused, not used.
# Usage: tests/no_osmesa_build.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1 build=$2
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DAOSUITE_OSMESA=OFF \
  -DAOSUITE_BUILD_TESTS=OFF -DAOSUITE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target aosuite >/dev/null
"$build/aosuite" gl-info --json | grep -q '"osmesa_built": false'
"$build/aosuite" check "$src/suites/default.toml" --no-reuse --jobs "$(nproc)" \
  --report "$build/report-default"
if "$build/aosuite" render --gl osmesa --width 8 --height 8 --out "$build/refused" 2>"$build/err"; then
  echo "no_osmesa_build: --gl osmesa rendered in a build without OSMesa" >&2
  exit 1
fi
grep -q "no OSMesa backend" "$build/err"
test ! -e "$build/refused"
echo "no_osmesa_build: default suite passed without OSMesa"
