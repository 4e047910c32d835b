#!/usr/bin/env python3
"""scripts/stl_to_ply.js, which turns the CAD parts' STL files into the PLY the scenes load
(scripts/fetch_assets.sh), on STL files made here: a cube, ASCII and binary, with a sliver and
with stored normals that are wrong. Both give the same PLY: the cube's 12 triangles with three
vertices each and each triangle's own outward normal at its corners, the sliver left out. Bad
input is one line, exit 1, no output. Needs node (Debian's nodejs); skips (exit 77) without it.

  python3 tests/stl_to_ply_test.py SOURCE_DIR
"""
import base64
import os
import shutil
import struct
import subprocess
import sys
import tempfile

SKIP = 77
CUBE = [  # outward winding, two triangles a face
    ((0, 0, 0), (0, 1, 0), (1, 1, 0)), ((0, 0, 0), (1, 1, 0), (1, 0, 0)),  # z = 0, normal -z
    ((0, 0, 1), (1, 0, 1), (1, 1, 1)), ((0, 0, 1), (1, 1, 1), (0, 1, 1)),  # z = 1, +z
    ((0, 0, 0), (1, 0, 0), (1, 0, 1)), ((0, 0, 0), (1, 0, 1), (0, 0, 1)),  # y = 0, -y
    ((0, 1, 0), (0, 1, 1), (1, 1, 1)), ((0, 1, 0), (1, 1, 1), (1, 1, 0)),  # y = 1, +y
    ((0, 0, 0), (0, 0, 1), (0, 1, 1)), ((0, 0, 0), (0, 1, 1), (0, 1, 0)),  # x = 0, -x
    ((1, 0, 0), (1, 1, 0), (1, 1, 1)), ((1, 0, 0), (1, 1, 1), (1, 0, 1)),  # x = 1, +x
]
SLIVER = ((0, 0, 0), (1, 0, 0), (2, 1e-6, 0))  # its smallest angle's sine is 5e-7


def ascii_stl(triangles, coordinate=repr):
    lines = ["solid cube"]
    for t in triangles:
        lines += ["facet normal 0 0 0", " outer loop"]
        lines += ["  vertex " + " ".join(coordinate(c) for c in p) for p in t]
        lines += [" endloop", "endfacet"]
    return ("\n".join(lines + ["endsolid cube"]) + "\n").encode()


def binary_stl(triangles):
    out = b"binary cube".ljust(80, b" ") + struct.pack("<I", len(triangles))
    for t in triangles:  # a stored normal of (7, 7, 7): the converter must not use it
        out += struct.pack("<12fH", 7, 7, 7, *[c for p in t for c in p], 0)
    return out


def convert(node, script, stl, out):
    return subprocess.run([node, script, stl, out, "test"], capture_output=True, text=True)


def read_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    assert header[:2] == ["ply", "format binary_little_endian 1.0"], header
    nv = int(next(l for l in header if l.startswith("element vertex")).split()[2])
    nf = int(next(l for l in header if l.startswith("element face")).split()[2])
    assert [l for l in header if l.startswith("property float")] == [
        "property float " + k for k in ("x", "y", "z", "nx", "ny", "nz")], header
    vertices = [struct.unpack_from("<6f", data, end + 24 * i) for i in range(nv)]
    faces = [struct.unpack_from("<B3i", data, end + 24 * nv + 13 * i) for i in range(nf)]
    assert len(data) == end + 24 * nv + 13 * nf, "trailing or missing bytes"
    return data[end:], vertices, faces


def main():
    source = sys.argv[1]
    node = shutil.which("node")
    if not node:
        print("skipped: no node (Debian's nodejs) on PATH")
        return SKIP
    script = os.path.join(source, "scripts", "stl_to_ply.js")
    with tempfile.TemporaryDirectory() as tmp:
        bodies = []
        for name, stl in (("a.stl", ascii_stl(CUBE + [SLIVER])), ("b.stl", binary_stl(CUBE + [SLIVER]))):
            path = os.path.join(tmp, name)
            open(path, "wb").write(stl)
            r = convert(node, script, path, path + ".ply")
            assert r.returncode == 0, r.stderr
            body, vertices, faces = read_ply(path + ".ply")
            bodies.append(body)
            assert len(faces) == 12 and len(vertices) == 36, (name, len(faces), len(vertices))
            for k, (count, *idx) in enumerate(faces):
                assert count == 3 and idx == [3 * k, 3 * k + 1, 3 * k + 2], (name, k, idx)
                corners = [vertices[i] for i in idx]
                assert [c[:3] for c in corners] == [tuple(map(float, p)) for p in CUBE[k]], (name, k)
                normal = corners[0][3:]
                assert all(c[3:] == normal for c in corners), (name, k, "one normal a triangle")
                axis = [i for i in range(3) if normal[i] != 0]
                assert len(axis) == 1 and abs(normal[axis[0]]) == 1, (name, k, normal)
                # Outward: on the face the triangle lies on, pointing away from the cube's centre.
                a = axis[0]
                assert corners[0][a] == (1 if normal[a] > 0 else 0), (name, k, normal)
        assert bodies[0] == bodies[1], "ASCII and binary STL of the same triangles differ"

        bad = {
            "truncated.stl": binary_stl(CUBE)[:-10],
            "nan.stl": ascii_stl(CUBE, coordinate=lambda c: "nan"),
            "slivers.stl": ascii_stl([SLIVER]),
            "empty.stl": b"",
        }
        for name, stl in bad.items():
            path = os.path.join(tmp, name)
            open(path, "wb").write(stl)
            r = convert(node, script, path, path + ".ply")
            assert r.returncode == 1, (name, r.returncode, r.stderr)
            assert r.stderr.count("\n") == 1 and path in r.stderr, (name, r.stderr)
            assert not os.path.exists(path + ".ply"), (name, "wrote output")
        # module_to_ply.js, the npm mesh modules' converter, through the same PLY writer: a
        # module of JSON lines and one of base64 triples (the snowden form) give the same PLY.
        module = os.path.join(source, "scripts", "module_to_ply.js")
        positions, cells = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2], [0, 3, 1]]
        b64 = lambda fmt, rows: base64.b64encode(b"".join(struct.pack(fmt, *r) for r in rows)).decode()
        forms = {
            "lines.js": "exports.positions=%s;\nexports.cells=%s;\n" % (positions, cells),
            "packed.js": ';exports.positions = require("./load")(Float32Array, "%s");exports.cells = '
                         'require("./load")(Uint32Array, "%s");' % (b64("<3f", positions), b64("<3I", cells)),
        }
        plys = []
        for name, text in forms.items():
            path = os.path.join(tmp, name)
            open(path, "w").write(text)
            r = convert(node, module, path, path + ".ply")
            assert r.returncode == 0, r.stderr
            data = open(path + ".ply", "rb").read()
            end = data.index(b"end_header\n") + len(b"end_header\n")
            assert b"element vertex 4\n" in data[:end] and b"property float nx" not in data[:end], name
            assert data[end:] == b"".join(struct.pack("<3f", *p) for p in positions) + b"".join(
                struct.pack("<B3i", 3, *c) for c in cells), (name, "vertices then faces")
            plys.append(data)
        assert plys[0] == plys[1], "the two module forms differ"
        for name, text in {"out_of_range.js": "exports.positions=[[0,0,0]];\nexports.cells=[[0,1,2]];\n",
                           "code.js": "module.exports = require('fs');\n"}.items():
            path = os.path.join(tmp, name)
            open(path, "w").write(text)
            r = convert(node, module, path, path + ".ply")
            assert r.returncode == 1 and r.stderr.count("\n") == 1 and path in r.stderr, (name, r.stderr)
            assert not os.path.exists(path + ".ply"), (name, "wrote output")
    print("stl_to_ply, module_to_ply: the forms agree; bad input refused")
    return 0


if __name__ == "__main__":
    sys.exit(main())
