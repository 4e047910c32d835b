#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/*_fuzz.cpp) with clang into a build folder of their own
# and runs each for SECONDS (default 60), one after the other, on its seed corpus
# (fuzz/corpus/<target without _fuzz>/) copied into the build folder, where what it finds is kept for the
# next run. Exits 1 if any target crashed, hung (over 10 s on one input), leaked or ran out of
# memory (2 GB), naming the input that did it.
# Usage: fuzz/run.sh [SECONDS] [TARGET...]
# AOSUITE_FUZZ_BUILD sets the build folder (default: build-fuzz/ in the repository).
# AOSUITE_FUZZ_FRESH=1 drops what earlier runs kept and starts from the seeds alone, as CI's
# fuzz_smoke does (a large kept corpus can hide what one mutation of a seed reaches).
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
if ! [[ $seconds =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: fuzz/run.sh [SECONDS] [TARGET...]" >&2
  exit 2
fi
shift $(($# > 0 ? 1 : 0))
build=${AOSUITE_FUZZ_BUILD:-$src/build-fuzz}
if [ $# -gt 0 ]; then
  targets=("$@")
else
  targets=()
  for f in "$src"/fuzz/*_fuzz.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi

start=$SECONDS
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
mkdir -p "$build"
cmake -S "$src" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DAOSUITE_FUZZ=ON -DAOSUITE_BUILD_TESTS=OFF -DAOSUITE_BUILD_BENCH=OFF "${launcher[@]}" \
  >"$build/fuzz-configure.log" 2>&1 || { tail -n 30 "$build/fuzz-configure.log" >&2; exit 1; }
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}" >"$build/fuzz-build.log" 2>&1 ||
  { tail -n 60 "$build/fuzz-build.log" >&2; exit 1; }
echo "fuzz: built ${#targets[@]} targets in $((SECONDS - start)) s"

dictionary() {
  case $1 in
    png_* | inflate_*) echo png ;;
    mesh_*) echo mesh ;;
    scene_* | suite_*) echo toml ;;
    exr_*) echo exr ;;
    *) echo json ;;
  esac
}

# Each target's scratch files (the parsers that read files) go here, not to /tmp.
export TMPDIR=$build/tmp
mkdir -p "$TMPDIR" "$build/logs"
export UBSAN_OPTIONS=print_stacktrace=1
export LSAN_OPTIONS=suppressions=$src/fuzz/lsan.supp:print_suppressions=0
failed=()
for t in "${targets[@]}"; do
  corpus=$build/corpus/$t artifacts=$build/artifacts/$t/ log=$build/logs/$t.log
  if [ "${AOSUITE_FUZZ_FRESH:-0}" = 1 ]; then rm -rf "$corpus"; fi
  mkdir -p "$corpus" "$artifacts"
  cp -n "$src/fuzz/corpus/${t%_fuzz}/"* "$corpus/"
  if "$build/fuzz/$t" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -dict="$src/fuzz/$(dictionary "$t").dict" -artifact_prefix="$artifacts" \
    -print_final_stats=1 "$corpus" >"$log" 2>&1; then
    # libFuzzer's last status line: executions, coverage (cov: edges), corpus, exec/s, memory.
    echo "fuzz: $t: $(grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -n 1)"
  else
    failed+=("$t")
    tail -n 40 "$log" >&2
    echo "fuzz: $t FAILED (log: $log)" >&2
    grep -o 'Test unit written to .*' "$log" | sed 's/^Test unit written to /fuzz: reproducer: /' >&2 ||
      true
    echo "fuzz: reproduce with: $build/fuzz/$t REPRODUCER" >&2
  fi
done
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, $((SECONDS - start)) s in all"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: failed: ${failed[*]}" >&2
  exit 1
fi
