#!/usr/bin/env python3
"""Checks that the library's includes point one way: a folder of OpenMeshSkinned/ includes only itself and
the folders below it (LAYERS, lowest first), and no two units (X.hh with its X.cc) include each other,
directly or around a cycle.

    check_layers.py REPO_ROOT

It also checks that README.md's layout table has one row per folder of OpenMeshSkinned/, lowest layer first.
"""
import os
import re
import sys

# Lowest first. A folder may include the folders of earlier rows; folders on one row do not include each other.
LAYERS = [
    ["Platform", "Skin"],
    ["Mesh"],
    ["Eval", "Deform"],
    ["Collapse"],
    ["Solver"],
    ["Decimater", "IO"],
    ["Lod"],
]
INCLUDE = re.compile(r'\s*#\s*include\s*[<"]([^>"]+)[>"]')


def library_includes(root):
    """Yields (file, included file), both relative to root, for every include of a library file."""
    lib = os.path.join(root, "OpenMeshSkinned")
    for folder, _, names in os.walk(lib):
        for name in sorted(names):
            if not name.endswith((".hh", ".cc")):
                continue
            path = os.path.join(folder, name)
            rel = os.path.relpath(path, root)
            with open(path, encoding="utf-8", errors="replace") as f:
                for line in f:
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    target = m.group(1)
                    if target.startswith("OpenMeshSkinned/"):
                        yield rel, target
                    elif os.path.exists(os.path.join(folder, target)):
                        yield rel, os.path.relpath(os.path.join(folder, target), root)


def folder_of(rel):
    return rel.split("/")[1]


def readme_layout_problems(root, folders, rank):
    rows = []
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        for line in f:
            m = re.match(r"\|\s*`OpenMeshSkinned/([A-Za-z]+)/?`\s*\|", line)
            if m:
                rows.append(m.group(1))
    problems = []
    for d in folders:
        if d not in rows:
            problems.append(f"README.md's layout table has no row for OpenMeshSkinned/{d}")
    for d in rows:
        if d not in folders:
            problems.append(f"README.md's layout table names OpenMeshSkinned/{d}, which does not exist")
    ranks = [rank.get(d, -1) for d in rows]
    if ranks != sorted(ranks):
        problems.append("README.md's layout table is not in layer order (lowest first): " + ", ".join(rows))
    return problems


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    rank = {name: i for i, row in enumerate(LAYERS) for name in row}
    problems = []
    folders = sorted(d for d in os.listdir(os.path.join(root, "OpenMeshSkinned"))
                     if os.path.isdir(os.path.join(root, "OpenMeshSkinned", d)))
    for d in folders:
        if d not in rank:
            problems.append(f"OpenMeshSkinned/{d}/ is in no layer of tests/layers/check_layers.py")
    graph = {}
    for src, dst in library_includes(root):
        unit_src, unit_dst = os.path.splitext(src)[0], os.path.splitext(dst)[0]
        if unit_src != unit_dst:
            graph.setdefault(unit_src, set()).add(unit_dst)
        a, b = folder_of(src), folder_of(dst)
        if a == b or a not in rank or b not in rank:
            continue
        if rank[b] >= rank[a]:
            problems.append(f"{src} includes {dst}: {b}/ is not below {a}/")
    # Unit-level cycles (depth-first search, colours: 1 on the stack, 2 done).
    colour = {}

    def visit(node, stack):
        colour[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if colour.get(nxt) == 1:
                problems.append("include cycle: " + " -> ".join(stack[stack.index(nxt):] + [nxt]))
            elif nxt not in colour:
                visit(nxt, stack)
        stack.pop()
        colour[node] = 2

    for node in sorted(graph):
        if node not in colour:
            visit(node, [])
    problems += readme_layout_problems(root, folders, rank)
    for p in problems:
        print("check_layers: " + p, file=sys.stderr)
    if problems:
        return 1
    print(f"check_layers: {len(graph)} units, {sum(len(v) for v in graph.values())} includes, one direction")
    return 0


if __name__ == "__main__":
    sys.exit(main())
