#!/usr/bin/env python3
"""Checks that the folders of src/raytrace include each other one way only (issue 36: "no
include runs back up"): from the `#include "raytrace/<folder>/..."` lines, the folders' include
graph must have no cycle. Prints each folder's includes; exits 1 naming a cycle."""
import os
import re
import sys

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src", "raytrace")
edges = {}
for folder, _, files in os.walk(root):
    rel = os.path.relpath(folder, root).split(os.sep)[0]
    if rel == ".":
        continue
    for name in files:
        if not name.endswith((".h", ".cpp")):
            continue
        with open(os.path.join(folder, name), encoding="utf-8") as f:
            for m in re.finditer(r'#include "raytrace/(\w+)/', f.read()):
                if m.group(1) != rel:
                    edges.setdefault(rel, set()).add(m.group(1))

for folder in sorted(edges):
    print(f"{folder} -> {', '.join(sorted(edges[folder]))}")


def cycle_from(start):
    # Depth-first search for a path back to `start`.
    stack = [(start, [start])]
    seen = set()
    while stack:
        node, path = stack.pop()
        for nxt in edges.get(node, ()):
            if nxt == start:
                return path + [start]
            if nxt not in seen:
                seen.add(nxt)
                stack.append((nxt, path + [nxt]))
    return None


for folder in sorted(edges):
    cycle = cycle_from(folder)
    if cycle:
        print("include cycle: " + " -> ".join(cycle), file=sys.stderr)
        sys.exit(1)
print("no include cycle between the folders of src/raytrace")
