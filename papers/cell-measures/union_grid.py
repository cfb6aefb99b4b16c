#!/usr/bin/env python3
"""Independent estimates of the union of the probe-expanded balls, to check
that vorball's per-atom volumes and SAS areas add up to it.

usage: union_grid.py BALLS [--probe P] [--spacing H ...] [--points N]

BALLS: one ball a line, 'x y z r' (the first four numbers; '#' lines and
extra columns ignored), e.g. the balls compare_voronota.py writes.

  volume: the number of grid points (spacing H, cell centres) inside some
          expanded ball times H^3, slab by slab in z (numpy), for each H;
  area:   N points spread evenly (golden spiral) on every expanded sphere,
          the fraction not inside another expanded ball times 4 pi r^2
          (Shrake-Rupley with many points).
Neither is a bound: the point is agreement to their own error (volume ~
H x surface, area ~ 1/sqrt(N) per sphere) with vorball's enclosures."""
import argparse
import math
import sys

import numpy as np


def read_balls(path):
    rows = []
    with open(path) as f:
        for line in f:
            t = line.split("#", 1)[0].split()
            if len(t) >= 4:
                rows.append([float(v) for v in t[:4]])
    return np.array(rows, dtype=np.float64)


def union_volume(c, r, h):
    lo = (c - r[:, None]).min(axis=0) - h
    hi = (c + r[:, None]).max(axis=0) + h
    n = np.ceil((hi - lo) / h).astype(int)
    xs = lo[0] + h * (np.arange(n[0]) + 0.5)
    ys = lo[1] + h * (np.arange(n[1]) + 0.5)
    count = 0
    for kz in range(n[2]):
        z = lo[2] + h * (kz + 0.5)
        dz2 = r * r - (c[:, 2] - z) ** 2
        live = np.nonzero(dz2 > 0)[0]
        if live.size == 0:
            continue
        slab = np.zeros((n[0], n[1]), dtype=bool)
        for i in live:
            rr = math.sqrt(dz2[i])
            i0 = max(int((c[i, 0] - rr - lo[0]) / h) - 1, 0)
            i1 = min(int((c[i, 0] + rr - lo[0]) / h) + 2, n[0])
            j0 = max(int((c[i, 1] - rr - lo[1]) / h) - 1, 0)
            j1 = min(int((c[i, 1] + rr - lo[1]) / h) + 2, n[1])
            dx = (xs[i0:i1] - c[i, 0]) ** 2
            dy = (ys[j0:j1] - c[i, 1]) ** 2
            slab[i0:i1, j0:j1] |= dx[:, None] + dy[None, :] < dz2[i]
        count += int(slab.sum())
    return count * h ** 3


def union_area(c, r, npts):
    k = np.arange(npts) + 0.5
    zz = 1.0 - 2.0 * k / npts
    phi = math.pi * (3.0 - math.sqrt(5.0)) * k
    rho = np.sqrt(1.0 - zz * zz)
    unit = np.stack([rho * np.cos(phi), rho * np.sin(phi), zz], axis=1)
    total = 0.0
    for i in range(len(r)):
        d = np.linalg.norm(c - c[i], axis=1)
        near = np.nonzero((d < r + r[i]) & (np.arange(len(r)) != i))[0]
        p = c[i] + r[i] * unit
        free = np.ones(npts, dtype=bool)
        for j in near:
            free &= ((p - c[j]) ** 2).sum(axis=1) >= r[j] * r[j]
        total += free.mean() * 4.0 * math.pi * r[i] ** 2
    return total


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("balls")
    ap.add_argument("--probe", type=float, default=1.4)
    ap.add_argument("--spacing", type=float, nargs="+", default=[0.2, 0.1, 0.05])
    ap.add_argument("--points", type=int, default=20000)
    a = ap.parse_args()
    b = read_balls(a.balls)
    if len(b) == 0:
        sys.exit("union_grid.py: no balls in " + a.balls)
    c, r = b[:, :3], b[:, 3] + a.probe
    for h in a.spacing:
        print(f"volume\tspacing {h}\t{union_volume(c, r, h):.4f}")
    print(f"area\tpoints {a.points}\t{union_area(c, r, a.points):.4f}")


if __name__ == "__main__":
    main()
