#!/usr/bin/env bash
# The steps of github-actions.yml on one machine: run SUITE in N shards (each its own report
# folder, as each matrix job's), merge them into one report and one JUnit file, and exit with the
# merged result (0 all passed, 1 any failed or new, 2 any could not be judged), as the workflow's
# merge job does. A shard's own exit status is not the verdict: only the merged report is.
#
#   examples/ci/run_shards.sh SUITE N OUT [AOSUITE]     # OUT/shard-<i>/, OUT/merged/, OUT/junit.xml
set -uo pipefail
suite=$1 n=$2 out=$3 aosuite=${4:-aosuite}
mkdir -p "$out"
for ((i = 0; i < n; i++)); do
  # One matrix job each in CI; exit 2 (a broken shard) stops here, 0 and 1 go on to the merge.
  "$aosuite" check "$suite" --shard "$i/$n" --report "$out/shard-$i" >"$out/shard-$i.log"
  rc=$?
  if [ "$rc" -ge 2 ]; then
    cat "$out/shard-$i.log" >&2
    exit "$rc"
  fi
done
shards=()
for ((i = 0; i < n; i++)); do shards+=("$out/shard-$i"); done
"$aosuite" report merge --out "$out/merged" --junit "$out/junit.xml" "${shards[@]}"
