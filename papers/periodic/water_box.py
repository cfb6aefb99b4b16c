#!/usr/bin/env python3
"""A water box as GRO (issue 34's benchmark input): waters on a jittered
cubic lattice of 3.1 A (0.0336 molecules per A^3, liquid water's density),
each O with two H at 0.9572 A and 104.52 degrees in a random orientation,
coordinates in nm with 3 decimals (GRO's precision), the box on the last
line. Deterministic for a seed.

usage: water_box.py CELLS [SEED] > water.gro   (CELLS^3 waters, box 0.31 CELLS nm)
"""
import math
import random
import sys


def main():
    cells = int(sys.argv[1])
    rnd = random.Random(int(sys.argv[2]) if len(sys.argv) > 2 else 34)
    a = 0.31  # nm
    box = cells * a
    lines = []
    n = 0
    for i in range(cells):
        for j in range(cells):
            for k in range(cells):
                o = [(i + 0.5) * a + rnd.uniform(-0.03, 0.03), (j + 0.5) * a + rnd.uniform(-0.03, 0.03),
                     (k + 0.5) * a + rnd.uniform(-0.03, 0.03)]
                # A random orthonormal frame: the H's in its xy plane.
                while True:
                    u = [rnd.gauss(0, 1) for _ in range(3)]
                    if math.sqrt(sum(c * c for c in u)) > 1e-3:
                        break
                nu = math.sqrt(sum(c * c for c in u))
                u = [c / nu for c in u]
                t = [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0]
                v = [u[1] * t[2] - u[2] * t[1], u[2] * t[0] - u[0] * t[2], u[0] * t[1] - u[1] * t[0]]
                nv = math.sqrt(sum(c * c for c in v))
                v = [c / nv for c in v]
                half = math.radians(104.52) / 2
                h = [[o[d] + 0.09572 * (math.cos(half) * u[d] + s * math.sin(half) * v[d]) for d in range(3)]
                     for s in (1, -1)]
                res = (n // 3) + 1
                for name, p in (("OW", o), ("HW1", h[0]), ("HW2", h[1])):
                    n += 1
                    lines.append("%5d%-5s%5s%5d%8.3f%8.3f%8.3f" % (res % 100000, "SOL", name, n % 100000,
                                                                p[0], p[1], p[2]))
    print("water box, %d waters" % (cells ** 3))
    print("%5d" % n)
    print("\n".join(lines))
    print("%10.5f%10.5f%10.5f" % (box, box, box))


if __name__ == "__main__":
    main()
