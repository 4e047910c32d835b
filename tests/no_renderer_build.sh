#!/usr/bin/env bash
# Configures and builds aosuite without the AO bench (-DAOSUITE_RENDERER=OFF): the image-
# regression tool alone. Checks that nothing it built needs GL, EGL, Embree, assimp or OpenCV,
# that the bench's commands say it is absent, then runs the main build's image-case and
# folder-mode tests (harness_cli_tests, ImageCases.*) against it.
# Usage: tests/no_renderer_build.sh SOURCE_DIR BUILD_DIR HARNESS_CLI_TESTS
set -euo pipefail
src=$1 build=$2 tests=$3
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DAOSUITE_RENDERER=OFF \
  -DAOSUITE_BUILD_TESTS=OFF -DAOSUITE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target aosuite >/dev/null
test ! -e "$build/libaosuite_gl.so"
# libaosuite_oiio.so is left out: Debian's OpenImageIO itself links OpenCV, and it is opened
# only for formats other than PNG and EXR.
for f in "$build/aosuite" "$build/libaosuite_check.so" "$build/libaosuite_exr.so"; do
  if readelf -d "$f" | grep NEEDED | grep -Ei 'libGL|libEGL|OSMesa|embree|assimp|opencv'; then
    echo "no_renderer_build: $f needs a renderer library" >&2
    exit 1
  fi
done
if "$build/aosuite" render 2>"$build/err"; then
  echo "no_renderer_build: render ran without the AO bench" >&2
  exit 1
fi
grep -q "built without the AO bench" "$build/err"
AOSUITE_TEST_BIN="$build/aosuite" "$tests" --gtest_filter='ImageCases.*'
echo "no_renderer_build: the image-regression tool passed its image-case and folder-mode tests"
