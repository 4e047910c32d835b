#!/usr/bin/env bash
# Builds every target once with clang, AddressSanitizer + UndefinedBehaviorSanitizer and
# libFuzzer's coverage instrumentation (-DAOSUITE_SANITIZE=ON -DAOSUITE_FUZZ=ON), at -O1, into
# BUILD_DIR. Two tests use it (tests/CMakeLists.txt, fixture `instrumented`): `sanitize` runs
# the unit, renderer, harness and sweep tests in it (tests/sanitize.sh), `fuzz_smoke` its fuzz
# targets (fuzz/run.sh). One build for both, at -O1 rather than -O3: on CI's two cores the two
# separate -O3 builds took over 50 minutes together and ran past their limits; checks find the
# same faults at -O1, which is what the sanitizers' own documentation recommends.
# Usage: tests/instrumented_build.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$(cd "$1" && pwd) build=$2
start=$SECONDS
mkdir -p "$build"
cmake -S "$src" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
  "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" -DAOSUITE_SANITIZE=ON -DAOSUITE_FUZZ=ON \
  -DAOSUITE_BUILD_TESTS=ON -DAOSUITE_BUILD_BENCH=OFF >"$build/configure.log" 2>&1 ||
  { tail -n 30 "$build/configure.log" >&2; exit 1; }
# Every target, so no test executable or fuzz target is left out by a list kept by hand.
cmake --build "$build" -j "$(nproc)" >"$build/build.log" 2>&1 ||
  { grep -m 20 -B 2 -A 8 'error' "$build/build.log" >&2 || tail -n 60 "$build/build.log" >&2; exit 1; }
echo "instrumented build: $((SECONDS - start)) s"
