#!/usr/bin/env python3
"""Checks the architecture: every project #include stays inside what its CMake target links, and the
folders form no cycle.

    python3 tools/check_layers.py [BUILD_DIR]

1. Link closure: `cmake --graphviz` writes the target graph of BUILD_DIR's configuration (re-configured in
   place; without BUILD_DIR a temporary folder is configured and removed); a file of a
   folder may include a header of another folder only if the folder's target links that folder's target
   (directly or through others).
2. Folder graph: the folders (solver's sub-folders counted separately, material/io apart from material)
   with an edge A -> B when a file in A includes a header in B; any cycle is reported.
Exit 0 when both hold, 1 with one line per violation otherwise.
"""
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')

# Folder (relative to the root) -> the CMake target its sources are compiled into.
TARGETS = {
    "io": "cushion_io",
    "material": "cushion_material",
    "material/io": "cushion_material_io",
    "mesh": "cushion_mesh",
    "solver": "cushion_solver",
    "calibration": "cushion_calibration",
    "tools": "cushion",
}


def folder_of(path):
    """Folder node of a path relative to the root: solver/<sub> kept, tests/<sub> kept, else top level."""
    parts = path.split("/")
    if parts[0] in ("solver", "tests", "material") and len(parts) > 2:
        return parts[0] + "/" + parts[1]
    return parts[0]


def target_of(folder):
    if folder.startswith("solver"):
        return "cushion_solver"
    if folder.startswith("tests/"):
        return "test_" + folder.split("/")[1]
    return TARGETS.get(folder)


def link_closure(build_dir):
    """target -> set of targets it links (transitively), from CMake's graphviz output."""
    with tempfile.TemporaryDirectory() as tmp:
        dot = os.path.join(tmp, "deps.dot")
        subprocess.run(["cmake", "-S", ROOT, "-B", build_dir or os.path.join(tmp, "build"), f"--graphviz={dot}"],
                       check=True, stdout=subprocess.DEVNULL)
        text = open(dot).read()
    names = dict(re.findall(r'"(node\d+)"\s*\[\s*label\s*=\s*"([^"]+)"', text))
    edges = {}
    for a, b in re.findall(r'"(node\d+)"\s*->\s*"(node\d+)"', text):
        edges.setdefault(names[a], set()).add(names[b])
    closure = {}
    for t in names.values():
        seen, stack = set(), [t]
        while stack:
            for n in edges.get(stack.pop(), ()):
                if n not in seen:
                    seen.add(n)
                    stack.append(n)
        closure[t] = seen
    return closure


def project_includes():
    """(file, line number, folder of the file, included header) for every quoted project include."""
    for base in ("io", "material", "mesh", "solver", "calibration", "tools", "tests"):
        for dirpath, _, files in os.walk(os.path.join(ROOT, base)):
            for name in files:
                if not name.endswith((".cpp", ".hpp", ".h")):
                    continue
                full = os.path.join(dirpath, name)
                rel = os.path.relpath(full, ROOT)
                for number, line in enumerate(open(full, encoding="utf-8", errors="replace"), 1):
                    m = INCLUDE.match(line)
                    if m and os.path.exists(os.path.join(ROOT, m.group(1))):
                        yield rel, number, folder_of(os.path.dirname(rel) + "/x"), m.group(1)


def find_cycles(graph):
    """Strongly connected components with more than one folder (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in list(graph):
        if v not in index:
            visit(v)
    return out


def main():
    build_dir = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else None
    closure = link_closure(build_dir)
    problems, graph = [], {}
    for rel, number, folder, header in project_includes():
        to = folder_of(header)
        if to != folder and not folder.startswith("tests"):
            graph.setdefault(folder, set()).add(to)
        source_target, header_target = target_of(folder), target_of(to)
        if source_target is None or header_target is None or source_target == header_target:
            continue
        if source_target in closure and header_target not in closure[source_target]:
            problems.append(f"{rel}:{number}: includes {header} ({header_target}), "
                            f"but {source_target} does not link it")
    for comp in find_cycles(graph):
        problems.append("folder cycle: " + " <-> ".join(comp) + " (edges: " + "; ".join(
            f"{a} -> {b}" for a in comp for b in sorted(graph.get(a, ())) if b in comp) + ")")
    for p in problems:
        print(p)
    edges = sum(len(v) for v in graph.values())
    print(f"check_layers: {len(graph)} folders, {edges} folder edges, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
