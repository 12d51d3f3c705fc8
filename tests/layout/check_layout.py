#!/usr/bin/env python3
"""The folder layout tells the story (harness/README.md): foundations, then
the stages config → plan → run → measure → record → report. This check reads
every #include "folder/..." of the project and fails when
  - folders include each other in a cycle,
  - a folder includes one that harness/README.md ranks after it,
  - a technique includes anything beyond its own folder and the installed
    API: the plugin API (core, gl, plugin) and the shadow-map kit (common),
    which is installed too, so that a technique built elsewhere has all a
    built-in has (two built-in families share a helper library with another:
    those two edges are named below, and no other may appear),
  - the kit includes anything beyond the plugin API (its headers are
    installed: they may name nothing that is not),
  - a harness folder is missing from harness/README.md's table."""
import collections
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([A-Za-z0-9_]+)/', re.M)
PLUGIN_API = {"core", "gl", "plugin"}
# shadowbench::shadow_kit, techniques/common/, installed as include/shadowbench/common/.
SHADOW_KIT = "common"
# Built-in families that use another family's helper library (not installed).
SHARED_BETWEEN_FAMILIES = {("penumbra_wedge", "shadow_volume"), ("planar", "accumulation")}


def folder_of(root, path):
    rel = os.path.relpath(path, root).split(os.sep)
    if rel[0] == "harness":
        return rel[1]
    return rel[0]  # scenes, techniques


def sources(root, top):
    for base, _, files in os.walk(os.path.join(root, top)):
        for f in files:
            if f.endswith((".h", ".cpp")):
                yield os.path.join(base, f)


def readme_ranks(root):
    """Folder → rank, from the table rows `| rank | `folder` | ... |`."""
    ranks = {}
    with open(os.path.join(root, "harness", "README.md")) as f:
        for m in re.finditer(r"^\|\s*(\d+)\s*\|\s*`([a-z_]+)/`", f.read(), re.M):
            ranks[m.group(2)] = int(m.group(1))
    return ranks


def check_technique_include(root, path, dst):
    """An include of folder `dst`/ in techniques/<src>/...: the installed API
    only. Folders of neither the project nor the techniques are not ours."""
    where = os.path.relpath(path, root)
    src = where.split(os.sep)[1]
    if dst == src or not any(os.path.isdir(os.path.join(root, *parts)) for parts in
                             (("harness", dst), ("techniques", dst), (dst,))):
        return
    if src == SHADOW_KIT:
        if dst not in PLUGIN_API:
            sys.exit(f"{where} includes {dst}/: the shadow-map kit's headers are installed, "
                     f"so it may use the plugin API only ({', '.join(sorted(PLUGIN_API))})")
        return
    if dst in PLUGIN_API or dst == SHADOW_KIT or (src, dst) in SHARED_BETWEEN_FAMILIES:
        return
    sys.exit(f"{where} includes {dst}/: techniques may use the installed API only "
             f"({', '.join(sorted(PLUGIN_API | {SHADOW_KIT}))}), as a technique built "
             f"elsewhere must")


def main():
    root = sys.argv[1]
    graph = collections.defaultdict(set)
    where = {}
    for top in ("harness", "scenes", "techniques"):
        for path in sources(root, top):
            src = folder_of(root, path)
            with open(path, encoding="utf-8") as f:
                text = f.read()
            for dst in INCLUDE.findall(text):
                if top == "techniques":
                    check_technique_include(root, path, dst)
                if dst == src or not (os.path.isdir(os.path.join(root, "harness", dst)) or
                                      os.path.isdir(os.path.join(root, dst))):
                    continue
                graph[src].add(dst)
                where.setdefault((src, dst), os.path.relpath(path, root))

    # Cycles, by depth-first search.
    state = {}

    def visit(n, stack):
        state[n] = "open"
        for m in sorted(graph[n]):
            if state.get(m) == "open":
                cycle = stack[stack.index(m):] + [m] if m in stack else [n, m]
                sys.exit("folders include each other in a cycle: " + " -> ".join(cycle) +
                         f" (e.g. {where.get((n, m))})")
            if m not in state:
                visit(m, stack + [m])
        state[n] = "done"

    for n in sorted(graph):
        if n not in state:
            visit(n, [n])

    ranks = readme_ranks(root)
    folders = sorted(d for d in os.listdir(os.path.join(root, "harness"))
                     if os.path.isdir(os.path.join(root, "harness", d)))
    missing = [d for d in folders if d not in ranks]
    if missing:
        sys.exit(f"harness/README.md does not place {', '.join(missing)} in its table")
    for src, dsts in sorted(graph.items()):
        for dst in sorted(dsts):
            if src in ranks and dst in ranks and ranks[dst] > ranks[src]:
                sys.exit(f"{where[(src, dst)]}: {src}/ (rank {ranks[src]}) includes {dst}/ "
                         f"(rank {ranks[dst]}), which harness/README.md puts after it")
    for src in sorted(graph):
        print(f"{src} -> {' '.join(sorted(graph[src]))}")


if __name__ == "__main__":
    main()
