#!/usr/bin/env python3
"""Checks the layering of include/sylva (ctest layers:include_graph).

Folders are layers: a header may include headers of its own folder and of the folders it
builds on, never of a folder that builds on it. Two rules, read from the #include lines:

  1. The folder graph has no cycle: no two folders include each other, directly or through
     a third (a folder and its own `detail/` subfolder count as one).
  2. The generic filter stays generic: `filter/` (and `core/`, `detail/`, `diff/`, `noise/`)
     include nothing from the models (`motion/`, `landmarks/`, `measurements/`), from the
     sensor front ends (`laser_camera/`, `laser/`), from the parking controller (`parking/`) or
     from the SLAM layer (`slam/`).

An include of a header that does not exist is an error as well.

    python3 scripts/check_layers.py            exit 1 and a list of the offending includes
    python3 scripts/check_layers.py --graph    prints the folder graph
    python3 scripts/check_layers.py --root DIR checks DIR/include instead of this repository's
    python3 scripts/check_layers.py selftest   shows that both rules catch a violation
"""

import os
import re
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*[<"](sylva/[^">]+)[">]', re.M)

GENERIC = ["core", "detail", "diff", "noise", "filter"]
SPECIFIC = ["motion", "landmarks", "measurements", "laser_camera", "laser", "parking", "slam"]


def folder_of(rel):
    """'sylva/association/detail/x.hpp' -> 'association'; 'sylva/sylva.hpp' -> '' (umbrellas)."""
    parts = rel.split("/")[1:-1]
    return parts[0] if parts else ""


def include_edges(include_dir):
    """[(header, included header)] for every sylva header under include_dir."""
    edges = []
    base = os.path.join(include_dir, "sylva")
    for dirpath, _, files in os.walk(base):
        for name in files:
            if not name.endswith(".hpp"):
                continue
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, include_dir)
            with open(path, encoding="utf-8") as f:
                text = f.read()
            for target in INCLUDE_RE.findall(text):
                edges.append((rel, target))
    return sorted(edges)


def check(include_dir):
    errors = []
    edges = include_edges(include_dir)
    graph = {}
    for src, dst in edges:
        if not os.path.exists(os.path.join(include_dir, dst)):
            errors.append(f"{src}: includes {dst}, which does not exist")
            continue
        a, b = folder_of(src), folder_of(dst)
        if not a or not b or a == b:
            continue  # umbrellas may include anything; a folder may include itself
        graph.setdefault(a, {}).setdefault(b, []).append(f"{src} -> {dst}")
        if a in GENERIC and b in SPECIFIC:
            errors.append(f"{src}: the generic layer '{a}/' includes the specific '{b}/' ({dst})")
    # Cycles between folders: a depth-first search that reports each back edge with its path.
    state, stack = {}, []

    def visit(node):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph.get(node, {})):
            if state.get(nxt) == "open":
                cycle = stack[stack.index(nxt):] + [nxt]
                witness = "; ".join(graph[a][b][0] for a, b in zip(cycle, cycle[1:]))
                errors.append(f"folders include each other: {' -> '.join(cycle)} ({witness})")
            elif nxt not in state:
                visit(nxt)
        stack.pop()
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node)
    return errors, graph


def selftest():
    """Both rules must catch a planted violation in a copy of a tiny tree."""
    with tempfile.TemporaryDirectory() as tmp:
        def write(rel, *includes):
            path = os.path.join(tmp, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as f:
                f.write("#pragma once\n" + "".join(f'#include "{i}"\n' for i in includes))
        write("sylva/core/a.hpp")
        write("sylva/filter/ekf.hpp", "sylva/core/a.hpp")
        write("sylva/measurements/m.hpp", "sylva/core/a.hpp")
        ok, _ = check(tmp)
        if ok:
            print("selftest: a clean tree was reported:", ok)
            return 1
        write("sylva/filter/ekf.hpp", "sylva/core/a.hpp", "sylva/measurements/m.hpp")
        generic, _ = check(tmp)
        write("sylva/filter/ekf.hpp", "sylva/core/a.hpp")
        write("sylva/core/a.hpp", "sylva/measurements/m.hpp")
        cycle, _ = check(tmp)
        write("sylva/core/a.hpp", "sylva/core/missing.hpp")
        missing, _ = check(tmp)
    caught = [any("generic layer" in e for e in generic), any("include each other" in e for e in cycle),
              any("does not exist" in e for e in missing)]
    print(f"selftest: generic-includes-specific caught: {caught[0]}, folder cycle caught: {caught[1]}, "
          f"missing header caught: {caught[2]}")
    return 0 if all(caught) else 1


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "selftest":
        return selftest()
    root = sys.argv[sys.argv.index("--root") + 1] if "--root" in sys.argv else ROOT
    errors, graph = check(os.path.join(root, "include"))
    if "--graph" in sys.argv:
        for a in sorted(graph):
            print(f"{a}/ -> {', '.join(sorted(b + '/' for b in graph[a]))}")
    for e in errors:
        print("check_layers:", e)
    if errors:
        return 1
    print(f"check_layers: {len(graph)} folders, no cycle, the generic layer includes nothing specific")
    return 0


if __name__ == "__main__":
    sys.exit(main())
