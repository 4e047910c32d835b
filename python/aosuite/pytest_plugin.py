"""pytest plugin: golden-image assertions with aosuite's one comparison.

    pytest -p aosuite.pytest_plugin            # or pytest_plugins = ["aosuite.pytest_plugin"]

    def test_frame(assert_matches_golden):
        assert_matches_golden(render(), "goldens/frame.png", max_mismatch_percent=0.1)

`pytest --update-goldens` writes missing and failing goldens instead of failing. A failure writes
the actual image and the diff under the test's own folder of pytest's temporary directory, names
them in the assertion message, and adds an "aosuite" section to the test's report.
"""

from __future__ import annotations

import re

import pytest

import aosuite


def pytest_addoption(parser):
    parser.addoption("--update-goldens", action="store_true", default=False,
                     help="aosuite: write missing and failing goldens from the images")


@pytest.fixture
def assert_matches_golden(request, tmp_path_factory):
    update = request.config.getoption("--update-goldens")
    test = re.sub(r"[^A-Za-z0-9_.-]", "_", request.node.name)

    def check(image, golden, **tolerance):
        failures = tmp_path_factory.getbasetemp() / "aosuite-failures" / test
        result = aosuite.matches_golden(image, golden, update=update, failures=str(failures),
                                        **tolerance)
        if not result:
            lines = [f"{result.status}: {result.message}"]
            if result.actual_file:
                lines.append(f"actual: {result.actual_file}")
            if result.diff_file:
                lines.append(f"diff: {result.diff_file}")
            request.node.add_report_section("call", "aosuite", "\n".join(lines))
            raise AssertionError(f"{golden}: {result.status}: {result.message}")
        return result

    return check
