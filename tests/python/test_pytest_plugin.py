"""The pytest plugin as a renderer's test suite uses it, run in a pytester sandbox: NEW without
a golden, --update-goldens writes it, a changed frame fails naming the failure images it wrote
and adds an "aosuite" report section."""
import numpy as np

import aosuite

TEST_FILE = """
import numpy as np

def frame(level):
    img = np.zeros((24, 32, 3), np.uint8)
    img[..., 0] = np.arange(32, dtype=np.uint8) * 8
    img[8:16, 8:16] = level
    return img

def test_frame(assert_matches_golden):
    assert_matches_golden(frame(LEVEL), "goldens/frame.png")
"""


def _run(pytester, level, *args):
    pytester.makepyfile(test_render=TEST_FILE.replace("LEVEL", str(level)))
    return pytester.runpytest("-p", "aosuite.pytest_plugin", *args)


def test_new_then_update_then_pass_then_fail(pytester):
    result = _run(pytester, 100)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*NEW: no golden yet at goldens/frame.png*"])
    golden = pytester.path / "goldens" / "frame.png"
    assert not golden.exists()

    _run(pytester, 100, "--update-goldens").assert_outcomes(passed=1)
    assert golden.exists()
    _run(pytester, 100).assert_outcomes(passed=1)

    before = golden.read_bytes()
    result = _run(pytester, 140, "-rA")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*FAIL: *max channel delta 40 (allowed 8)*",
                                 "*aosuite*", "*actual: *aosuite-failures*actual.png*"])
    assert golden.read_bytes() == before  # a failure never touches the golden
    written = [line.split("actual: ", 1)[1].strip() for line in result.outlines
               if line.startswith("actual: ")]
    assert written, result.outlines
    actual = aosuite.compare(written[0], golden)
    assert not actual and actual.max_channel_delta == 40

    _run(pytester, 140, "--update-goldens").assert_outcomes(passed=1)
    assert golden.read_bytes() != before
    _run(pytester, 140).assert_outcomes(passed=1)


def test_matches_golden_writes_failure_images(tmp_path):
    golden = tmp_path / "g.png"
    frame = np.full((8, 8, 4), 200, np.uint8)
    assert aosuite.matches_golden(frame, golden).status == "NEW"
    assert aosuite.matches_golden(frame, golden, update=True)
    changed = frame.copy()
    changed[2:4, 2:4, :3] = 0
    result = aosuite.matches_golden(changed, golden, failures=str(tmp_path / "f"), name="t")
    assert result.status == "FAIL"
    assert result.actual_file.endswith("f/t/actual.png") and result.diff_file.endswith("diff.png")
    assert aosuite.compare(result.actual_file, changed)
    assert str(golden) in result.message and result.actual_file in result.message
