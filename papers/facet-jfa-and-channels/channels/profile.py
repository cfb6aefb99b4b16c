#!/usr/bin/env python3
"""Writes the radius profile of one channel of a `vorball channels --json`
table as TSV: coordinate along an axis, clearance radius, x, y, z.

    profile.py TABLE.json AXIS [CHANNEL] > profile.tsv

AXIS is x, y or z (gramicidin in 1grm_single_hole2.pdb lies along y), or
three comma-separated numbers "ux,uy,uz" for a direction; CHANNEL is the id
(default 1, the longest)."""
import json
import sys


def main():
    table, axis = sys.argv[1], sys.argv[2]
    want = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    if axis in ("x", "y", "z"):
        u = [1.0 if axis == a else 0.0 for a in "xyz"]
    else:
        u = [float(v) for v in axis.split(",")]
        n = sum(v * v for v in u) ** 0.5
        u = [v / n for v in u]
    frame = json.load(open(table))["frames"][0]
    ch = [c for c in frame["channels"] if c["id"] == want][0]
    print("# %s channel %d: length %.3f A, bottleneck %.3f A at %s" %
          (table, want, ch["length_A"], ch["bottleneck_A"], ch["bottleneck_at"]))
    print("# s\tradius\tx\ty\tz")
    for x, y, z, r in ch["centreline"]:
        print("%.3f\t%.3f\t%.3f\t%.3f\t%.3f" % (x * u[0] + y * u[1] + z * u[2], r, x, y, z))


if __name__ == "__main__":
    main()
