"""The Python tests run against the build's module (PYTHONPATH=build/python, set by CTest) and
its `aosuite` command (AOSUITE_BIN)."""
import os

import pytest

pytest_plugins = ["aosuite.pytest_plugin", "pytester"]


@pytest.fixture(scope="session")
def aosuite_bin():
    return os.environ["AOSUITE_BIN"]
