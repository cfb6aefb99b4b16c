#!/usr/bin/env python3
"""Regenerates the equal-radius suite (corpus/equal-radius/*.xyzr).

Every coordinate is written from integers, so each file holds exactly the
decimals below, with no binary floating point on the way. The random sets use
splitmix64 so the files do not depend on Python's random module.
Run from anywhere: python3 generate.py
"""
from fractions import Fraction
from pathlib import Path
import math

HERE = Path(__file__).resolve().parent


def dec(q):
    """Exact decimal text of a Fraction whose denominator divides 10^k."""
    q = Fraction(q)
    k = 0
    while (q * 10**k).denominator != 1:
        k += 1
        assert k < 19, q
    n = q * 10**k
    sign = "-" if n < 0 else ""
    digits = str(abs(n.numerator)).rjust(k + 1, "0")
    text = digits if k == 0 else digits[:-k] + "." + digits[-k:]
    return sign + text


def write(name, comment, centres, radius):
    seen = set()
    with open(HERE / name, "w") as f:
        for line in comment:
            f.write("# " + line + "\n")
        for c in centres:
            assert c not in seen, c
            seen.add(c)
            f.write(" ".join(dec(v) for v in c) + " " + dec(radius) + "\n")


def shifted(points, origin):
    return [tuple(Fraction(o) + p for o, p in zip(origin, q)) for q in points]


ORIGIN = (Fraction("10.25"), Fraction("-3.7"), Fraction("0.125"))


def simple_cubic():
    a = Fraction("3.1")
    pts = [(i * a, j * a, k * a) for i in range(4) for j in range(4) for k in range(4)]
    write("sc.xyzr", ["simple cubic, 4x4x4 sites, spacing 3.1, shifted by (10.25,-3.7,0.125)",
                      "27 vertices, each of degree 8 (cube centres)"],
          shifted(pts, ORIGIN), Fraction("1.5"))


def bcc():
    a = Fraction(3)
    pts = [(i * a, j * a, k * a) for i in range(4) for j in range(4) for k in range(4)]
    pts += [((i + Fraction(1, 2)) * a, (j + Fraction(1, 2)) * a, (k + Fraction(1, 2)) * a)
            for i in range(3) for j in range(3) for k in range(3)]
    write("bcc.xyzr", ["body-centred cubic, 3x3x3 cells, a = 3, shifted by (10.25,-3.7,0.125)",
                       "interior vertices have degree 4 (truncated octahedra);",
                       "the block's faces add co-spherical groups"],
          shifted(pts, ORIGIN), Fraction("1.2"))


def fcc():
    h = Fraction(2)  # half the cube edge a = 4
    pts = [(i * h, j * h, k * h) for i in range(5) for j in range(5) for k in range(5)
           if (i + j + k) % 2 == 0]
    write("fcc.xyzr", ["face-centred cubic, 2x2x2 cells, a = 4, shifted by (10.25,-3.7,0.125)",
                       "tetrahedral holes give degree-4 vertices, octahedral holes degree 6"],
          shifted(pts, ORIGIN), Fraction("1.3"))


def sphere_points(d):
    """All integer points with x^2 + y^2 + z^2 = d^2 (Pythagorean quadruples)."""
    pts = []
    for x in range(-d, d + 1):
        for y in range(-d, d + 1):
            z2 = d * d - x * x - y * y
            if z2 < 0:
                continue
            z = math.isqrt(z2)
            if z * z == z2:
                pts += [(x, y, z)] if z == 0 else [(x, y, z), (x, y, -z)]
    return sorted(pts)


def sphere(name, d, scale, radius):
    centre = (Fraction("1.25"), Fraction("-0.75"), Fraction("2.5"))
    pts = [tuple(c + scale * v for c, v in zip(centre, p)) for p in sphere_points(d)]
    write(name, ["%d integer points with x^2+y^2+z^2 = %d^2, scaled by %s, centred at"
                 " (1.25,-0.75,2.5)" % (len(pts), d, dec(scale)),
                 "exactly co-spherical: one vertex of degree %d at the centre" % len(pts)],
          pts, radius)


def icosahedron():
    # The golden ratio is irrational; 1.618034 stands in for it. The points
    # (0, +-1, +-a) and their cyclic permutations satisfy |v|^2 = 1 + a^2 for
    # every a, so the twelve stay exactly co-spherical; only the equal edge
    # lengths are approximate.
    a = Fraction("1.618034")
    s = Fraction(2)
    pts = []
    for u in (-1, 1):
        for v in (-a, a):
            for p in ((0, u, v), (u, v, 0), (v, 0, u)):
                pts.append(tuple(s * c for c in p))
    pts.append((Fraction(0), Fraction(0), Fraction(0)))
    write("icosahedron.xyzr", ["regular icosahedron (0,+-2,+-2a) cyclic, a = 1.618034 ~ golden ratio,"
                               " plus its centre",
                               "the 12 outer points are exactly co-spherical; 20 vertices of degree 4"],
          shifted(pts, ORIGIN), Fraction("1.0"))


MASK = (1 << 64) - 1


def splitmix64(state):
    state = (state + 0x9E3779B97F4A7C15) & MASK
    z = state
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
    return state, z ^ (z >> 31)


def random_set(n, seed):
    # Box edge for about one centre per 27 cubic units (spacing ~3, as atoms);
    # coordinates in thousandths.
    edge = round((27 * n) ** (1 / 3) * 1000)
    state = seed
    pts, seen = [], set()
    while len(pts) < n:
        c = []
        for _ in range(3):
            state, r = splitmix64(state)
            c.append(Fraction(r % edge, 1000))
        c = tuple(c)
        if c not in seen:
            seen.add(c)
            pts.append(c)
    write("random-%d.xyzr" % n, ["%d uniform random centres in a box of edge %s, thousandths,"
                                 " splitmix64 seed %d" % (n, dec(Fraction(edge, 1000)), seed)],
          pts, Fraction("1.6"))


if __name__ == "__main__":
    simple_cubic()
    bcc()
    fcc()
    sphere("sphere-30.xyzr", 3, Fraction(1), Fraction("0.5"))
    sphere("sphere-270.xyzr", 21, Fraction("0.5"), Fraction("1.0"))
    icosahedron()
    for n in (100, 1000, 10000):
        random_set(n, 20261122 + n)
