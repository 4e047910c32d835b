#!/usr/bin/env bash
# bench/gpu_check.sh, the script a GPU lease runs, on llvmpipe at 64x36 with one frame each: it
# must print its three tables (fragment, compute, compute over the depth-only G-buffer), each
# with a row for every technique `aosuite render --help` names, so that no lease is spent on a
# broken script (one was: pass_table.py misread the help once CLI11 wrapped its choices).
#   tests/gpu_check_smoke.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1
build=$2
out=$(AOSUITE_GL=${AOSUITE_GL:-auto} GPU_CHECK_SIZES=64x36 "$src/bench/gpu_check.sh" "$build" 1)
choices=$("$build/aosuite" render --help | grep -A1 -e '--technique' |
  grep -oE '[a-z0-9_]+(\|[a-z0-9_]+)+')
tables=$(grep -c '^| technique | G-buffer ms | AO ms' <<<"$out")
[ "$tables" = 3 ] || { echo "gpu_check.sh printed $tables tables, not 3:"; echo "$out"; exit 1; }
for t in ${choices//|/ }; do
  rows=$(grep -cE "^\| $t \| [0-9.]+ \| [0-9.]+ \|" <<<"$out" || true)
  [ "$rows" = 3 ] || { echo "gpu_check.sh: $t has $rows rows with times, not 3:"; echo "$out"; exit 1; }
done
echo "gpu_check.sh: 3 tables, a timed row for each of: ${choices//|/ }"
