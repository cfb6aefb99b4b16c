#!/usr/bin/env python3
"""Two runs of vorball cells against each other, enclosure by enclosure.

usage: compare_enclosures.py OLD.tsv NEW.tsv [--tolerance T] [--probe P]

OLD and NEW are both per-atom tables (-o: id ... volume volume_lo volume_hi sas
sas_lo sas_hi) or both contact tables (--contacts: id1 id2 area area_lo
area_hi). For every row (atoms by id, contacts by the pair) and value: the two
enclosures must intersect (both hold the exact value), and NEW's width must
stay within T * max(|value|, floor), the floor 1e-3 of the smallest expanded
ball's volume or area (radius P: a floor no larger than the one vorball uses).
The same rows must be present in both. Prints counts, the summed widths and
the worst relative widths; exits 1 on a miss."""
import argparse
import math
import sys


def table(path):
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f if l.strip() and not l.startswith("#")]
    head = lines[0].split("\t")
    return head, [dict(zip(head, l.split("\t"))) for l in lines[1:]]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--tolerance", type=float, default=1e-6)
    ap.add_argument("--probe", type=float, default=1.4)
    a = ap.parse_args()
    ho, old = table(a.old)
    hn, new = table(a.new)
    if ho != hn:
        sys.exit(f"compare_enclosures.py: the headers differ: {ho} and {hn}")
    vfloor = 1e-3 * 4.0 / 3.0 * math.pi * a.probe ** 3
    sfloor = 1e-3 * 4.0 * math.pi * a.probe ** 2
    if "area" in ho:
        key = lambda r: (r["id1"], r["id2"])
        values = [("area", sfloor)]
    else:
        key = lambda r: r["id"]
        values = [("volume", vfloor), ("sas", sfloor)]
    o = {key(r): r for r in old}
    n = {key(r): r for r in new}
    bad = 0
    if set(o) != set(n):
        print(f"rows only in OLD: {len(set(o) - set(n))}, only in NEW: {len(set(n) - set(o))}")
        bad += 1
    for v, fl in values:
        meet = wide = 0
        wsum_o = wsum_n = 0.0
        worst = (0.0, None)
        for k in sorted(set(o) & set(n), key=lambda k: [int(x) for x in (k if isinstance(k, tuple) else (k,))]):
            lo0, hi0 = float(o[k][v + "_lo"]), float(o[k][v + "_hi"])
            lo1, hi1 = float(n[k][v + "_lo"]), float(n[k][v + "_hi"])
            mid = float(n[k][v])
            if not (lo1 <= hi0 and lo0 <= hi1):
                print(f"  {v} {k}: NEW [{lo1!r}, {hi1!r}] misses OLD [{lo0!r}, {hi0!r}]")
                bad += 1
            else:
                meet += 1
            w = hi1 - lo1
            wsum_o += hi0 - lo0
            wsum_n += w
            rel = w / max(abs(mid), fl)
            if rel > a.tolerance:
                wide += 1
                bad += 1
            if rel > worst[0]:
                worst = (rel, k)
        print(f"{v}: {meet} of {len(set(o) & set(n))} enclosures meet; widths summed OLD {wsum_o:.3e} "
              f"NEW {wsum_n:.3e}; NEW wider than {a.tolerance:g} * max(|value|, {fl:.3g}): {wide}; "
              f"worst relative width {worst[0]:.2e} ({worst[1]})")
    print("OK" if bad == 0 else f"FAILED: {bad}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
