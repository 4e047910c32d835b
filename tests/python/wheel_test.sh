#!/usr/bin/env bash
# The Python module as users build it with no network: `pip wheel --no-build-isolation` on a copy
# of the checkout, the wheel installed alone into a scratch folder, then
#   - `import aosuite` from there compares two arrays with the CLI's verdict and message;
#   - the pytest plugin loads by its entry point (no -p): a NumPy frame is gated against a
#     golden, --update-goldens writes it, and a failure writes the actual and diff images;
#   - check() without an aosuite command says how to get one.
# Usage: tests/python/wheel_test.sh SOURCE_DIR WORK_DIR AOSUITE_BIN
set -euo pipefail
src=$(realpath "$1") work=$2 aosuite=$(realpath "$3")
python=/usr/bin/python3
rm -rf "$work"
mkdir -p "$work/src"
work=$(realpath "$work")
tar -C "$src" --exclude='./build*' --exclude=./.git --exclude=./dist -cf - . | tar -C "$work/src" -xf -
cd "$work"
export CCACHE_BASEDIR=$work/src
if ! $python -m pip wheel --no-build-isolation --no-deps --no-index -w dist ./src >pip.log 2>&1; then
  tail -40 pip.log
  echo "wheel_test: pip wheel failed" >&2
  exit 1
fi
whl=$(ls dist/aosuite-*.whl)
$python -m zipfile -l "$whl" >listing.txt  # whole: grep -q on a pipe would cut the listing short
grep -q 'aosuite/_aosuite' listing.txt || { echo "no extension in $whl" >&2; exit 1; }
$python -m zipfile -e "$whl" site  # what pip install --target does, without pip's PEP 668 check
export PYTHONPATH=$work/site

# The same verdict as the command, on arrays.
$python - "$aosuite" <<'PY'
import subprocess, sys, numpy as np, aosuite
a = np.full((16, 16, 3), 100, np.uint8)
b = a.copy(); b[2:6, 2:6] = 160
r = aosuite.compare(b, a)
assert not r and r.message, r
aosuite.write_image("a.png", a); aosuite.write_image("b.png", b)
cli = subprocess.run([sys.argv[1], "compare", "a.png", "b.png"], capture_output=True, text=True)
assert cli.returncode == 1 and r.message in cli.stdout, (r.message, cli.stdout)
print("wheel: compare", r.message)
PY
$python -c 'import aosuite, sys; sys.exit(0 if "/site/aosuite/" in aosuite.__file__ else 1)'

# The plugin by entry point: a frame gated against a golden it writes on request.
mkdir -p t
cat >t/test_frame.py <<'PY'
import numpy as np
def test_frame(assert_matches_golden, request):
    frame = np.full((8, 8, 3), 90 if request.config.getoption("--update-goldens") else 200, np.uint8)
    assert_matches_golden(frame, "goldens/frame.png")
PY
(cd t && $python -m pytest -q -p no:cacheprovider --update-goldens test_frame.py >../first.log 2>&1) ||
  { cat first.log; echo "wheel_test: --update-goldens failed" >&2; exit 1; }
[ -f t/goldens/frame.png ] || { echo "wheel_test: no golden written" >&2; exit 1; }
set +e
(cd t && $python -m pytest -q -p no:cacheprovider test_frame.py >../second.log 2>&1)
rc=$?
set -e
if [ "$rc" != 1 ] || ! grep -q "diff" second.log; then
  cat second.log
  echo "wheel_test: a changed frame did not fail with its images (pytest exited $rc)" >&2
  exit 1
fi

# check() with no command anywhere: one clear error.
PATH=/usr/bin:/bin $python - <<'PY'
import aosuite
try:
    aosuite.check("nothing.toml")
except FileNotFoundError as e:
    assert "AOSUITE_BIN" in str(e), e
    print("wheel: check without a command:", e)
else:
    raise SystemExit("check() ran with no aosuite command")
PY
echo "wheel_test: $(basename "$whl") builds offline, installs alone, compares and gates"
