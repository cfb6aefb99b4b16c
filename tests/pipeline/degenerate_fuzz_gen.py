#!/usr/bin/env python3
"""Small degenerate sphere sets for degenerate_fuzz.sh (issue 27), exact decimals.

usage: degenerate_fuzz_gen.py SEED COUNT OUT_DIR

Writes OUT_DIR/SEED+k.xyzr for k = 0 .. COUNT-1: 4 to 12 balls each, one kind
per set (chosen from the set's seed), the rest of the balls random near the
degenerate group so that they take part in its vertices. Kinds:
  nested       balls strictly inside a larger one (empty cells), and a ball inside those
  internal     internally tangent: |ci - cj| + Ri = Rj exactly (a rational unit
               vector from a Pythagorean quadruple times a decimal distance): pairs,
               one small ball inside 3 or 4 larger ones tangent to each, or the
               four balls of issue 27 moved
  tangent      externally tangent pairs: |ci - cj| = Ri + Rj exactly
  coincident   equal centres with different radii
  grid         a subset of an sc, bcc or fcc block, equal radii or two radii
  jittered     the same, every coordinate moved by up to 1e-12, 1e-9, 1e-6 or 1e-3
  cospherical  points of an integer sphere (|p| = 3, 5, 6, 7, 9), balls tangent to
               one sphere (equal or unequal radii: |c - O| = rho + r exactly)
The first line of each file is a comment naming the seed and kind. Every
number is an exact decimal (Fractions, splitmix64): no binary floating point.
Standard library only.
"""
import math
import sys
from fractions import Fraction as F
from pathlib import Path

# The exact decimal writer (and Pythagorean points) of the corpus generator:
# one copy for every script that writes exact inputs.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "corpus" / "equal-radius"))
from generate import dec  # noqa: E402 (corpus/equal-radius/generate.py)

MASK = (1 << 64) - 1
KINDS = ["nested", "internal", "tangent", "coincident", "grid", "jittered", "cospherical"]


class Rng:
    def __init__(self, seed):
        self.s = (seed * 0x2545F4914F6CDD1D + 27) & MASK

    def next(self):
        self.s = (self.s + 0x9E3779B97F4A7C15) & MASK
        z = self.s
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return z ^ (z >> 31)

    def below(self, n):
        return self.next() % n

    def pick(self, seq):
        return seq[self.below(len(seq))]

    def dec(self, lo, hi, places=1):
        """A uniform decimal in [lo, hi] with PLACES decimals."""
        u = 10**places
        return F(lo) + F(self.below(int((F(hi) - F(lo)) * u) + 1), u)


def sphere_points(d):
    pts = []
    for x in range(-d, d + 1):
        for y in range(-d, d + 1):
            z2 = d * d - x * x - y * y
            if z2 >= 0 and math.isqrt(z2) ** 2 == z2:
                z = math.isqrt(z2)
                pts += [(x, y, z)] if z == 0 else [(x, y, z), (x, y, -z)]
    return pts


# Rational unit directions (a, b, c) / d from Pythagorean quadruples.
QUADS = [(p, d) for d in (1, 3, 7, 9) for p in sphere_points(d)]


def random_ball(rng, spread=4):
    return (tuple(rng.dec(-spread, spread) for _ in range(3)), rng.dec("0.5", 3))


def along(c, p, d, s):
    """c + s p / d, with s a multiple of d / 10 so the result is a decimal."""
    return tuple(ci + s * pi / d for ci, pi in zip(c, p))


def make(seed):
    rng = Rng(seed)
    kind = KINDS[seed % len(KINDS)]
    n = 4 + rng.below(9)
    balls = []
    if kind == "nested":
        c, R = random_ball(rng, 2)[0], rng.dec(3, 5)
        balls.append((c, R))
        for _ in range(1 + rng.below(3)):  # strictly inside: |ci - c| + ri < R
            p, d = rng.pick(QUADS)
            m = rng.below(int(R / 2 * 10 / d) + 1)
            s = F(m * d, 10)  # |ci - c| = s <= R / 2, ri < R / 2: strictly inside
            balls.append((along(c, p, d, s), rng.dec("0.1", R / 2 - F(1, 10))))
        if rng.below(2):  # a ball inside the first inner one as well
            ci, ri = balls[1]
            balls.append((ci, ri / 2))
    elif kind == "internal":
        for _ in range(1 + rng.below(2)):
            c, R = (tuple(rng.dec(-2, 2, 0) for _ in range(3)), rng.dec(2, 4))
            p, d = rng.pick(QUADS)
            s = F(d * (1 + rng.below(9)), 10)  # |ci - c| = s, a multiple of d / 10
            while s >= R:
                s /= 2
            balls += [(c, R), (along(c, p, d, s), R - s)]
        way = rng.below(4)
        if way == 0:  # the four balls, moved: vertex at the small centre, t = -2
            o = tuple(rng.dec(-1, 1, 0) for _ in range(3))
            balls = [(o, F(2))] + [(tuple(oi + (1 if k == j else 0) for k, oi in enumerate(o)), F(3))
                                   for j in range(3)] + balls[:2]
        elif way == 1:  # one small ball internally tangent to 3 or 4 larger ones in random directions
            o, r = tuple(rng.dec(-1, 1) for _ in range(3)), rng.dec("0.5", 2)
            balls = [(o, r)]
            for _ in range(3 + rng.below(2)):
                p, d = rng.pick(QUADS)
                s = F(d * (1 + rng.below(20)), 10)
                balls.append((along(o, p, d, s), s + r))
    elif kind == "tangent":
        for _ in range(1 + rng.below(3)):
            c, r1 = random_ball(rng, 3)
            p, d = rng.pick(QUADS)
            s = F(d * (6 + rng.below(30)), 10)  # |ci - cj| = s = r1 + r2
            while s <= r1:
                r1 /= 2
            balls += [(c, r1), (along(c, p, d, s), s - r1)]
    elif kind == "coincident":
        for _ in range(1 + rng.below(3)):
            c = tuple(rng.dec(-3, 3) for _ in range(3))
            r = rng.dec("0.5", 2)
            balls += [(c, r), (c, r + rng.dec("0.1", 2))]
    elif kind in ("grid", "jittered"):
        lat = rng.pick(["sc", "bcc", "fcc"])
        basis = {"sc": [(0, 0, 0)], "bcc": [(0, 0, 0), (F(1, 2),) * 3],
                 "fcc": [(0, 0, 0), (0, F(1, 2), F(1, 2)), (F(1, 2), 0, F(1, 2)), (F(1, 2), F(1, 2), 0)]}[lat]
        a = rng.pick([F(2), F("2.5"), F("3.1")])
        sites = [tuple((i + b[k]) * a for k, i in enumerate(ijk)) for ijk in
                 [(i, j, k) for i in range(3) for j in range(3) for k in range(3)] for b in basis]
        sites = sorted(set(sites))
        for i in range(len(sites) - 1, 0, -1):
            j = rng.below(i + 1)
            sites[i], sites[j] = sites[j], sites[i]
        radii = [a * F(2, 5)] if rng.below(2) else [a * F(2, 5), a * F(3, 10)]
        amp = F(rng.pick(["1e-12", "1e-9", "1e-6", "1e-3"])) if kind == "jittered" else F(0)
        for s in sites[:n]:
            if amp:
                s = tuple(x + amp * (rng.below(2001) - 1000) / 1000 for x in s)
            balls.append((s, rng.pick(radii)))
    else:  # cospherical
        d = rng.pick([3, 5, 6, 7, 9])
        pts = sphere_points(d)
        o = tuple(rng.dec(-1, 1) for _ in range(3))
        rho = F(d) - F(1)
        unequal = rng.below(2)
        k = min(n, 4 + rng.below(5))
        for _ in range(k):
            p = rng.pick(pts)
            q = rng.pick([F(1), F("1.1"), F("1.2")]) if unequal else F(1)
            c = tuple(oi + q * pi for oi, pi in zip(o, p))
            if all(c != b[0] for b in balls):
                balls.append((c, q * d - rho))
    seen, unique = set(), []
    for b in balls:  # identical balls are an input error (E104), not a degenerate case
        if b not in seen:
            seen.add(b)
            unique.append(b)
    while len(unique) < n:  # fill with random balls around the group
        b = random_ball(rng, 5)
        if b not in seen:
            seen.add(b)
            unique.append(b)
    return kind, unique[:12]


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    seed0, count, out = int(argv[0]), int(argv[1]), Path(argv[2])
    out.mkdir(parents=True, exist_ok=True)
    for seed in range(seed0, seed0 + count):
        kind, balls = make(seed)
        with open(out / ("%d.xyzr" % seed), "w") as f:
            f.write("# degenerate_fuzz seed %d: %s, %d balls\n" % (seed, kind, len(balls)))
            for c, r in balls:
                f.write("%s %s %s %s\n" % (dec(c[0]), dec(c[1]), dec(c[2]), dec(r)))


if __name__ == "__main__":
    main(sys.argv[1:])
