"""aosuite.compare gives the CLI's verdict and failed limits on the same images, whether they are
arrays or files: generated pairs (a fixed seed; regressions and benign changes) under several
tolerances, each compared through the module twice and through `aosuite compare --json`."""
import json
import subprocess

import numpy as np
import pytest

import aosuite

CHANGES = {
    "identical": lambda a, rng: a.copy(),
    "brighter 2 %": lambda a, rng: np.clip(a.astype(int) * 102 // 100, 0, 255).astype(np.uint8),
    "noise 1 %": lambda a, rng: np.clip(a + rng.integers(-4, 5, a.shape), 0, 255).astype(np.uint8),
    "±1 on a few pixels": lambda a, rng: _few(a, rng, 1),
    "patch": lambda a, rng: _patch(a),
    "1 px shift": lambda a, rng: np.roll(a, 1, axis=1),
    "channel swap": lambda a, rng: a[..., ::-1].copy(),
}
TOLERANCES = [
    {},
    {"max_mismatch_percent": 1},
    {"max_channel_delta": 255, "max_mean_shift": 3, "max_mean_delta": 3},
    {"mode": "nothing"},
    {"shift_radius": 1},
]


def _few(a, rng, delta):
    b = a.astype(int)
    for _ in range(3):
        y, x = rng.integers(0, a.shape[0]), rng.integers(0, a.shape[1])
        b[y, x, :3] += delta
    return np.clip(b, 0, 255).astype(np.uint8)


def _patch(a):
    b = a.copy()
    b[4:10, 4:10, :3] = 255 - b[4:10, 4:10, :3]
    return b


def _base(rng, channels):
    # A smooth gradient with texture: what a render looks like more than white noise does.
    y, x = np.mgrid[0:40, 0:48]
    img = np.stack([(x * 5) % 256, (y * 6) % 256, (x + y) * 2 % 256, np.full_like(x, 255)], -1)
    img = np.clip(img + rng.integers(-10, 11, img.shape), 0, 255).astype(np.uint8)
    img[..., 3] = 255
    return img[..., :channels]


def _cli(aosuite_bin, actual, expected, limits):
    # `aosuite compare REFERENCE TEST`: the second file is judged against the first.
    args = [aosuite_bin, "compare", str(expected), str(actual), "--json"]
    for k, v in limits.items():
        args += ["--limit", f"{k}={str(v).lower() if isinstance(v, bool) else v}"]
    run = subprocess.run(args, capture_output=True, text=True, check=False)
    assert run.returncode in (0, 1), run.stderr
    return run.returncode, json.loads(run.stdout)


@pytest.mark.parametrize("channels", [3, 4])
@pytest.mark.parametrize("change", sorted(CHANGES))
def test_same_verdict_as_the_cli(tmp_path, aosuite_bin, change, channels):
    rng = np.random.default_rng(7)
    expected = _base(rng, channels)
    actual = CHANGES[change](expected, rng)
    a, e = tmp_path / "a.png", tmp_path / "e.png"
    aosuite.write_image(a, actual)
    aosuite.write_image(e, expected)
    for limits in TOLERANCES:
        in_memory = aosuite.compare(actual, expected, **limits)
        on_disk = aosuite.compare(a, e, **limits)
        rc, cli = _cli(aosuite_bin, a, e, limits)
        assert bool(in_memory) == bool(on_disk) == (rc == 0), (change, limits)
        assert in_memory.failed == on_disk.failed == cli.get("failed_gates", []), (change, limits)
        assert in_memory.mismatch_percent == pytest.approx(cli["rawMisMatchPercentage"])


def test_defaults_fail_regressions_and_pass_benign_changes():
    rng = np.random.default_rng(11)
    expected = _base(rng, 3)
    for change in ("brighter 2 %", "noise 1 %", "patch", "1 px shift", "channel swap"):
        assert not aosuite.compare(CHANGES[change](expected, rng), expected), change
    assert aosuite.compare(CHANGES["±1 on a few pixels"](expected, rng), expected)


def test_a_limit_named_changes_only_that_limit():
    rng = np.random.default_rng(3)
    expected = _base(rng, 3)
    brighter = CHANGES["brighter 2 %"](expected, rng)
    # Lifting the channel cap leaves the mean-shift limit in force.
    result = aosuite.compare(brighter, expected, max_channel_delta=255)
    assert not result and any("mean shift" in f for f in result.failed), result.failed


def test_16_bit_and_float_arrays():
    grey16 = (np.arange(64 * 64, dtype=np.uint16).reshape(64, 64) * 13)
    assert aosuite.compare(grey16, grey16.copy())
    assert not aosuite.compare(grey16, grey16 // 2)
    linear = np.linspace(0, 4, 32 * 32 * 3, dtype=np.float32).reshape(32, 32, 3)
    assert aosuite.compare(linear, linear.copy())
    # Float images without a gate must be identical; a FLIP gate judges them perceptually.
    nudged = linear + 1e-4
    assert not aosuite.compare(nudged, linear)
    gated = aosuite.compare(nudged, linear, float_gates=["flip.max_mean=0.02"])
    assert gated and gated.metrics["flip"]["mean"] < 0.02
    # Another bit depth is a failure unless allowed.
    eight = (grey16 >> 8).astype(np.uint8)
    assert not aosuite.compare(eight, grey16)


def test_bad_input_is_one_clear_error(tmp_path):
    img = np.zeros((4, 4, 3), np.uint8)
    with pytest.raises(ValueError, match="unknown limit 'max_mismatch'"):
        aosuite.compare(img, img, max_mismatch=1)
    with pytest.raises(ValueError, match="missing.png"):
        aosuite.compare(tmp_path / "missing.png", img)
    with pytest.raises(TypeError, match="uint8, uint16, float32 or float64"):
        aosuite.compare(img.astype(np.int32), img)
    (tmp_path / "junk.png").write_bytes(b"not a png")
    with pytest.raises(ValueError, match="junk.png"):
        aosuite.compare(tmp_path / "junk.png", img)
