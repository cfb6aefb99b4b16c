#!/usr/bin/env python3
"""Independent check of a golden: recomputes every vertex of an XYZR input by
brute force over all quadruples in 300-digit decimal arithmetic (no code shared
with vorball) and compares ids and doubles with golden/CASE.tsv.

    python3 corpus/check_golden.py [--fast] corpus/inputs/CASE.xyzr corpus/golden/CASE.tsv

Cost grows as n^4 with slow arithmetic: seconds to a minute for the
constructed cases. --fast first solves each quadruple in doubles and skips it
when a sphere is closer than t by more than 1e-6 of the input's scale: a
heuristic, not a proof (a few minutes for the 70-atom crambin fragment, and
wrong on jittered_lattice, whose quadruples doubles cannot solve).
Not run by ctest. Exit status 0 when the golden agrees exactly.

Method: for a quadruple a, b, c, d the tangency conditions |p - c_i| = r_i + t,
squared and subtracted from the one of sphere a, are three linear equations in
(x, y, z, t); their kernel v and a particular solution u give the line
u + mu v, and the squared condition of sphere a is a quadratic in mu. Roots
with r_i + t < 0 for a defining sphere solve only the squared system and are
dropped; a root is a vertex when no sphere is strictly closer than t. Residuals
and coordinates below 1e-150 count as zero: inputs carry at most 18 digits,
so a genuine non-zero value is far larger.
"""
import itertools
import sys
from decimal import Decimal, getcontext

getcontext().prec = 300
ZERO = Decimal("1e-150")


def read_xyzr(path):
    spheres = []
    for line in open(path):
        line = line.split("#")[0].split()
        if line:
            spheres.append(tuple(Decimal(v) for v in line[:4]))
    return spheres


def det3(a, b, c):
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


def tangent_spheres(quad, S, zero=ZERO):
    """Points (x, y, z, t) tangent to the four spheres (Decimal or float S);
    None when the quadruple does not determine a finite set."""
    x0, y0, z0, r0 = S[quad[0]]
    w0 = x0 * x0 + y0 * y0 + z0 * z0 - r0 * r0
    rows, rhs = [], []
    for i in quad[1:]:
        x, y, z, r = S[i]
        rows.append([2 * (x - x0), 2 * (y - y0), 2 * (z - z0), 2 * (r - r0)])
        rhs.append(x * x + y * y + z * z - r * r - w0)

    def minor(skip):
        return [[row[k] for k in range(4) if k != skip] for row in rows]

    v = [(1 if k % 2 == 0 else -1) * det3(*minor(k)) for k in range(4)]
    k = max(range(4), key=lambda i: abs(v[i]))
    if abs(v[k]) <= zero:
        return None
    m = minor(k)
    D = det3(*m)
    sol = []
    for j in range(3):
        mm = [list(r) for r in m]
        for i in range(3):
            mm[i][j] = rhs[i]
        sol.append(det3(*mm) / D)
    u = sol[:k] + [0 * D] + sol[k:]
    q = [u[0] - x0, u[1] - y0, u[2] - z0]
    s0 = r0 + u[3]
    A = v[0] ** 2 + v[1] ** 2 + v[2] ** 2 - v[3] ** 2
    B = 2 * (q[0] * v[0] + q[1] * v[1] + q[2] * v[2] - s0 * v[3])
    C = q[0] ** 2 + q[1] ** 2 + q[2] ** 2 - s0 * s0
    if abs(A) <= zero:
        mus = [-C / B] if abs(B) > zero else []
    else:
        disc = B * B - 4 * A * C
        if disc < 0:
            return []
        sq = disc ** 0.5 if isinstance(disc, float) else disc.sqrt()
        mus = [(-B - sq) / (2 * A), (-B + sq) / (2 * A)]
    points = [[u[i] + mu * v[i] for i in range(4)] for mu in mus]
    return [p for p in points if all(S[i][3] + p[3] >= 0 for i in quad)]


def far_from_empty(quad, F, margin):
    """--fast: True when every double root of the quadruple has a sphere
    closer than t by more than margin (or there is clearly no root)."""
    try:
        roots = tangent_spheres(quad, F, 1e-9 * margin)
    except ZeroDivisionError:
        return False
    if roots is None:
        return False
    for p in roots:
        if all(((p[0] - x) ** 2 + (p[1] - y) ** 2 + (p[2] - z) ** 2) ** 0.5 - r - p[3] > -margin
               for x, y, z, r in F):
            return False
    return True


def vertices(S, fast):
    F = [tuple(float(c) for c in s) for s in S]
    scale = 1 + max(abs(c) for s in F for c in s)
    found = {}
    for quad in itertools.combinations(range(len(S)), 4):
        if fast and far_from_empty(quad, F, 1e-6 * scale):
            continue
        for p in tangent_spheres(quad, S) or []:
            gaps = [((p[0] - x) ** 2 + (p[1] - y) ** 2 + (p[2] - z) ** 2).sqrt() - r - p[3]
                    for x, y, z, r in S]
            if any(g < -ZERO for g in gaps):
                continue
            members = frozenset(i for i, g in enumerate(gaps) if abs(g) <= ZERO)
            # An exact zero comes out as a residue of about 1e-300.
            point = tuple(0.0 if abs(c) <= ZERO else float(c) for c in p)
            found[(members, point)] = None
    return sorted((tuple(sorted(m)), p) for m, p in found)


def read_golden(path):
    out = []
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        f = line.rstrip("\n").split("\t")
        out.append((tuple(int(i) for i in f[0].split(",")), tuple(float(c) for c in f[1:5])))
    return out


def main():
    args = sys.argv[1:]
    fast = args[:1] == ["--fast"]
    args = args[1:] if fast else args
    if len(args) != 2:
        sys.exit(__doc__)
    mine = vertices(read_xyzr(args[0]), fast)
    golden = read_golden(args[1])
    # float() of a 300-digit value is the nearest double: compare bit for bit
    # (0.0 == -0.0 here; the golden's sign of zero is not checked).
    if mine == golden:
        print("%s: %d vertices, identical" % (args[1], len(mine)))
        return 0
    print("%s: golden %d vertices, brute force %d" % (args[1], len(golden), len(mine)))
    for v in sorted(set(golden) - set(mine))[:10]:
        print("  only in golden:", v)
    for v in sorted(set(mine) - set(golden))[:10]:
        print("  only in brute force:", v)
    return 1


if __name__ == "__main__":
    sys.exit(main())
