#!/usr/bin/env python3
"""Fails when a lower layer includes a higher one.

The layers, lowest first: common, compare, renderer, reference, harness, cli. A file may
include its own layer and those below it, never one above (data flows one way).
    tests/lint/check_layers.py SOURCE_DIR
"""
import pathlib
import re
import sys

LAYERS = ["common", "compare", "renderer", "reference", "harness", "cli"]


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    bad = []
    for layer in LAYERS:
        for f in sorted((root / layer).rglob("*.[ch]pp")):
            for n, line in enumerate(f.read_text(errors="replace").splitlines(), 1):
                m = re.match(r'#include "(\w+)/', line)
                if m and m.group(1) in LAYERS and LAYERS.index(m.group(1)) > LAYERS.index(layer):
                    bad.append(f"{f.relative_to(root)}:{n}: {layer}/ includes {m.group(1)}/")
    for b in bad:
        print(b)
    print(f"{len(bad)} upward includes")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
