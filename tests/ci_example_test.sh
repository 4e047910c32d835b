#!/usr/bin/env bash
# examples/ci: the sharded workflow's steps (examples/ci/run_shards.sh) on a suite of image cases
# with passing, failing and new cases give the same verdicts, messages and JUnit counts as one
# run of the whole suite; blessing from the merged report makes the next run pass; a missing
# shard is refused.
#   tests/ci_example_test.sh SOURCE_DIR AOSUITE
set -euo pipefail
src=$1 aosuite=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/aosuite-ci-example.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir -p s/img
draw() {  # draw NAME R G B: a 16x16 picture with a gradient, so cases differ
  /usr/bin/python3 - "$@" <<'PY'
import sys
from PIL import Image
name, r, g, b = sys.argv[1], *map(int, sys.argv[2:])
img = Image.new("RGB", (16, 16))
img.putdata([((r + x * 3) % 256, (g + y * 5) % 256, b) for y in range(16) for x in range(16)])
img.save(f"s/img/{name}.png")
PY
}
: >s/suite.toml
for i in 0 1 2 3 4 5 6 7; do
  draw "c$i" $((i * 30)) $((i * 20)) $((200 - i * 10))
  printf '[[case]]\nname = "c%s"\nfiles = ["img/c%s.png"]\n\n' "$i" "$i" >>s/suite.toml
done
"$aosuite" bless s/suite.toml --filter '^c[0-6]$' >/dev/null   # c7 stays NEW
draw c2 0 0 0        # a real change
draw c5 150 100 153  # a small one: fails the default tolerance
set +e
"$aosuite" check s/suite.toml --report single --junit single.xml >single.log
single=$?
"$src/examples/ci/run_shards.sh" s/suite.toml 3 sharded "$aosuite" >sharded.log
sharded=$?
set -e
[ "$single" = 1 ] && [ "$sharded" = 1 ] || {
  echo "exit statuses: single $single, sharded $sharded" >&2
  cat single.log sharded.log >&2
  exit 1
}
/usr/bin/python3 - <<'PY'
import json, re, sys
def cases(path):
    run = json.load(open(path))
    return run, {c["id"]: (c["status"], c["message"],
                           [(i["status"], i.get("mismatch_percent")) for i in c["images"]])
                 for c in run["cases"]}
single_run, single = cases("single/results.json")
merged_run, merged = cases("sharded/merged/results.json")
assert single == merged, (single, merged)
assert sorted(s for s, *_ in single.values()).count("FAIL") == 2, single
assert single["c7"][0] == "NEW", single["c7"]
assert "partial" not in merged_run.get("shard", ""), merged_run.get("shard")
counts = lambda f: re.search(r'<testsuite [^>]*tests="(\d+)" failures="(\d+)"', open(f).read()).groups()
assert counts("single.xml") == counts("sharded/junit.xml") == ("8", "3"), (counts("single.xml"), counts("sharded/junit.xml"))
PY
# The workflow's bless job: accept what the merged report shows; the next run passes.
"$aosuite" bless s/suite.toml --failed --report sharded/merged >/dev/null
"$aosuite" check s/suite.toml --report again >/dev/null
# A merge with a shard missing is refused (exit 2), writing nothing.
set +e
"$aosuite" report merge --out partial sharded/shard-0 sharded/shard-2 2>merge.err
rc=$?
set -e
[ "$rc" = 2 ] && [ ! -e partial/results.json ] || {
  echo "merge without shard 1: exit $rc" >&2
  cat merge.err >&2
  exit 1
}
echo "ci example: 3 shards merged = one run (8 cases: 2 FAIL, 1 NEW); bless from the merged report passes"
