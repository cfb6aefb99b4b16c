#!/usr/bin/env python3
"""Periodic boxes against replicated open runs (issue 34).

  periodic_check.py gen CASE DIR    writes DIR/CASE.xyzr (the box's atoms),
                                    DIR/CASE.block.xyzr (the K x K x K copy,
                                    atom i of copy (dx,dy,dz) written as line
                                    (copy index) * n + i) and DIR/CASE.box
                                    (the --box numbers) and DIR/CASE.k (K)
  periodic_check.py cmp CASE DIR    compares DIR/CASE.periodic.tsv with
                                    DIR/CASE.block.tsv

Cases: fcc (one cubic unit cell of 4 balls, K = 5), random (40 balls in an
orthorhombic box, K = 3), triclinic (40 balls in a triclinic box, K = 3).

The comparison: every vertex of the open run of the block is mapped to
(atom, shift) members and to its canonical translate (the rule of
core/periodic/vb_periodic.h, written again here); those whose canonical
member of smallest id lies in the central copy are the periodic vertices,
provided their tangent spheres cannot reach out of the block (checked:
2 (t + Rmax) below the block's margin of (K - 1) / 2 box heights). That set
must equal the periodic file's, member lists exactly and points to 1e-9.
Exact decimals throughout (fractions), never through a double.
"""
import sys
from fractions import Fraction as F


def dec(q):
    """An exact decimal string of a fraction with a power-of-ten denominator."""
    q = F(q)
    s = "-" if q < 0 else ""
    q = abs(q)
    d = 0
    while (q * 10 ** d).denominator != 1:
        d += 1
    v = q * 10 ** d
    i = str(v.numerator)
    if d == 0:
        return s + i
    i = i.rjust(d + 1, "0")
    return s + i[:-d] + "." + i[-d:]



def lcg(seed):
    state = seed
    while True:
        state = (state * 6364136223846793005 + 1442695040888963407) % (1 << 64)
        yield state >> 11


def case_data(case):
    """(box rows, atoms [(x, y, z, r)], K) with exact fractions."""
    if case == "fcc":
        a = F(4)
        box = [(a, 0, 0), (0, a, 0), (0, 0, a)]
        basis = [(0, 0, 0), (F(1, 2), F(1, 2), 0), (F(1, 2), 0, F(1, 2)), (0, F(1, 2), F(1, 2))]
        o = (F(1, 10), F(2, 10), F(3, 10))
        atoms = [(o[0] + a * b[0], o[1] + a * b[1], o[2] + a * b[2], F(12, 10)) for b in basis]
        return box, atoms, 5
    if case == "random":
        box = [(F(9), 0, 0), (0, F(10), 0), (0, 0, F(11))]
    elif case == "triclinic":
        box = [(F(10), 0, 0), (F(25, 10), F(95, 10), 0), (F(-15, 10), F(2), F(105, 10))]
    else:
        raise SystemExit("unknown case " + case)
    rnd = lcg(34 if case == "random" else 3434)
    atoms = []
    while len(atoms) < 40:
        u = [F(next(rnd) % 1000, 1000) for _ in range(3)]
        r = F(8, 10) + F(next(rnd) % 700, 1000)
        p = tuple(sum(u[k] * box[k][a] for k in range(3)) for a in range(3))
        # Keep balls apart (no containment) modulo the box: 27 images.
        ok = True
        for q in atoms:
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for dz in (-1, 0, 1):
                        d2 = sum((p[a] - q[a] - dx * box[0][a] - dy * box[1][a] - dz * box[2][a]) ** 2
                                 for a in range(3))
                        if d2 < F(16, 10) ** 2:
                            ok = False
        if ok:
            atoms.append(p + (r,))
    return box, atoms, 3


def gen(case, d):
    box, atoms, k = case_data(case)
    with open(f"{d}/{case}.xyzr", "w") as f:
        for x, y, z, r in atoms:
            f.write(f"{dec(x)} {dec(y)} {dec(z)} {dec(r)}\n")
    h = k // 2
    with open(f"{d}/{case}.block.xyzr", "w") as f:
        for dx in range(-h, h + 1):
            for dy in range(-h, h + 1):
                for dz in range(-h, h + 1):
                    for x, y, z, r in atoms:
                        p = [c + dx * box[0][a] + dy * box[1][a] + dz * box[2][a]
                             for a, c in enumerate((x, y, z))]
                        f.write(f"{dec(p[0])} {dec(p[1])} {dec(p[2])} {dec(r)}\n")
    with open(f"{d}/{case}.box", "w") as f:
        if case == "triclinic":
            f.write(" ".join(dec(c) for row in box for c in row) + "\n")
        else:
            f.write(" ".join(dec(box[a][a]) for a in range(3)) + "\n")


def canonical(members):
    """The canonical translate of a member list [(id, (dx, dy, dz))]:
    (sorted members, the shift subtracted)."""
    low = min(m[0] for m in members)
    best = None
    for i, s in members:
        if i != low:
            continue
        cand = sorted((j, tuple(t[a] - s[a] for a in range(3))) for j, t in members)
        if best is None or cand < best[0]:
            best = (cand, s)
    return best


def read_tsv(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            cols = line.rstrip("\n").split("\t")
            out.append((cols[0], [float(c) for c in cols[1:5]]))
    return out


def parse_member(tok):
    i, s = tok.split("@")
    return int(i), tuple(int(c) for c in s.strip("()").split(","))


def cmp(case, d):
    box, atoms, k = case_data(case)
    n, h = len(atoms), k // 2
    fbox = [[float(c) for c in row] for row in box]
    rmax = max(float(a[3]) for a in atoms)
    # Heights of the box (the distance between opposite faces).
    import math

    def cross(u, v):
        return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])

    vol = abs(sum(fbox[0][a] * cross(fbox[1], fbox[2])[a] for a in range(3)))
    heights = [vol / math.sqrt(sum(c * c for c in cross(fbox[(e + 1) % 3], fbox[(e + 2) % 3])))
               for e in range(3)]
    shifts = [(dx, dy, dz) for dx in range(-h, h + 1) for dy in range(-h, h + 1)
              for dz in range(-h, h + 1)]
    block = {}
    tmax = 0.0
    for ids, p in read_tsv(f"{d}/{case}.block.tsv"):
        members = [(int(e) % n, shifts[int(e) // n]) for e in ids.split(",")]
        canon, s = canonical(members)
        if s != (0, 0, 0):
            continue
        tmax = max(tmax, p[3])
        key = ",".join(f"{i}@({t[0]},{t[1]},{t[2]})" for i, t in canon)
        if key in block:
            raise SystemExit(f"FAIL: {case}: the block holds {key} twice")
        block[key] = p
    if 2 * (tmax + rmax) >= h * min(heights):
        raise SystemExit(f"FAIL: {case}: block too thin to decide (t up to {tmax})")
    per = {}
    for ids, p in read_tsv(f"{d}/{case}.periodic.tsv"):
        members = [parse_member(t) for t in ids.replace("),", ")\n").split("\n")]
        canon, s = canonical(members)
        key = ",".join(f"{i}@({t[0]},{t[1]},{t[2]})" for i, t in canon)
        if key != ids or s != (0, 0, 0):
            raise SystemExit(f"FAIL: {case}: {ids} is not canonical ({key})")
        if key in per:
            raise SystemExit(f"FAIL: {case}: {key} written twice")
        per[key] = p
    bad = 0
    for key in sorted(set(block) | set(per)):
        if key not in per:
            print(f"FAIL: {case}: missing in the periodic file: {key} {block[key]}")
            bad += 1
        elif key not in block:
            print(f"FAIL: {case}: not in the block: {key} {per[key]}")
            bad += 1
        elif max(abs(a - b) for a, b in zip(block[key], per[key])) > 1e-9:
            print(f"FAIL: {case}: {key} at {per[key]}, the block's at {block[key]}")
            bad += 1
    if bad or not per:
        raise SystemExit(f"FAIL: {case}: {bad} difference(s), {len(per)} periodic vertices")
    print(f"ok: {case}: {len(per)} periodic vertices = the central copy of the "
          f"{k}x{k}x{k} block (largest t {tmax:.6g})")


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("gen", "cmp"):
        raise SystemExit(__doc__)
    (gen if sys.argv[1] == "gen" else cmp)(sys.argv[2], sys.argv[3])
