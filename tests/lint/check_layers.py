#!/usr/bin/env python3
"""Fails when an include points the wrong way.

1. Layers: each folder may include itself and the folders LAYERS gives it, never one above
   (data flows one way). The renderer stands on common alone: it makes images, it never
   compares them.
2. Units: a header and its source file (x.hpp, x.cpp) are one unit. No unit may include a
   unit that includes it back, directly or through others (inside a folder as across them).
    tests/lint/check_layers.py SOURCE_DIR
"""
import pathlib
import re
import sys

# Each layer and what it may include besides itself, lowest first.
LAYERS = {
    "common": set(),
    # Pictures in memory and every format: PNG, EXR, the rest through OpenImageIO.
    "image": {"common"},
    "compare": {"common", "image"},
    "renderer": {"common"},
    "reference": {"common", "image", "compare", "renderer"},
    # The image-regression tool: suites, goldens, reports. Other kinds of case (the AO bench's
    # rendered scenes) register themselves from above (harness/case_kind.hpp).
    "harness": {"common", "image", "compare"},
    # The AO bench on top of the tool: rendered cases, its report section.
    "ao": {"common", "image", "compare", "renderer", "reference", "harness"},
    # The C++ library (include/aosuite/aosuite.hpp): the harness's verdict for a renderer's tests.
    "api": {"common", "image", "compare", "harness"},
    "cli": {"common", "image", "compare", "renderer", "reference", "harness", "ao"},
}
INCLUDE = re.compile(r'#include "([\w/]+)\.[ch]pp"')


def includes(root):
    """{unit: {included unit: (file, line)}}, a unit being 'folder/.../stem'."""
    graph = {}
    for layer in LAYERS:
        for f in sorted((root / layer).rglob("*.[ch]pp")):
            unit = str(f.relative_to(root).with_suffix(""))
            edges = graph.setdefault(unit, {})
            for n, line in enumerate(f.read_text(errors="replace").splitlines(), 1):
                m = INCLUDE.match(line)
                if m and m.group(1) != unit:
                    edges.setdefault(m.group(1), (f.relative_to(root), n))
    return graph


def cycles(graph):
    """Strongly connected components of more than one unit (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v), on.add(v)
        for w in graph.get(v, {}):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            scc = []
            while True:
                w = stack.pop()
                on.discard(w)
                scc.append(w)
                if w == v:
                    break
            if len(scc) > 1:
                out.append(sorted(scc))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    graph = includes(root)
    bad = []
    for unit, edges in sorted(graph.items()):
        layer = unit.split("/")[0]
        for target, (f, n) in edges.items():
            top = target.split("/")[0]
            if top in LAYERS and top != layer and top not in LAYERS[layer]:
                bad.append(f"{f}:{n}: {layer}/ includes {top}/")
    for scc in cycles(graph):
        links = [f"{graph[a][b][0]}:{graph[a][b][1]}: {a} -> {b}"
                 for a in scc for b in graph[a] if b in scc]
        bad.append("include cycle between " + ", ".join(scc) + "\n    " + "\n    ".join(links))
    for b in bad:
        print(b)
    print(f"{len(bad)} wrong-way includes")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
