"""Builds aosuite's Python extension (_aosuite) through the project's CMake, for a wheel or an
sdist (pyproject.toml): only the image tool (no renderer, tests or benchmarks) is configured,
and only the module's target built."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(aosuite VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                        "-DAOSUITE_RENDERER=OFF", "-DAOSUITE_BUILD_TESTS=OFF",
                        "-DAOSUITE_BUILD_BENCH=OFF", "-DAOSUITE_PYTHON=ON",
                        f"-DPython3_EXECUTABLE={sys.executable}",
                        # No build folder to fall back on once installed: check() needs the
                        # aosuite command on PATH or AOSUITE_BIN.
                        "-DAOSUITE_PYTHON_FALLBACK_BIN="], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "aosuite_python", "-j",
                        str(os.cpu_count() or 1)], check=True)
        built = next((build / "python" / "aosuite").glob("_aosuite*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(version=project_version(), ext_modules=[Extension("aosuite._aosuite", sources=[])],
      cmdclass={"build_ext": CMakeBuild})
