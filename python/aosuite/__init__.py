"""aosuite from Python: the one comparison the `aosuite` command runs, on NumPy arrays and files.

    import aosuite
    result = aosuite.compare(frame, "goldens/frame.png", max_mismatch_percent=0.1)
    assert result, result.message

Images are file paths (any format aosuite reads) or arrays, height x width [x channels]:
uint8 (1-4 channels, as a browser canvas holds them), uint16 (1 or 3, as a 16-bit PNG) or
float32/float64 (1 or 3 linear channels, as an EXR). The tolerance is keyword arguments named as
in a suite's [tolerance] table (LIMIT_KEYS); every limit not named keeps its default, so the
verdict and its message are exactly the CLI's.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from dataclasses import dataclass, field
from typing import Any, Optional

from . import _aosuite

LIMIT_KEYS = _aosuite.LIMIT_KEYS
__all__ = ["Result", "Run", "compare", "matches_golden", "write_image", "check", "bless",
           "LIMIT_KEYS"]


@dataclass
class Result:
    """One comparison's outcome. True when the images count as the same (PASS or WARN)."""

    status: str  # PASS, WARN, FAIL (matches_golden: NEW when there is no golden yet)
    message: str  # the failed limits, "warning: ..." for warned ones, "" when it passed
    failed: list = field(default_factory=list)
    warned: list = field(default_factory=list)
    identical: bool = False
    comparable: bool = False
    actual_kind: str = ""
    expected_kind: str = ""
    mismatch_percent: float = 0.0
    mismatch_text: str = ""
    max_channel_delta: int = 0
    differing_pixels: int = 0
    mean_shift: float = 0.0
    mean_delta: float = 0.0
    largest: tuple = (0.0, -1, -1)  # largest difference and its first (x, y)
    metrics: dict = field(default_factory=dict)  # {"flip": {"mean": ...}, ...}
    diff: Any = None  # Resemble's diff image (uint8 RGBA) when asked for and not the same
    actual_file: str = ""  # matches_golden: the failure images written, or ""
    diff_file: str = ""

    def __bool__(self) -> bool:
        return self.status in ("PASS", "WARN")


def compare(actual, expected, *, gates=(), float_gates=(), metrics=(), diff=False,
            **limits) -> Result:
    """`actual` against `expected`, as `aosuite compare` judges them.

    gates: "METRIC.KEY=VALUE" as `--gate` ("flip.max_mean=0.02"), beside the limits;
    float_gates: the same for float images only; metrics: names measured without a limit
    ("flip", "ssim", "rmse", "psnr"); diff: return Resemble's diff image when they differ.
    """
    return Result(**_aosuite.compare(actual, expected, gates=list(gates),
                                     float_gates=list(float_gates), metrics=list(metrics),
                                     diff=diff, **limits))


def write_image(file, image) -> None:
    """Writes a uint8 array as PNG or a float array as EXR, replacing the file only once complete."""
    _aosuite.write_image(os.fspath(file), image)


def _update_requested() -> bool:
    return os.environ.get("AOSUITE_UPDATE_GOLDENS", "") not in ("", "0")


def matches_golden(image, golden, *, update: Optional[bool] = None,
                   failures: Optional[str] = None, name: Optional[str] = None,
                   **tolerance) -> Result:
    """`image` against the golden file, as the C++ API's matches_golden.

    NEW when there is no golden yet. With `update` (default: AOSUITE_UPDATE_GOLDENS=1) a missing
    or failing golden is written from the image in its own format, and the result is PASS. On a
    failure the actual image and the diff are written under `failures` (default:
    $AOSUITE_FAILURES, else ./aosuite-failures), in a folder `name` (default: the golden's stem),
    and the message names them.
    """
    golden = os.fspath(golden)
    update = _update_requested() if update is None else update
    if not os.path.exists(golden):
        if update:
            os.makedirs(os.path.dirname(golden) or ".", exist_ok=True)
            write_image(golden, image)
            return Result(status="PASS", message="", identical=True)
        return Result(status="NEW", message=f"no golden yet at {golden} "
                      "(AOSUITE_UPDATE_GOLDENS=1 or pytest --update-goldens writes it)")
    result = compare(image, golden, diff=True, **tolerance)
    if result:
        return result
    if update:
        write_image(golden, image)
        return Result(status="PASS", message="")
    folder = os.path.join(failures or os.environ.get("AOSUITE_FAILURES", "aosuite-failures"),
                          name or os.path.splitext(os.path.basename(golden))[0])
    os.makedirs(folder, exist_ok=True)
    ext = os.path.splitext(golden)[1]
    result.actual_file = os.path.abspath(os.path.join(folder, "actual" + ext))
    write_image(result.actual_file, image)
    if result.diff is not None:
        result.diff_file = os.path.abspath(os.path.join(folder, "diff.png"))
        write_image(result.diff_file, result.diff)
    written = result.actual_file + (", " + result.diff_file if result.diff_file else "")
    result.message = f"{golden}: {result.message} (written: {written})"
    return result


@dataclass
class Run:
    """A suite run: the `aosuite` command's exit status, its cases and summary as `--json`
    prints them (each case as results.json records it), and its report folder."""

    exit_status: int  # 0 all passed, 1 any failed or new, 2 any could not be judged
    cases: list
    summary: dict
    report: str
    stderr: str = ""

    def __bool__(self) -> bool:
        return self.exit_status == 0

    def case(self, case_id: str) -> dict:
        return next(c for c in self.cases if c["id"] == case_id)


def _aosuite_command() -> str:
    # AOSUITE_BIN, else the aosuite on PATH, else the build this module was built with (none
    # for a wheel).
    found = (os.environ.get("AOSUITE_BIN") or shutil.which("aosuite")
             or _aosuite.BUILD_AOSUITE)
    if not found:
        raise FileNotFoundError("no aosuite command: install the aosuite package, or set "
                                "AOSUITE_BIN to the aosuite program")
    return found


def _suite_args(suite, goldens, filter, shard):
    args = [os.fspath(suite)]
    if goldens is not None:
        args += ["--goldens", os.fspath(goldens)]
    if filter is not None:
        args += ["--filter", filter]
    if shard is not None:
        args += ["--shard", shard]
    return args


def check(suite, *, report=None, goldens=None, filter=None, shard=None, jobs=None,
          junit=None, extra=()) -> Run:
    """Runs `aosuite check` on a suite file and returns its results: the same run, verdicts,
    messages, report and exit status as the command (it is the command)."""
    report = os.fspath(report) if report is not None else os.path.join(
        "reports", os.path.splitext(os.path.basename(os.fspath(suite)))[0])
    args = [_aosuite_command(), "check", *_suite_args(suite, goldens, filter, shard),
            "--report", report, "--json"]
    if jobs is not None:
        args += ["-j", str(jobs)]
    if junit is not None:
        args += ["--junit", os.fspath(junit)]
    done = subprocess.run(args + list(extra), capture_output=True, text=True, check=False)
    lines = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    cases = [line for line in lines if line.get("type") == "case"]
    summary = next((line for line in lines if line.get("type") == "summary"), {})
    if done.returncode == 2 and not summary:
        raise ValueError(done.stderr.strip() or f"aosuite check exited with 2: {args}")
    return Run(done.returncode, cases, summary, report, done.stderr)


def bless(suite, *, goldens=None, filter=None, report=None, failed=False, force=False) -> int:
    """Runs `aosuite bless` (from `report`'s images with failed=True); returns its exit status,
    raising ValueError with its message when it could not bless."""
    args = [_aosuite_command(), "bless", *_suite_args(suite, goldens, filter, None)]
    if failed:
        args += ["--failed"]
    if report is not None:
        args += ["--report", os.fspath(report)]
    if force:
        args += ["--force"]
    done = subprocess.run(args, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise ValueError(done.stderr.strip() or done.stdout.strip())
    return done.returncode
