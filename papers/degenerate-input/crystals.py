#!/usr/bin/env python3
"""Degenerate inputs for issue 27, written as exact decimals (XYZR).

usage: crystals.py lattice KIND N [--a A] [--r R] [--jitter AMP] [--seed S] [-o FILE]
       crystals.py random KIND N [--a A] [--r R] [--seed S] [-o FILE]
       crystals.py cospherical K [--unequal] [-o FILE]
       crystals.py suite OUT_DIR [--sizes K]

lattice   KIND = fcc | bcc | sc, N x N x N unit cells of edge A (a decimal
          string), every ball of radius R: the cells' basis sites only (4, 2
          or 1 per cell: fcc 4 N^3 balls, bcc 2 N^3, sc N^3), so the block's
          far faces are open. Defaults: fcc A = 3.61, R = 1.28 (copper; the
          spheres overlap slightly: A sqrt(2)/4 = 1.276); bcc A = 2.87,
          R = 1.24 (iron: A sqrt(3)/4 = 1.243); sc A = 3.35, R = 1.68
          (polonium: A/2 = 1.675). With --jitter AMP (a decimal: 1e-12,
          1e-9, 1e-6, 1e-3) each coordinate moves by m AMP / 1000 for an
          integer m uniform in [-1000, 1000] (splitmix64 from --seed), written
          exactly: AMP = 1e-12 gives 15 decimals.
random    the same count, box [0, N A)^3 and radius as `lattice KIND N`,
          centres uniform in thousandths (splitmix64 from --seed), distinct.
cospherical  K balls whose centres lie on one sphere, all tangent to the
          sphere of radius rho = d - 1.5 about the common centre: centre
          O + q_j p_j for the integer points p_j of x^2+y^2+z^2 = d^2 (the
          smallest d in 3..60 with exactly K points, else the smallest with
          more, the first K in a fixed shuffled order; d = 11 has exactly 78)
          and radius r_j = q_j d - rho, so
          |c_j - O| = rho + r_j exactly. q_j = 1 (equal radii: r = 1.5) or
          with --unequal q_j cycles through 1, 1.05, 1.1, 1.2 (radii 1.5,
          2.05, 2.6, 3.7): one vertex of degree K at O, t = rho (9.5 for K = 78).
suite     writes the whole benchmark set of papers/degenerate-input/README.md
          into OUT_DIR: for each of fcc, bcc, sc and each size (about 500,
          1372, 4000 and 10^4 balls; --sizes K keeps the first K sizes)
          KIND-COUNT-exact, -j1e-12, -j1e-9, -j1e-6, -j1e-3 and -random, and
          cospherical-78-equal, cospherical-78-unequal.

Every point is shifted by (10.25, -3.7, 0.125) so no coordinate is trivially
zero. Every number is computed as a Fraction and written as its exact
decimal (no binary floating point). Standard library only.
"""
import argparse
import sys
from fractions import Fraction
from pathlib import Path

# The exact decimal writer (and Pythagorean points) of the corpus generator:
# one copy for every script that writes exact inputs.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "corpus" / "equal-radius"))
from generate import dec, sphere_points  # noqa: E402 (corpus/equal-radius/generate.py)

ORIGIN = (Fraction("10.25"), Fraction("-3.7"), Fraction("0.125"))
DEFAULTS = {"fcc": ("3.61", "1.28"), "bcc": ("2.87", "1.24"), "sc": ("3.35", "1.68")}
BASIS = {
    "sc": [(0, 0, 0)],
    "bcc": [(0, 0, 0), (Fraction(1, 2),) * 3],
    "fcc": [(0, 0, 0), (0, Fraction(1, 2), Fraction(1, 2)),
            (Fraction(1, 2), 0, Fraction(1, 2)), (Fraction(1, 2), Fraction(1, 2), 0)],
}
# Cells per side for about 500, 1372, 4000 and 10^4 balls (fcc 4 N^3, bcc 2 N^3, sc N^3).
SIZES = {"fcc": [5, 7, 10, 14], "bcc": [6, 9, 13, 17], "sc": [8, 11, 16, 22]}
JITTERS = ["1e-12", "1e-9", "1e-6", "1e-3"]
MASK = (1 << 64) - 1


class SplitMix64:
    def __init__(self, seed):
        self.state = seed & MASK

    def next(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return z ^ (z >> 31)

    def below(self, n):
        return self.next() % n  # bias below 2^-40 for the n used here


def write(path, comment, balls):
    out = sys.stdout if path in (None, "-") else open(path, "w")
    try:
        for line in comment:
            out.write("# " + line + "\n")
        for (x, y, z), r in balls:
            out.write("%s %s %s %s\n" % (dec(x + ORIGIN[0]), dec(y + ORIGIN[1]), dec(z + ORIGIN[2]), dec(r)))
    finally:
        if out is not sys.stdout:
            out.close()


def lattice_sites(kind, n, a):
    return [((i + b[0]) * a, (j + b[1]) * a, (k + b[2]) * a)
            for i in range(n) for j in range(n) for k in range(n) for b in BASIS[kind]]


def lattice(kind, n, a, r, jitter=None, seed=1):
    a, r = Fraction(a), Fraction(r)
    sites = lattice_sites(kind, n, a)
    what = "%s crystal, %d^3 unit cells, a = %s, r = %s, %d balls" % (kind, n, dec(a), dec(r), len(sites))
    if jitter is None:
        return [what, "exact lattice sites (shifted by (10.25,-3.7,0.125))"], [(s, r) for s in sites]
    amp = Fraction(jitter)
    rng = SplitMix64(seed)
    step = amp / 1000
    moved = [tuple(c + (rng.below(2001) - 1000) * step for c in s) for s in sites]
    return [what, "every coordinate jittered by m * %s, m uniform in [-1000, 1000], splitmix64 seed %d"
            % (dec(step), seed)], [(s, r) for s in moved]


def random_like(kind, n, a, r, seed=1):
    a, r = Fraction(a), Fraction(r)
    count = len(BASIS[kind]) * n**3
    edge = n * a * 1000  # thousandths
    assert edge.denominator == 1, "the box edge must be a whole number of thousandths"
    edge = int(edge)
    rng = SplitMix64(seed)
    seen, pts = set(), []
    while len(pts) < count:
        p = tuple(Fraction(rng.below(edge), 1000) for _ in range(3))
        if p not in seen:
            seen.add(p)
            pts.append(p)
    return ["%d uniform random balls of radius %s in [0, %s)^3 (the box and density of the %s crystal"
            " of %d^3 cells), thousandths, splitmix64 seed %d" % (count, dec(r), dec(n * a), kind, n, seed)], \
        [(p, r) for p in pts]


def cospherical(k, unequal=False, seed=7):
    counts = {d: len(sphere_points(d)) for d in range(3, 61)}
    exact = [d for d in counts if counts[d] == k]
    enough = [d for d in counts if counts[d] >= k]
    if not enough:
        raise ValueError("no integer sphere of radius <= 60 has %d points" % k)
    d = exact[0] if exact else enough[0]
    pts = sphere_points(d)
    if len(pts) > k:  # a fixed shuffle, then the first k
        rng = SplitMix64(seed)
        for i in range(len(pts) - 1, 0, -1):
            j = rng.below(i + 1)
            pts[i], pts[j] = pts[j], pts[i]
        pts = sorted(pts[:k])
    rho = d - Fraction("1.5")
    qs = [Fraction(1)] if not unequal else [Fraction(s) for s in ("1", "1.05", "1.1", "1.2")]
    balls = []
    for j, p in enumerate(pts):
        q = qs[j % len(qs)]
        balls.append((tuple(q * c for c in p), q * d - rho))
    return ["%d balls tangent to the sphere of radius %s about (10.25,-3.7,0.125): centres q_j p_j for integer"
            " points p_j with |p_j| = %d, radius q_j %d - %s, q_j in {%s}" %
            (k, dec(rho), d, d, dec(rho), ", ".join(dec(q) for q in qs)),
            "one Voronoi vertex of degree %d at the common centre, t = %s" % (k, dec(rho))], balls


def suite(out_dir, sizes):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    names = []
    for kind in ("fcc", "bcc", "sc"):
        a, r = DEFAULTS[kind]
        for n in SIZES[kind][:sizes]:
            count = len(BASIS[kind]) * n**3
            base = "%s-%d" % (kind, count)
            variants = [("exact", lambda: lattice(kind, n, a, r))]
            variants += [("j" + j, (lambda j=j: lattice(kind, n, a, r, jitter=j, seed=count)))
                         for j in JITTERS]
            variants += [("random", lambda: random_like(kind, n, a, r, seed=count))]
            for tag, make in variants:
                name = "%s-%s.xyzr" % (base, tag)
                comment, balls = make()
                write(out / name, comment, balls)
                names.append(name)
    for tag, unequal in (("equal", False), ("unequal", True)):
        name = "cospherical-78-%s.xyzr" % tag
        comment, balls = cospherical(78, unequal)
        write(out / name, comment, balls)
        names.append(name)
    return names


def main(argv):
    p = argparse.ArgumentParser(description="exact-decimal degenerate inputs (issue 27)",
                                usage=__doc__.split("\n\n")[1])
    sub = p.add_subparsers(dest="cmd", required=True)
    for cmd in ("lattice", "random"):
        s = sub.add_parser(cmd)
        s.add_argument("kind", choices=sorted(BASIS))
        s.add_argument("n", type=int)
        s.add_argument("--a")
        s.add_argument("--r")
        s.add_argument("--seed", type=int, default=1)
        s.add_argument("-o", dest="out")
        if cmd == "lattice":
            s.add_argument("--jitter")
    s = sub.add_parser("cospherical")
    s.add_argument("k", type=int)
    s.add_argument("--unequal", action="store_true")
    s.add_argument("-o", dest="out")
    s = sub.add_parser("suite")
    s.add_argument("out_dir")
    s.add_argument("--sizes", type=int, default=4, help="how many of the four sizes (default 4)")
    args = p.parse_args(argv)
    if args.cmd == "suite":
        names = suite(args.out_dir, args.sizes)
        print("wrote %d files into %s" % (len(names), args.out_dir))
        return
    if args.cmd == "cospherical":
        comment, balls = cospherical(args.k, args.unequal)
    else:
        a = args.a or DEFAULTS[args.kind][0]
        r = args.r or DEFAULTS[args.kind][1]
        if args.cmd == "lattice":
            comment, balls = lattice(args.kind, args.n, a, r, args.jitter, args.seed)
        else:
            comment, balls = random_like(args.kind, args.n, a, r, args.seed)
    write(args.out, comment, balls)


if __name__ == "__main__":
    main(sys.argv[1:])
