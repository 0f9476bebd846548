#!/usr/bin/env python3
"""Structure check of the C modules: no dependency cycle, no file over the line limit.

A module is a header together with the source files that define what it declares (a
function or a variable named in the header, outside comments, and defined without
`static` in the .c); headers and sources tied that way are one module, and a source that
implements no header is a module of its own. Module A depends on module B when a file of
A includes a header of B. That graph must have no cycle: a cycle of includes, or a call
that goes back up (say, a sub-solve that calls the public entry point by name), shows as
one. Every .c and .h file must have at most LINE_LIMIT lines.

usage: scripts/check_cycles.py [--root DIR] [--limit N] [FOLDER ...]
  FOLDER   folders to check, relative to the root (default: plan planner core executor)
  --root   the repository (default: this script's parent folder)
  --limit  the line limit (default LINE_LIMIT)
Cycles and long files named in KNOWN_CYCLES / KNOWN_LONG are reported, not failed.
Exit status 0 when both hold, 1 with the cycles and long files listed otherwise.
"""

import argparse
import os
import re
import sys

LINE_LIMIT = 800  # lines per .c / .h file (CONTRIBUTING: one concern per file)
DEFAULT_FOLDERS = ("plan", "planner", "core", "executor")
# Known, left to the work that owns them (issue #42): a cycle is known by one header of
# it, a long file by its path. A new cycle or long file fails; a known one is reported.
KNOWN_CYCLES = {
    "planner/include/hv/pick_model.h": "hv_fruit_t lives in plan_instance.h, which builds "
    "instances with the pick model",
    "executor/can/include/hv/can_bus.h": "the CAN transports and their wire format (item 5)",
}
KNOWN_LONG = {}
SKIP_DIRS = {"build", ".git", ".venv", "__pycache__"}

INCLUDE_RE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
COMMENT_RE = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)
STRING_RE = re.compile(r'"(\\.|[^"\\])*"')
IDENT_RE = re.compile(r"\b[A-Za-z_]\w*\b")
# an external definition starts at column 0: a function (its "(" before any ";" or "=",
# and a body) or a variable with an initialiser
FUNC_DEF_RE = re.compile(
    r"^(?!static\b|extern\b|typedef\b|struct\b|enum\b|union\b|#)"
    r"[A-Za-z_][\w \t\*]*?\b([A-Za-z_]\w*)\s*\([^;{]*\)\s*\{",
    re.M,
)
VAR_DEF_RE = re.compile(
    r"^(?!static\b|extern\b|typedef\b|#)[A-Za-z_][\w \t\*]*?\b([A-Za-z_]\w*)"
    r"\s*(?:\[[^\]]*\])?\s*=",
    re.M,
)


def source_files(root, folders):
    out = []
    for folder in folders:
        top = os.path.join(root, folder)
        for d, dirs, files in os.walk(top):
            dirs[:] = sorted(x for x in dirs if x not in SKIP_DIRS and not x.startswith("build"))
            out += [os.path.join(d, f) for f in sorted(files) if f.endswith((".c", ".h"))]
    return out


def strip(text):
    return STRING_RE.sub('""', COMMENT_RE.sub(" ", text))


def resolve(inc, from_file, include_dirs):
    for d in [os.path.dirname(from_file)] + include_dirs:
        p = os.path.normpath(os.path.join(d, inc))
        if os.path.isfile(p):
            return p
    return None  # a system or generated header: outside the graph


def modules(files, include_dirs):
    """(module of each file, module dependency graph as {module: set(module)})"""
    text = {f: open(f, encoding="utf-8", errors="replace").read() for f in files}
    defined = {}  # name -> sources defining it
    for f in files:
        if f.endswith(".c"):
            body = strip(text[f])
            for rx in (FUNC_DEF_RE, VAR_DEF_RE):
                for m in rx.finditer(body):
                    defined.setdefault(m.group(1), set()).add(f)
    parent = {f: f for f in files}

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for h in files:
        if h.endswith(".h"):
            for name in set(IDENT_RE.findall(strip(text[h]))):
                for c in defined.get(name, ()):
                    parent[find(c)] = find(h)
    includes = {
        f: [p for p in (resolve(i, f, include_dirs) for i in INCLUDE_RE.findall(text[f])) if p]
        for f in files
    }
    graph = {}
    for f in files:
        a = find(f)
        graph.setdefault(a, set())
        for h in includes[f]:
            if h in parent and find(h) != a:
                graph[a].add(find(h))
    return {f: find(f) for f in files}, graph, includes


def cycles(graph):
    """The strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
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

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument("--limit", type=int, default=LINE_LIMIT)
    ap.add_argument("folders", nargs="*", default=list(DEFAULT_FOLDERS))
    args = ap.parse_args(argv)
    root = os.path.abspath(args.root)
    files = source_files(root, args.folders)
    include_dirs = sorted(
        os.path.join(dp, "include")
        for folder in args.folders
        for dp, dn, _ in os.walk(os.path.join(root, folder))
        if "include" in dn
    )
    module_of, graph, _ = modules(files, include_dirs)

    def rel(p):
        return os.path.relpath(p, root)

    bad = known = 0
    for comp in cycles(graph):
        members = {m: sorted(rel(f) for f in files if module_of[f] == m) for m in comp}
        why = [KNOWN_CYCLES[f] for m in comp for f in members[m] if f in KNOWN_CYCLES]
        if why:
            known += 1
        else:
            bad += 1
        print(
            "%scycle between %d modules%s:"
            % ("known " if why else "", len(comp), " (%s)" % why[0] if why else "")
        )
        for m in comp:
            deps = sorted(rel(d) for d in graph[m] if d in comp)
            print("  %s -> %s" % (" + ".join(members[m]), ", ".join(deps)))
    for f in files:
        n = sum(1 for _ in open(f, encoding="utf-8", errors="replace"))
        if n > args.limit:
            why = KNOWN_LONG.get(rel(f))
            known += why is not None
            bad += why is None
            print(
                "%s%s: %d lines, over the limit of %d%s"
                % ("known: " if why else "", rel(f), n, args.limit, " (%s)" % why if why else "")
            )
    n_mod = len(set(module_of.values()))
    print("%d files in %d modules: %d problems, %d known" % (len(files), n_mod, bad, known))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
