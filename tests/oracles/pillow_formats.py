#!/usr/bin/env python3
"""aosuite reads JPEG, TIFF, WebP, BMP, Targa (and HDR) files to exactly their decoded pixels.

Generates images (smooth gradients with noise, odd sizes) in each format and kind Pillow writes,
decodes each with Pillow, and writes the decoded pixels as a PNG (8-bit, or 16-bit grey). Then,
through `aosuite compare --batch`:
  - every file against its decoded PNG: RMSE and largest error 0 (the same pixels);
  - Resemble.js on each pair of files equals Resemble.js on their decoded PNGs, key for key;
  - float TIFFs (which no PNG holds): RMSE between two files equals numpy's on Pillow's floats;
  - Radiance HDR (which Pillow neither reads nor writes): RMSE equals numpy's on RGBE decoded
    by hand;
and `aosuite check --actual --expected` on folders of such files gives each pair the mismatch
Resemble gives their decoded PNGs.
    tests/oracles/pillow_formats.py AOSUITE_BIN
Exit 77 (skipped) when Pillow or numpy is missing.
"""
import json
import pathlib
import subprocess
import sys
import tempfile

try:
    import numpy as np
    from PIL import Image
except ImportError:
    print("pillow_formats: Pillow or numpy is missing: skipped")
    sys.exit(77)


def image(rng, h, w, channels, peak):
    yy, xx = np.mgrid[0:h, 0:w]
    base = [(xx * (k + 1) / w + yy * (3 - k) / h) / 4 for k in range(channels)]
    arr = np.stack(base, axis=-1) * peak + rng.normal(0, peak / 20, (h, w, channels))
    return np.clip(arr, 0, peak)


def cases(rng, out):
    """(file, decoded PNG or None, kind) for every format and kind."""
    made = []
    sizes = [(17, 23), (32, 48), (5, 64), (40, 9)]
    for i, (h, w) in enumerate(sizes):
        rgb = image(rng, h, w, 3, 255).astype(np.uint8)
        grey = image(rng, h, w, 1, 255).astype(np.uint8)[:, :, 0]
        rgba = np.dstack([rgb, image(rng, h, w, 1, 255).astype(np.uint8)])
        writes = [
            (f"q{q}_{i}.jpg", Image.fromarray(rgb), {"quality": q}) for q in (40, 90, 100)
        ] + [
            (f"grey_{i}.jpg", Image.fromarray(grey, "L"), {"quality": 85}),
            (f"lossy_{i}.webp", Image.fromarray(rgb), {"quality": 80}),
            (f"lossless_{i}.webp", Image.fromarray(rgba, "RGBA"), {"lossless": True}),
            (f"rgb_{i}.tif", Image.fromarray(rgb), {}),
            (f"rgba_{i}.tif", Image.fromarray(rgba, "RGBA"), {"compression": "tiff_lzw"}),
            (f"grey_{i}.tif", Image.fromarray(grey, "L"), {}),
            (f"grey16_{i}.tif",
             Image.fromarray(image(rng, h, w, 1, 65535).astype(np.uint16)[:, :, 0], "I;16"), {}),
            (f"rgb_{i}.bmp", Image.fromarray(rgb), {}),
            # 32 bits, BI_RGB: Pillow writes the alpha into the reserved byte and reads it back
            # as RGB (BGRX).
            (f"bgrx_{i}.bmp", Image.fromarray(rgba, "RGBA"), {}),
            (f"rgba_{i}.tga", Image.fromarray(rgba, "RGBA"), {}),
            (f"rle_{i}.tga", Image.fromarray(rgb), {"compression": "tga_rle"}),
            (f"top_{i}.tga", Image.fromarray(grey, "L"), {"orientation": 1}),
            # GIF, through OpenImageIO: its first frame.
            (f"pal_{i}.gif", Image.fromarray(rgb).quantize(16), {}),
        ]
        for name, img, opts in writes:
            path = out / name
            img.save(path, **opts)
            decoded = Image.open(path)
            decoded.load()
            png = out / (name + ".png")
            if decoded.mode in ("I;16", "I"):
                Image.fromarray(np.asarray(decoded).astype(np.uint16), "I;16").save(png)
            else:
                decoded.convert("RGBA").save(png)
            made.append((path, png))
    return made


def rle_scanline(row):
    """One RGBE scanline in Radiance's new run-length encoding: 2, 2, the width, then each
    channel as runs (128 + n, value) of 3 to 127 equal bytes and literals (n, bytes) of up to
    128."""
    out = bytearray([2, 2, len(row) >> 8, len(row) & 255])
    for c in range(4):
        data, i = row[:, c].tolist(), 0
        while i < len(data):
            run = 1
            while i + run < len(data) and run < 127 and data[i + run] == data[i]:
                run += 1
            if run >= 3:
                out += bytes([128 + run, data[i]])
                i += run
                continue
            j = i
            while j < len(data) and j - i < 128 and not (
                    j + 2 < len(data) and data[j] == data[j + 1] == data[j + 2]):
                j += 1
            out += bytes([j - i]) + bytes(data[i:j])
            i = j
    return bytes(out)


def batch(binary, pairs, *options):
    lines = "".join(f"{a}\t{b}\n" for a, b in pairs)
    run = subprocess.run([binary, "compare", "--batch", "-", *options], input=lines,
                         capture_output=True, text=True, check=False)
    results = [json.loads(line) for line in run.stdout.splitlines()]
    if len(results) != len(pairs):
        sys.exit(f"compare --batch gave {len(results)} lines for {len(pairs)} pairs: {run.stderr}")
    return results


def main():
    binary = sys.argv[1]
    rng = np.random.default_rng(7)
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp)
        made = cases(rng, out)
        # 1. The same pixels as Pillow: RMSE 0 against the decoded PNG.
        for (path, png), r in zip(made, batch(binary, made, "--metric", "rmse")):
            rmse = r.get("rmse")
            if not rmse or rmse["max_abs"] != 0:
                failures.append(f"{path.name}: not Pillow's pixels: {r}")
        # 2. Resemble on files = Resemble on their decoded PNGs (each with the next of its kind).
        pairs = [(made[i][0], made[i + 1][0]) for i in range(0, len(made) - 1)
                 if made[i][0].suffix == made[i + 1][0].suffix]
        png_pairs = [(pathlib.Path(str(a) + ".png"), pathlib.Path(str(b) + ".png"))
                     for a, b in pairs]
        for (a, b), x, y in zip(pairs, batch(binary, pairs, "--mode", "nothing"),
                                batch(binary, png_pairs, "--mode", "nothing")):
            strip = lambda d: {k: v for k, v in d.items() if k not in ("a", "b", "analysisTime")}
            if strip(x) != strip(y):
                failures.append(f"Resemble {a.name} vs {b.name}: {x} != {y}")
        # 3. Float TIFF: RMSE of two files equals numpy's on Pillow's floats.
        floats = []
        for k in range(2):
            arr = image(rng, 21, 34, 1, 4.0).astype(np.float32)[:, :, 0]
            path = out / f"float_{k}.tif"
            Image.fromarray(arr, "F").save(path)
            floats.append((path, np.asarray(Image.open(path), dtype=np.float64)))
        want = float(np.sqrt(np.mean((floats[0][1] - floats[1][1]) ** 2)))
        got = batch(binary, [(floats[0][0], floats[1][0])], "--metric", "rmse")[0]["rmse"]["value"]
        if abs(got - want) > 1e-12 * max(1.0, want):
            failures.append(f"float TIFF RMSE {got} != numpy's {want}")
        # The same floats, compressed: the same samples, so the same image with no gate at all.
        Image.open(floats[0][0]).save(out / "float_lzw.tif", compression="tiff_lzw")
        run = subprocess.run([binary, "compare", str(floats[0][0]), str(out / "float_lzw.tif")],
                             capture_output=True, text=True, check=False)
        if run.returncode != 0:
            failures.append(f"float TIFF re-encoded with LZW: exit {run.returncode}, {run.stdout}")
        # 4. Radiance HDR (Pillow writes none): flat RGBE scanlines, decoded as Radiance's
        # rgbe.c does, m * 2^(e - 136).
        hdr = []
        for k in range(2):
            rgbe = rng.integers(0, 256, (4, 6, 4), dtype=np.uint8)
            rgbe[:, :, 3] = rng.integers(120, 140, (4, 6))
            path = out / f"sky_{k}.hdr"
            path.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 6\n" + rgbe.tobytes())
            scale = np.ldexp(1.0, rgbe[:, :, 3].astype(np.int64) - 136)[:, :, None]
            hdr.append((path, rgbe[:, :, :3] * scale))
        want = float(np.sqrt(np.mean((hdr[0][1] - hdr[1][1]) ** 2)))
        got = batch(binary, [(hdr[0][0], hdr[1][0])], "--metric", "rmse")[0]
        if abs(got.get("rmse", {}).get("value", -1) - want) > 1e-6 * max(1.0, want):
            failures.append(f"Radiance HDR RMSE {got} != {want}")
        # Wider scanlines, run-length encoded as rgbe.c writes them (runs and literals per
        # channel), are the same pixels as the flat file: RMSE 0 between them and numpy's RMSE
        # against another.
        rgbe = rng.integers(0, 256, (5, 40, 4), dtype=np.uint8)
        rgbe[:, :, 3] = rng.integers(120, 140, (5, 40))
        rgbe[:, 5:20, :] = rgbe[:, 5:6, :]  # runs to encode as runs
        rgbe[:, :, 0] = np.where(rgbe[:, :, 0] == 2, 3, rgbe[:, :, 0])  # no flat line looks RLE
        header = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 5 +X 40\n"
        (out / "wide_flat.hdr").write_bytes(header + rgbe.tobytes())
        (out / "wide_rle.hdr").write_bytes(header + b"".join(rle_scanline(r) for r in rgbe))
        scale = np.ldexp(1.0, rgbe[:, :, 3].astype(np.int64) - 136)[:, :, None]
        for other, values in ((out / "wide_flat.hdr", rgbe[:, :, :3] * scale),):
            got = batch(binary, [(out / "wide_rle.hdr", other)], "--metric", "rmse")[0]
            if got.get("rmse", {}).get("value", -1) != 0:
                failures.append(f"run-length encoded HDR differs from the flat one: {got}")
        (out / "wide_half.hdr").write_bytes(header + (rgbe // 2).tobytes())
        half = (rgbe // 2)
        half_values = half[:, :, :3] * np.ldexp(1.0, half[:, :, 3].astype(np.int64) - 136)[:, :, None]
        half_values[half[:, :, 3] == 0] = 0
        want = float(np.sqrt(np.mean((values - half_values) ** 2)))
        got = batch(binary, [(out / "wide_rle.hdr", out / "wide_half.hdr")], "--metric", "rmse")[0]
        if abs(got.get("rmse", {}).get("value", -1) - want) > 1e-6 * max(1.0, want):
            failures.append(f"run-length encoded HDR RMSE {got} != {want}")
        # 5. Folder mode: each JPEG pair's mismatch is Resemble's on the decoded PNGs.
        for side in ("actual", "expected", "actual_png", "expected_png"):
            (out / side).mkdir()
        jpegs = [p for p, _ in made if p.suffix == ".jpg"]
        for j, (a, b) in enumerate(zip(jpegs, jpegs[1:] + jpegs[:1])):
            for side, src in (("actual", a), ("expected", b)):
                (out / side / f"{j}.jpg").write_bytes(src.read_bytes())
                (out / f"{side}_png" / f"{j}.png").write_bytes(
                    pathlib.Path(str(src) + ".png").read_bytes())
        mismatch = {}
        for kind, ext in (("", "jpg"), ("_png", "png")):
            run = subprocess.run([binary, "check", "--actual", str(out / f"actual{kind}"),
                                  "--expected", str(out / f"expected{kind}"), "--json",
                                  "--max-mismatch", "100", "--report", str(out / f"r{kind}")],
                                 capture_output=True, text=True, check=False)
            for line in run.stdout.splitlines():
                c = json.loads(line)
                if c.get("type") == "case":
                    mismatch.setdefault(c["id"].split(".")[0], {})[ext] = [
                        v["mismatch_percent"] for v in c["images"]]
        for j, m in sorted(mismatch.items()):
            if m.get("jpg") != m.get("png") or not m.get("jpg"):
                failures.append(f"folder mode {j}.jpg: {m}")
        # Folder mode pairs what compare reads: GIFs too.
        for side in ("gif_a", "gif_e"):
            (out / side).mkdir()
            for p, _ in made:
                if p.suffix == ".gif":
                    (out / side / p.name).write_bytes(p.read_bytes())
        run = subprocess.run([binary, "check", "--actual", str(out / "gif_a"), "--expected",
                              str(out / "gif_e"), "--report", str(out / "r_gif")],
                             capture_output=True, text=True, check=False)
        if run.returncode != 0 or "4 images: 4 unchanged" not in run.stdout:
            failures.append(f"folder mode on GIFs: exit {run.returncode}, {run.stdout[-300:]}")
        # 6. A file that is no image, or a cut JPEG: one line naming it, what is wrong and the
        # formats aosuite reads; exit 2.
        (out / "notes.jpg").write_text("not a JPEG")
        (out / "cut.jpg").write_bytes(made[0][0].read_bytes()[:200])
        # Cut inside the scan data, where libjpeg pads with grey and only warns, and Pillow
        # refuses it ("image file is truncated"); the CMYK one is OpenImageIO's to decode.
        whole = made[0][0].read_bytes()
        (out / "half.jpg").write_bytes(whole[:len(whole) // 2])
        cmyk = np.dstack([image(rng, 40, 50, 3, 255), image(rng, 40, 50, 1, 255)])
        Image.fromarray(cmyk.astype(np.uint8), "CMYK").save(out / "cmyk.jpg", quality=90)
        whole = (out / "cmyk.jpg").read_bytes()
        (out / "half_cmyk.jpg").write_bytes(whole[:len(whole) // 2])
        for bad, said in (("notes.jpg", "not an image: no signature"), ("cut.jpg", "JPEG"),
                          ("half.jpg", "Premature end of JPEG file"),
                          ("half_cmyk.jpg", "Premature end of JPEG file")):
            run = subprocess.run([binary, "compare", str(out / bad), str(made[0][0])],
                                 capture_output=True, text=True, check=False)
            if run.returncode != 2 or run.stderr.count("\n") != 1 \
                    or f"{bad}: " not in run.stderr or said not in run.stderr \
                    or "aosuite reads PNG, EXR, JPEG, TIFF" not in run.stderr:
                failures.append(f"{bad}: exit {run.returncode}, {run.stderr!r}")
        # 7. Each decoder library is loaded for its formats only: a PNG comparison maps neither,
        # a JPEG, WebP, TIFF, Targa or BMP one libaosuite_codecs.so alone, with no OpenImageIO
        # and so no OpenCV (Debian's OpenImageIO links it); a colour-mapped Targa, which the
        # codecs library leaves to it, OpenImageIO.
        png_a, png_b = made[0][1], made[1][1]
        first = {suffix: next(f for f, _ in made if f.suffix == suffix)
                 for suffix in (".jpg", ".webp", ".tif", ".tga", ".bmp")}
        mapped = out / "palette.tga"
        Image.fromarray(np.asarray(Image.open(made[0][1]))[:, :, :3]).quantize(16).save(mapped)
        expected = [((png_a, png_b), False, False), ((mapped, png_b), True, True)] + [
            ((first[s], png_b), True, False) for s in first]
        for pair, codecs, oiio in expected:
            run = subprocess.run([binary, "compare", str(pair[0]), str(pair[1])],
                                 env={"LD_DEBUG": "files", "PATH": "/usr/bin:/bin"},
                                 capture_output=True, text=True, check=False)
            seen = ("libaosuite_codecs.so" in run.stderr,
                    "libaosuite_oiio.so" in run.stderr and "libOpenImageIO" in run.stderr,
                    "libopencv" in run.stderr)
            if seen != (codecs, oiio, oiio):
                failures.append(f"compare {pair[0].name} {pair[1].name}: loaded (codecs, "
                                f"OpenImageIO, OpenCV) {seen}, expected {(codecs, oiio, oiio)}")
        print(f"pillow_formats: {len(made)} files, {len(pairs)} Resemble pairs, "
              f"{len(mismatch)} folder-mode pairs, a float TIFF and an HDR pair; "
              f"{len(failures)} failures")
    for f in failures:
        print(f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
