#!/usr/bin/env bash
# The default suite gates the renderer tightly enough to catch a one-weight change to the blur
# (0.4578 -> 0.5478, 1 to 4 levels on most renders, under Resemble's `less` threshold): with the
# shaders so changed (AOSUITE_SHADER_DIR), checking its village-street cases must fail, with the
# three tapped estimators (alchemy, sao, mssao: 2 to 4 levels) among the failures. (GTAO, UE4 and
# the bitmask move by one level there, within the suite's one-level budget.)
# Usage: tests/default_suite_mutation.sh SOURCE_DIR AOSUITE WORK_DIR
set -euo pipefail
src=$1 aosuite=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cp -r "$src/renderer/passes/shaders" "$work/shaders"
grep -q '0\.457833362' "$work/shaders/blur.glsl"
sed -i 's/0\.457833362/0.547833362/' "$work/shaders/blur.glsl"
set +e
AOSUITE_SHADER_DIR="$work/shaders" "$aosuite" check "$src/suites/default.toml" \
  --filter '^village-street-' --report "$work/report" --no-reuse >"$work/out.txt"
rc=$?
set -e
cat "$work/out.txt"
if [ "$rc" -ne 1 ]; then
  echo "default_suite_mutation: the suite exited $rc with a mutated blur (1 expected)" >&2
  exit 1
fi
failed=$(grep -c '^\[.*\] FAIL ' "$work/out.txt")
if [ "$failed" -lt 3 ]; then
  echo "default_suite_mutation: only $failed village-street cases caught the mutated blur" >&2
  exit 1
fi
echo "default_suite_mutation: $failed cases caught the mutated blur"
