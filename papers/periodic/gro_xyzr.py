#!/usr/bin/env python3
"""A GRO file's atoms as `x y z r` lines in Å (coordinates times 10 exactly,
as decimals), and its box as the 9 numbers of `vorball --box` (first line of
stderr), for runs on the very same balls by vorball and Voronota. Atoms
whose name is in --drop (default MW: TIP4P's massless virtual site) are left
out. Radii by element as vorball's built-in table infers them here: the
first letter of the name (H 1.20, C 1.70, N 1.55, O 1.52, S 1.80), sodium
ions (residue NA/NA+/SOD) 2.27.
usage: gro_xyzr.py FILE.gro [--drop MW] > balls.xyzr 2> box.txt"""
import sys
from decimal import Decimal

RADII = {"H": "1.20", "C": "1.70", "N": "1.55", "O": "1.52", "S": "1.80"}


def ang(s):
    return format(Decimal(s.strip()) * 10, "f")


def main():
    path = sys.argv[1]
    drop = {"MW"}
    if "--drop" in sys.argv:
        drop = set(sys.argv[sys.argv.index("--drop") + 1].split(","))
    with open(path) as f:
        lines = f.read().splitlines()
    n = int(lines[1])
    out = []
    for ln in lines[2:2 + n]:
        res, name = ln[5:10].strip(), ln[10:15].strip()
        if name in drop:
            continue
        r = "2.27" if res in ("NA", "NA+", "SOD") else RADII[name[0]]
        out.append("%s %s %s %s" % (ang(ln[20:28]), ang(ln[28:36]), ang(ln[36:44]), r))
    sys.stdout.write("\n".join(out) + "\n")
    b = [ang(x) for x in lines[2 + n].split()]
    if len(b) == 3:
        b = [b[0], "0", "0", "0", b[1], "0", "0", "0", b[2]]
    else:  # GRO: v1(x) v2(y) v3(z) v1(y) v1(z) v2(x) v2(z) v3(x) v3(y)
        b = [b[0], b[3], b[4], b[5], b[1], b[6], b[7], b[8], b[2]]
    sys.stderr.write(" ".join(b) + "\n")


main()
