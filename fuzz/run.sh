#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/*_fuzz.cpp) with clang into a build folder of their own
# and runs each for SECONDS (default 60), one after the other, on its seed corpus
# (fuzz/corpus/<target without _fuzz>/) copied into the build folder, where what it finds is kept for the
# next run. Exits 1 if any target crashed, hung (over 10 s on one input), leaked or ran out of
# memory (2 GB), naming the input that did it.
# Usage: fuzz/run.sh [SECONDS] [TARGET...]
#        fuzz/run.sh --runs N [TARGET...]
# --runs N is CI's deterministic smoke (the fuzz_smoke test): each target first replays every
# seed and reproducer of its corpus folder, then makes N executions of mutations from a fixed
# seed (-seed=1) into an empty scratch corpus, so a commit gets the same answer on every run.
# Random, open-ended fuzzing (SECONDS) stays here for people; what it finds goes into
# fuzz/corpus/<target>/ as a reproducer, and from there into every smoke run.
# AOSUITE_FUZZ_BUILD sets the build folder (default: build-fuzz/ in the repository).
# AOSUITE_FUZZ_FRESH=1 drops what earlier runs kept and starts from the seeds alone (a large
# kept corpus can hide what one mutation of a seed reaches).
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
usage() {
  echo "usage: fuzz/run.sh [SECONDS] [TARGET...] | fuzz/run.sh --runs N [TARGET...]" >&2
  exit 2
}
runs="" seconds=60
if [ "${1:-}" = --runs ]; then
  runs=${2:-}
  [[ $runs =~ ^[1-9][0-9]*$ ]] || usage
  shift 2
elif [ $# -gt 0 ]; then
  seconds=$1
  [[ $seconds =~ ^[1-9][0-9]*$ ]] || usage
  shift
fi
build=${AOSUITE_FUZZ_BUILD:-$src/build-fuzz}
if [ $# -gt 0 ]; then
  targets=("$@")
else
  targets=()
  for f in "$src"/fuzz/*_fuzz.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi

start=$SECONDS
mkdir -p "$build"
# A folder already configured keeps its settings: fuzz_smoke runs in the instrumented build
# (tests/instrumented_build.sh), which also holds the sanitized tests.
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$src" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DAOSUITE_FUZZ=ON -DAOSUITE_BUILD_TESTS=OFF -DAOSUITE_BUILD_BENCH=OFF \
    >"$build/fuzz-configure.log" 2>&1 || { tail -n 30 "$build/fuzz-configure.log" >&2; exit 1; }
fi
grep -q '^AOSUITE_FUZZ:BOOL=ON' "$build/CMakeCache.txt" ||
  { echo "fuzz: $build is not configured with -DAOSUITE_FUZZ=ON" >&2; exit 2; }
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
  seeds=$src/fuzz/corpus/${t%_fuzz}
  corpus=$build/corpus/$t artifacts=$build/artifacts/$t/ log=$build/logs/$t.log
  if [ -n "$runs" ]; then
    # A scratch corpus that starts empty: the seeds folder is read (replayed first), never
    # written, and nothing an earlier run kept can change what this one does.
    corpus=$build/smoke-corpus/$t
    rm -rf "$corpus"
    mkdir -p "$corpus" "$artifacts"
    flags=(-seed=1 -runs="$runs") dirs=("$corpus" "$seeds")
  else
    if [ "${AOSUITE_FUZZ_FRESH:-0}" = 1 ]; then rm -rf "$corpus"; fi
    mkdir -p "$corpus" "$artifacts"
    cp -n "$seeds/"* "$corpus/"
    flags=(-max_total_time="$seconds") dirs=("$corpus")
  fi
  if "$build/fuzz/$t" "${flags[@]}" -rss_limit_mb=2048 -timeout=10 \
    -dict="$src/fuzz/$(dictionary "$t").dict" -artifact_prefix="$artifacts" \
    -print_final_stats=1 "${dirs[@]}" >"$log" 2>&1; then
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
if [ -n "$runs" ]; then each="seeds + $runs executions from seed 1"; else each="$seconds s"; fi
echo "fuzz: ${#targets[@]} targets, $each each, $((SECONDS - start)) s in all"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: failed: ${failed[*]}" >&2
  exit 1
fi
