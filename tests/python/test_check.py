"""aosuite.check and aosuite.bless run a suite as the command does: NEW, bless, PASS, a changed
image FAILs with the command's message, approve from the report, and a malformed suite raises
one clear error."""
import numpy as np
import pytest

import aosuite


def _suite(tmp_path, level):
    (tmp_path / "img").mkdir(exist_ok=True)
    for name, value in (("a", level), ("b", 90)):
        img = np.zeros((12, 16, 3), np.uint8)
        img[..., 0] = np.arange(16, dtype=np.uint8) * 10
        img[4:8, 4:8] = value
        aosuite.write_image(tmp_path / "img" / f"{name}.png", img)
    suite = tmp_path / "s.toml"
    suite.write_text('[[case]]\nname = "a"\nfiles = ["img/a.png"]\n\n'
                     '[[case]]\nname = "b"\nfiles = ["img/b.png"]\n')
    return suite


def test_check_bless_and_approve(tmp_path):
    suite = _suite(tmp_path, 40)
    report = tmp_path / "report"
    run = aosuite.check(suite, report=report)
    assert not run and run.exit_status == 1
    assert [c["status"] for c in run.cases] == ["NEW", "NEW"]
    assert run.summary["new"] == 2

    aosuite.bless(suite)
    run = aosuite.check(suite, report=report)
    assert run and run.summary["passed"] == 2

    _suite(tmp_path, 80)  # case a changes
    run = aosuite.check(suite, report=report)
    assert run.exit_status == 1
    a = run.case("a")
    assert a["status"] == "FAIL" and "max channel delta 40 (allowed 8)" in a["message"]
    assert run.case("b")["status"] == "PASS"
    assert (report / "index.html").exists()

    aosuite.bless(suite, failed=True, report=report)
    assert aosuite.check(suite, report=report)


def test_a_malformed_suite_is_one_clear_error(tmp_path):
    suite = tmp_path / "bad.toml"
    suite.write_text("[[case]]\nname = \"x\"\nfiles = 3\n")
    with pytest.raises(ValueError, match="bad.toml"):
        aosuite.check(suite, report=tmp_path / "r")
