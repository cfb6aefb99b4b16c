#!/usr/bin/env python3
"""No arrow back up and no circles (issue 29, DESIGN.md "Rooms"): every
`#include "x.h"` of the library's rooms and its two peers, resolved to the
header's folder, must point to a room below or beside the includer's:

    core  <  gpu, verify  <  lib  <  cli, python/src

(gpu and verify do not include each other, nor cli and python/src; cli and
python/src reach the device layer through lib, never a gpu/ header). Below
the rooms, the wings (core/input, verify/arcs, ...) must form no circle of
includes other than those listed in KNOWN (each a wing pair whose mutual
includes are known, with the reason); a new circle, or a known one that has
gone (then drop it from KNOWN), fails. Prints the wing graph's circles.
No file of the library (core, gpu, verify, lib) is over MAX_LINES lines.

usage: rooms.py SOURCE_DIR
"""
import collections
import os
import re
import sys

ROOMS = {"core": 0, "gpu": 1, "verify": 1, "lib": 2, "cli": 3, "python/src": 3}
# Strongly connected sets of wings allowed to stay (each with its reason):
# none today. The last ones went with issue 29: the box readers moved to
# core/input (vb_box.h), judge declares its arc report calls (vb_verify_file.h),
# certify owns vb_verify_mpfr_version.
KNOWN = []
EXT = (".c", ".h", ".cl", ".cpp", ".hpp")
# Issue 29's bound on a library file: one job a file, read in one sitting.
MAX_LINES = 700


def room_of(path):
    for r in sorted(ROOMS, key=len, reverse=True):
        if path == r or path.startswith(r + "/"):
            return r
    return None


def wing_of(path):
    parts = path.split("/")
    if parts[0] == "python":
        return "python/src"
    return "/".join(parts[:2]) if len(parts) > 2 else parts[0]


def sccs(graph):
    """Tarjan's strongly connected components with more than one node."""
    index, low, stack, on, out, n = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = n[0]
        n[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = set()
            while True:
                w = stack.pop()
                on.discard(w)
                comp.add(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(comp)

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main():
    src = sys.argv[1]
    files = []
    for r in ROOMS:
        for dp, _, fn in os.walk(os.path.join(src, r)):
            files += [os.path.relpath(os.path.join(dp, f), src) for f in fn if f.endswith(EXT)]
    where = {}
    for f in files:
        if f.endswith((".h", ".hpp")):
            where.setdefault(os.path.basename(f), f)
    bad, wings = [], collections.defaultdict(set)
    for f in sorted(files):
        with open(os.path.join(src, f), errors="replace") as fh:
            text = fh.read()
        if ROOMS[room_of(f)] <= 2 and text.count("\n") > MAX_LINES:
            bad.append(f"{f}: {text.count(chr(10))} lines, over {MAX_LINES}")
        for m in re.finditer(r'^\s*#\s*include\s+"([^"]+)"', text, re.M):
            h = where.get(os.path.basename(m.group(1)))
            if not h:
                continue  # generated, or a system header in quotes
            a, b = room_of(f), room_of(h)
            if a != b and (ROOMS[b] >= ROOMS[a]):
                bad.append(f"{f} includes {h}: {b} is not below {a}")
            if ROOMS[a] == 3 and b == "gpu":
                bad.append(f"{f} includes {h}: {a} reaches gpu through lib only")
            if wing_of(f) != wing_of(h):
                wings[wing_of(f)].add(wing_of(h))
    circles = sccs(wings)
    for c in circles:
        print("circle:", " ".join(sorted(c)), "(known)" if c in KNOWN else "(NEW)")
        if c not in KNOWN:
            bad.append("a new circle of wings: " + " ".join(sorted(c)))
    for k in KNOWN:
        if k not in circles:
            bad.append("known circle gone (drop it from KNOWN): " + " ".join(sorted(k)))
    print(f"{len(files)} files, {sum(len(v) for v in wings.values())} wing arrows, "
          f"{len(circles)} circles of wings ({len(KNOWN)} known), 0 room circles by rank")
    for b in bad:
        print("rooms.py:", b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
