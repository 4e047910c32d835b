#!/usr/bin/env python3
"""Writes the tolerance corpus (tests/corpus_test.cpp): pairs of a golden ("expected") and a new
image ("actual") that a regression gate must fail (regressions/) or pass (benign/) under its
default tolerance. Deterministic (seeded); rerun it to regenerate:

    python3 tests/data/corpus/make_corpus.py tests/data/corpus

The images are what a renderer writes, not picked to pass: a shaded scene with antialiased edges
and a soft occlusion term; each regression is one realistic defect, each benign case a change of
encoder that keeps every pixel, or a driver's +-1 on a few pixels."""
import os
import sys

import numpy as np
from PIL import Image, ImageFilter

W, H = 192, 108
rng = np.random.default_rng(20261127)


def scene():
    """A sky gradient, a floor, three shaded discs with antialiased rims and contact shadows."""
    y, x = np.mgrid[0:H, 0:W].astype(np.float64)
    img = np.zeros((H, W, 3))
    sky = 0.55 + 0.35 * (1 - y / H)
    img[..., 0], img[..., 1], img[..., 2] = sky * 0.55, sky * 0.7, sky
    floor = y > H * 0.62
    img[floor] = np.array([0.42, 0.40, 0.36]) * (0.8 + 0.2 * (y[floor] / H))[:, None]
    for cx, cy, r, col in [(50, 60, 22, (0.8, 0.3, 0.25)), (105, 55, 28, (0.3, 0.7, 0.35)),
                           (155, 66, 16, (0.35, 0.4, 0.85))]:
        # contact shadow on the floor: a soft ambient-occlusion-like darkening
        d = np.hypot((x - cx) / (1.6 * r), (y - (cy + r)) / (0.35 * r))
        img *= (1 - 0.45 * np.clip(1 - d, 0, 1) ** 2)[..., None]
        # the disc, lit from the upper left, with a one-pixel antialiased rim (4x4 supersampled)
        cover = np.zeros((H, W))
        for sy in range(4):
            for sx in range(4):
                cover += np.hypot(x + (sx + 0.5) / 4 - cx, y + (sy + 0.5) / 4 - cy) < r
        cover /= 16
        nz = np.sqrt(np.clip(1 - ((x - cx) ** 2 + (y - cy) ** 2) / r ** 2, 0, 1))
        shade = np.clip(0.25 + 0.75 * (0.5 * nz - 0.35 * (x - cx) / r - 0.35 * (y - cy) / r), 0, 1)
        disc = np.array(col)[None, None, :] * shade[..., None]
        img = img * (1 - cover[..., None]) + disc * cover[..., None]
    return np.clip(img, 0, 1)


def to8(img):
    return np.round(img * 255).astype(np.uint8)


def to16(img):
    return np.round(img * 65535).astype(np.uint16)


def save(arr, path, fmt="PNG", **kw):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if arr.dtype == np.uint16:
        # Pillow writes 16-bit RGB PNGs only through the raw encoder; a grey-free RGB image is
        # written as 16-bit by encoding rows big-endian.
        import struct, zlib
        raw = b"".join(b"\0" + arr[r].astype(">u2").tobytes() for r in range(arr.shape[0]))
        def chunk(t, d):
            return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
        png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 16, 2, 0, 0, 0))
        png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
        open(path, "wb").write(png)
        return
    Image.fromarray(arr, "RGB").save(path, fmt, **kw)


def main(out):
    base = scene()
    b8 = to8(base)
    reg, ben = os.path.join(out, "regressions"), os.path.join(out, "benign")

    def pair(folder, name, expected, actual, ext="png", fmt="PNG", ekw=None, akw=None):
        save(expected, os.path.join(folder, "expected", f"{name}.{ext}"), fmt, **(ekw or {}))
        save(actual, os.path.join(folder, "actual", f"{name}.{ext}"), fmt, **(akw or {}))

    # Regressions: one realistic defect each.
    pair(reg, "shift_1px", b8, to8(np.roll(base, 1, axis=1)))
    pair(reg, "brightness_2pct", b8, to8(np.clip(base * 1.02, 0, 1)))
    noise = np.clip(rng.normal(0, 0.01, base.shape), -4 / 255, 4 / 255)
    pair(reg, "noise_1pct", b8, to8(np.clip(base + noise, 0, 1)))
    patch = b8.copy()
    patch[40:46, 96:102] = np.clip(patch[40:46, 96:102].astype(int) + 42, 0, 255)
    pair(reg, "patch_6x6", b8, patch)
    blurred = np.asarray(Image.fromarray(b8, "RGB").filter(ImageFilter.BoxBlur(1)))
    pair(reg, "blur", b8, blurred)
    pair(reg, "channel_swap", b8, b8[..., ::-1].copy())
    pair(reg, "depth_16_to_8", to16(base), b8)

    # Benign: another encoder, every pixel kept; a driver's +-1 on a few pixels.
    pair(ben, "png_reencode", b8, b8, ekw={"compress_level": 9},
         akw={"compress_level": 1, "optimize": False})
    pair(ben, "webp_lossless", b8, b8, "webp", "WEBP", {"lossless": True, "method": 6},
         {"lossless": True, "method": 0})
    pair(ben, "tiff", b8, b8, "tiff", "TIFF", {"compression": "raw"},
         {"compression": "tiff_lzw"})
    jitter = b8.astype(int)
    picked = rng.choice(W * H, size=W * H // 200, replace=False)  # 0.5 % of the pixels
    ys, xs = np.unravel_index(picked, (H, W))
    jitter[ys, xs] += rng.choice([-1, 1], size=(len(picked), 3))
    pair(ben, "driver_noise", b8, np.clip(jitter, 0, 255).astype(np.uint8))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__)))
