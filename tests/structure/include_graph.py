#!/usr/bin/python3
"""The include graph of lamina's library folders stays one-way.

Reads the `#include "..."` lines of every .hpp/.cpp under core, materials,
micro, homogenize and membrane (an include resolves against the including
file's folder, then against the repository root; one that names no file of
these folders, a third-party header, is left out) and fails, naming the
cycle or the include, when

  (a) two concepts include each other, directly or through others. A concept
      is a path without its extension: a.cpp -> b.hpp and b.cpp -> a.hpp is
      the cycle a -> b -> a;
  (b) the subfolders of a folder include each other (membrane/model ->
      membrane/loads -> membrane/model); a folder's own files count as one
      more member, "<folder>/.";
  (c) a top folder includes one it must not: core <- materials <- micro <-
      homogenize, materials <- membrane (each may include only those named
      in ALLOWED).

Usage: include_graph.py [ROOT]      check the tree at ROOT (default: the repository)
       include_graph.py --self-test plants each kind of fault in a temporary
                                    tree and checks that it is found
Exit status 0 when the graph is one-way, 1 with the faults on stderr.
"""

import os
import re
import sys
import tempfile

TOP = ["core", "materials", "micro", "homogenize", "membrane"]
# The top folders each top folder may include (besides itself).
ALLOWED = {
    "core": set(),
    "materials": {"core"},
    "micro": {"core", "materials"},
    "homogenize": {"core", "materials", "micro"},
    "membrane": {"core", "materials"},
}
# Concept cycles that predate this check, each the set of concepts of one
# tangle (a .cpp using a concept whose header needs its own): reported but
# not failed, until broken. A tangle that grows, a new one, or an entry here
# that no longer tangles (delete it then) fails. Keep this list shrinking.
KNOWN = []
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def sources(root):
    """Yields the .hpp/.cpp files of the top folders, relative to root."""
    for top in TOP:
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if name.endswith((".hpp", ".cpp")):
                    yield os.path.relpath(os.path.join(folder, name), root).replace(os.sep, "/")


def concept(path):
    """The path without its extension."""
    return os.path.splitext(path)[0]


def includes(root, files):
    """(file, included file) for every include that names one of files."""
    known = set(files)
    for f in files:
        with open(os.path.join(root, f), encoding="utf-8", errors="replace") as fh:
            for line in fh:
                m = INCLUDE.match(line)
                if not m:
                    continue
                here = os.path.normpath(os.path.join(os.path.dirname(f), m.group(1))).replace(os.sep, "/")
                for target in (here, os.path.normpath(m.group(1)).replace(os.sep, "/")):
                    if target in known:
                        yield f, target
                        break


def find_cycle(edges):
    """A cycle [n0, n1, ..., n0] of the directed graph edges (node -> set), or None."""
    state = {}  # 1: on the current path, 2: done
    for start in sorted(edges):
        if state.get(start):
            continue
        path, stack = [start], [iter(sorted(edges.get(start, ())))]
        state[start] = 1
        while stack:
            nxt = next(stack[-1], None)
            if nxt is None:
                state[path.pop()] = 2
                stack.pop()
            elif state.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            elif not state.get(nxt):
                state[nxt] = 1
                path.append(nxt)
                stack.append(iter(sorted(edges.get(nxt, ()))))
    return None


def cycles(edges):
    """(cycle, component): one cycle per strongly connected component of
    edges that has one (so that every tangle is named, not only the first)."""
    found = []
    remaining = {n: set(t) for n, t in edges.items()}
    while True:
        cycle = find_cycle(remaining)
        if not cycle:
            return found
        # The component of the cycle: the nodes that reach it and that it reaches.
        component = reach(remaining, cycle[0]) & reach(reverse(remaining), cycle[0])
        found.append((cycle, component))
        remaining = {n: t - component for n, t in remaining.items() if n not in component}


def reach(edges, start):
    """The nodes reachable from start (start included)."""
    seen, todo = {start}, [start]
    while todo:
        for n in edges.get(todo.pop(), ()):
            if n not in seen:
                seen.add(n)
                todo.append(n)
    return seen


def reverse(edges):
    """The graph with every edge turned around."""
    out = {}
    for n, targets in edges.items():
        for t in targets:
            out.setdefault(t, set()).add(n)
    return out


def member(folder, path):
    """The member of folder that path lies in: its subfolder, or folder/. for its own files."""
    rest = path[len(folder) + 1:]
    return folder + "/" + rest.split("/")[0] if "/" in rest else folder + "/."


def check(root, known=()):
    """@return the faults of the tree at root, one message each, and the
    known tangles (of @p known) found, one message each."""
    files = list(sources(root))
    pairs = list(includes(root, files))
    faults = []
    # (a) concepts
    concepts = {}
    for f, t in pairs:
        if concept(f) != concept(t):
            concepts.setdefault(concept(f), set()).add(concept(t))
    notes, seen = [], []
    for cycle, component in cycles(concepts):
        text = "include cycle between concepts: " + " -> ".join(cycle)
        if component in known:
            notes.append("known " + text)
            seen.append(component)
        else:
            faults.append(text)
    for k in known:
        if k not in seen:
            faults.append("known cycle of %s is gone: delete it from KNOWN" % ", ".join(sorted(k)))
    # (b) the members of every folder
    folders = {os.path.dirname(f) for f in files}
    for folder in sorted(folders | {os.path.dirname(d) for d in folders if "/" in d}):
        graph = {}
        for f, t in pairs:
            if f.startswith(folder + "/") and t.startswith(folder + "/"):
                a, b = member(folder, f), member(folder, t)
                if a != b:
                    graph.setdefault(a, set()).add(b)
        for cycle, _ in cycles(graph):
            faults.append("include cycle between the folders of " + folder + "/: " + " -> ".join(cycle))
    # (c) top folders
    for f, t in pairs:
        a, b = f.split("/")[0], t.split("/")[0]
        if a != b and b not in ALLOWED[a]:
            faults.append("%s includes %s: %s may include only %s" %
                          (f, t, a, ", ".join(sorted(ALLOWED[a])) or "itself"))
    return faults, notes


def self_test():
    """Plants each kind of fault in a small tree; @return 0 when each is found and the clean tree passes."""
    clean = {
        "core/a.hpp": "",
        "materials/law.hpp": '#include "core/a.hpp"\n',
        "membrane/model/m.hpp": '#include "materials/law.hpp"\n',
        "membrane/model/m.cpp": '#include "membrane/model/m.hpp"\n',
        "membrane/loads/l.hpp": '#include "membrane/model/m.hpp"\n',
        "membrane/run.cpp": '#include "membrane/loads/l.hpp"\n#include <vector>\n#include "gmsh.h"\n',
    }
    planted = {
        "concepts": ({"membrane/model/n.hpp": "", "membrane/model/n.cpp": '#include "m.hpp"\n',
                      "membrane/model/m.cpp": '#include "membrane/model/m.hpp"\n#include "n.hpp"\n'},
                     "include cycle between concepts: membrane/model/m -> membrane/model/n -> membrane/model/m"),
        "folders": ({"membrane/model/k.hpp": '#include "membrane/loads/l2.hpp"\n', "membrane/loads/l2.hpp": ""},
                    "include cycle between the folders of membrane/: membrane/loads -> membrane/model -> membrane/loads"),
        "own files": ({"membrane/model/k.cpp": '#include "membrane/run.hpp"\n', "membrane/run.hpp": ""},
                      "include cycle between the folders of membrane/: membrane/. -> membrane/loads -> membrane/model -> membrane/."),
        "top folders": ({"core/b.hpp": '#include "materials/law.hpp"\n'},
                        "core/b.hpp includes materials/law.hpp: core may include only itself"),
        "membrane above micro": ({"micro/c.hpp": "", "membrane/model/c.cpp": '#include "micro/c.hpp"\n'},
                                 "membrane/model/c.cpp includes micro/c.hpp: membrane may include only core, materials"),
    }
    failed = 0
    with tempfile.TemporaryDirectory() as root:  # a known tangle passes; a gone one fails
        for path, text in {**clean, **planted["concepts"][0]}.items():
            os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
            with open(os.path.join(root, path), "w", encoding="utf-8") as fh:
                fh.write(text)
        tangle = {"membrane/model/m", "membrane/model/n"}
        ok = check(root, [tangle])[0] == [] and check(root, [tangle, {"core/a", "core/x"}])[0] == [
            "known cycle of core/a, core/x is gone: delete it from KNOWN"]
        print("%-22s %s" % ("known list", "as expected" if ok else "MISSED"))
        failed += not ok
    for name, (extra, expected) in [("clean", ({}, None))] + list(planted.items()):
        with tempfile.TemporaryDirectory() as root:
            for path, text in {**clean, **extra}.items():
                os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
                with open(os.path.join(root, path), "w", encoding="utf-8") as fh:
                    fh.write(text)
            faults, _ = check(root)
        ok = faults == [] if expected is None else expected in faults
        print("%-22s %s%s" % (name, "found as expected" if ok and expected else "clean" if ok else "MISSED",
                              "" if ok else ": got %r, expected %r" % (faults, expected)))
        failed += not ok
    return 1 if failed else 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    faults, notes = check(root, KNOWN)
    for n in notes:
        print(n)
    for f in faults:
        print(f, file=sys.stderr)
    if not faults:
        print("include graph one-way: %d files of %s" % (len(list(sources(root))), ", ".join(TOP)))
    return 1 if faults else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
