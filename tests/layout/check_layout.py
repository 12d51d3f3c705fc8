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
  - a harness folder is missing from harness/README.md's table,
  - a harness header declares its names outside its folder's namespace:
    harness/<folder>/x.h opens sb::<folder> or a namespace within it
    (sb::<folder>::detail), never sb itself nor another folder's, except to
    forward-declare another folder's class (`namespace sb::gl { class GpuScene; }`);
    plugin/api_names.h alone opens sb, to keep the plugin API's names there.
    Namespaces of other libraries (CLI, std) are theirs,
  - a source of techniques/ (header or .cpp) declares its names outside its
    folder's namespace: techniques/<family>/ in sb::techniques::<family> (or
    a namespace within it), the kit, techniques/common/, in sb::techniques
    itself (or sb::techniques::detail); forward declarations aside, as above.
`check_layout.py --self-test` checks that check."""
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


# The one header that declares names in sb itself: using-declarations that
# keep the plugin API's names reachable as sb::X for plugins.
SB_NAMES_HEADER = "harness/plugin/api_names.h"
COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
STRING = re.compile(r'R"([^(\s]*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"', re.S)
NAMESPACE_OPEN = re.compile(r"\bnamespace\s+([A-Za-z_][A-Za-z0-9_:]*)\s*\{")
FORWARD_DECLARATION = re.compile(r"^(?:\s*(?:class|struct)\s+[A-Za-z_][A-Za-z0-9_]*\s*;)+\s*$")


def top_level_namespaces(text):
    """(name, body) of each namespace block opened outside any brace, in a
    text without comments and strings."""
    text = STRING.sub('""', COMMENT.sub(" ", text))
    depth, i, out = 0, 0, []
    while i < len(text):
        m = NAMESPACE_OPEN.match(text, i) if depth == 0 else None
        if m and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            start, level, j = m.end(), 1, m.end()
            while j < len(text) and level:
                level += {"{": 1, "}": -1}.get(text[j], 0)
                j += 1
            out.append((m.group(1), text[start:j - 1]))
            i = j
            continue
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    return out


def namespace_problem(where, folder, text):
    """Why the header `where` (in harness/`folder`/) declares names outside
    sb::`folder`, or None."""
    own = f"sb::{folder}"
    for name, body in top_level_namespaces(text):
        if name != "sb" and not name.startswith("sb::"):
            continue  # another library's (a forward declaration, a specialisation)
        if name == own or name.startswith(own + "::"):
            continue
        if name == "sb" and where == SB_NAMES_HEADER:
            continue
        if name != "sb" and FORWARD_DECLARATION.match(body):
            continue  # another folder's class, declared ahead
        return (f"{where} declares names in namespace {name}: a header of harness/{folder}/ "
                f"declares its names in {own} (or a namespace within it, {own}::detail); "
                f"harness/README.md, \"Namespaces\"")
    return None


def technique_namespace_problem(where, folder, text):
    """Why the source `where` (in techniques/`folder`/) declares names outside
    its folder's namespace, or None."""
    own = "sb::techniques" if folder == SHADOW_KIT else f"sb::techniques::{folder}"
    within = own + "::detail" if folder == SHADOW_KIT else own
    for name, body in top_level_namespaces(text):
        if name != "sb" and not name.startswith("sb::"):
            continue  # another library's
        if name == own or name == within or name.startswith(within + "::"):
            continue
        if name != "sb" and FORWARD_DECLARATION.match(body):
            continue  # another folder's class, declared ahead
        allowed = f"{own} or {within}" if folder == SHADOW_KIT else f"{own} (or a namespace within it)"
        return (f"{where} declares names in namespace {name}: a source of techniques/{folder}/ "
                f"declares its names in {allowed}; harness/README.md, \"Namespaces\"")
    return None


def check_technique_namespaces(root):
    for path in sorted(sources(root, "techniques")):
        parts = os.path.relpath(path, root).split(os.sep)
        if len(parts) < 3:
            continue  # techniques/*.cpp, if any: no family
        with open(path, encoding="utf-8") as f:
            problem = technique_namespace_problem(os.path.relpath(path, root), parts[1], f.read())
        if problem:
            sys.exit(problem)


def check_namespaces(root):
    for folder in sorted(os.listdir(os.path.join(root, "harness"))):
        base = os.path.join(root, "harness", folder)
        if not os.path.isdir(base):
            continue
        for path in sorted(sources(root, os.path.join("harness", folder))):
            if not path.endswith(".h"):
                continue
            with open(path, encoding="utf-8") as f:
                problem = namespace_problem(os.path.relpath(path, root), folder, f.read())
            if problem:
                sys.exit(problem)


def expect(rule, ok, bad):
    """`rule` (a *namespace_problem function) on made-up sources: None for
    each of `ok`, a reason for each of `bad`."""
    for where, folder, text in ok:
        problem = rule(where, folder, text)
        assert problem is None, f"refused, should accept: {text!r}: {problem}"
    for where, folder, text in bad:
        assert rule(where, folder, text), f"accepted, should refuse: {text!r}"


def self_test():
    """The namespace rules on made-up sources: what they accept and refuse."""
    ok = [("harness/run/a.h", "run", "namespace sb::run {\nstruct A {};\n}  // namespace sb::run"),
          ("harness/run/a.h", "run", "namespace sb::run::detail { int f(); }"),
          ("harness/run/a.h", "run", "namespace CLI { class App; }\nnamespace sb::run { }"),
          ("harness/plugin/a.h", "plugin",
           "namespace sb::gl {\nclass GpuScene;\n}\nnamespace sb::plugin { struct X { int a; }; }"),
          ("harness/plugin/api_names.h", "plugin", "namespace sb { using plugin::Technique; }"),
          ("harness/run/a.h", "run", "// namespace sb {\nnamespace sb::run { auto s = \"namespace sb {\"; }")]
    bad = [("harness/run/a.h", "run", "namespace sb {\nstruct A {};\n}"),
           ("harness/run/a.h", "run", "namespace sb::record { struct A {}; }"),
           ("harness/run/a.h", "run", "namespace sb::runner { }"),
           ("harness/core/a.h", "core", "namespace sb { using core::Scene; }"),
           ("harness/run/a.h", "run", "namespace sb::run { }\nnamespace sb { class A; }")]
    expect(namespace_problem, ok, bad)
    technique_ok = [
        ("techniques/planar/a.cpp", "planar",
         "namespace sb::techniques::planar {\nnamespace {\nint f();\n}\n}\nSHADOWBENCH_PLUGIN_ENTRY(x) {}"),
        ("techniques/planar/a.h", "planar", "namespace sb::techniques::planar::detail { int f(); }"),
        ("techniques/common/a.h", "common", "namespace sb::techniques { struct DepthMap {}; }"),
        ("techniques/common/a.h", "common", "namespace sb::techniques::detail { int f(); }"),
        ("techniques/common/a.h", "common",
         "namespace sb::gl {\nclass GpuScene;\n}\nnamespace sb::techniques { }"),
        ("techniques/planar/a.cpp", "planar", "namespace glm { }\nusing namespace sb;")]
    technique_bad = [
        ("techniques/planar/a.cpp", "planar", "namespace sb {\nnamespace {\nint f();\n}\n}"),
        ("techniques/planar/a.h", "planar", "namespace sb::shadow { int f(); }"),
        ("techniques/planar/a.h", "planar", "namespace sb::techniques { int f(); }"),
        ("techniques/planar/a.h", "planar", "namespace sb::techniques::accumulation { int f(); }"),
        ("techniques/planar/a.h", "planar", "namespace sb::techniques::planar_x { int f(); }"),
        ("techniques/common/a.h", "common", "namespace sb::techniques::shadow_map { int f(); }"),
        ("techniques/common/a.h", "common", "namespace sb::techniques::common { int f(); }")]
    expect(technique_namespace_problem, technique_ok, technique_bad)
    print(f"namespace rule: {len(ok) + len(technique_ok)} accepted, "
          f"{len(bad) + len(technique_bad)} refused, as expected")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return
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
    check_namespaces(root)
    check_technique_namespaces(root)
    for src in sorted(graph):
        print(f"{src} -> {' '.join(sorted(graph[src]))}")


if __name__ == "__main__":
    main()
