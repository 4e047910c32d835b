#!/usr/bin/env bash
# Runs the unit, renderer, harness and sweep tests in the instrumented build
# (tests/instrumented_build.sh: clang, AddressSanitizer + UndefinedBehaviorSanitizer). Any ASan,
# UBSan or LeakSanitizer report fails the run. Leaks are suppressed only in third-party
# libraries (tests/sanitize_lsan.supp: today libOSMesa alone), never in aosuite's own code.
# Usage: tests/sanitize.sh SOURCE_DIR BUILD_DIR [extra ctest arguments]
set -euo pipefail
src=$(cd "$1" && pwd) build=$2
shift 2
start=$SECONDS

# abort_on_error: a report kills the process (a test that spawns aosuite sees it fail too).
# Every check on, odr-violation included: libaosuite_gl.so links libaosuite_check.so instead of
# carrying a second copy of the harness (cli/CMakeLists.txt), so a suite with scene cases, which
# loads both, has one copy of every global.
# intercept_tls_get_addr=0: LeakSanitizer tells glibc's dynamic TLS blocks apart by an address
# test that some heap layouts pass by chance (google/sanitizers#1322); its tracer then scans a
# bogus range and crashes at exit ("Tracer caught signal 11"), so an unrelated change that moves
# the heap could fail this test. aosuite has no thread_local; stacks, globals and static TLS are
# still scanned.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1:check_initialization_order=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$src/tests/sanitize_lsan.supp:print_suppressions=0
# gtest_discover_tests stands a <target>_NOT_BUILT test, with no label, for a missing executable.
missing=$(ctest --test-dir "$build" -N | grep -o '[A-Za-z0-9_]*_NOT_BUILT' || true)
if [ -n "$missing" ]; then
  echo "sanitize: test executables not built: $(echo $missing)" >&2
  exit 1
fi
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -L '^(unit|renderer|harness|sweep)$' "$@"
echo "sanitize: tests passed in $((SECONDS - start)) s"
