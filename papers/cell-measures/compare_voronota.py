#!/usr/bin/env python3
"""Per-atom volumes and SAS areas: vorball cells against Voronota 1.29 on the
same balls.

usage: compare_voronota.py VORONOTA VORBALL INPUT [--probe P] [--out DIR]
                           [--threads N] [-- vorball cells options...]

1. `VORBALL cells INPUT --atoms DIR/atoms.tsv` gives vorball's values (their
   enclosures) and its sphere table; the balls (exact decimals as vorball read
   them, radii from its table) go to DIR/balls.txt as 'x y z r'.
2. `VORONOTA calculate-contacts --probe P --volumes-output DIR/voronota_volumes`
   reads those same balls on stdin (ids are the line numbers from 0, as
   vorball's); its contact lines 'i i area' are the SAS areas.
3. Per atom: volume and SAS from both, the difference, whether Voronota's
   value lies in vorball's enclosure; medians and largest differences, the
   atoms with the largest ones, sums, and the CPU time of each run (its
   children's getrusage: user + system).
Writes DIR/compare.tsv and prints the summary."""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import time


def run_timed(cmd, stdin=None, stdout=None):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    p = subprocess.run(cmd, stdin=stdin, stdout=stdout, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"compare_voronota.py: {' '.join(cmd)} failed ({p.returncode}): {p.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, p.stderr


def table(path):
    """Rows of a TSV past its '#' lines, as dicts by the header's names."""
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f if not l.startswith("#")]
    head = lines[0].split("\t")
    return [dict(zip(head, l.split("\t"))) for l in lines[1:] if l]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("voronota")
    ap.add_argument("vorball")
    ap.add_argument("input")
    ap.add_argument("--probe", default="1.4")
    ap.add_argument("--out", default="compare_out")
    ap.add_argument("--threads", default="1")
    ap.add_argument("--reuse", action="store_true",
                    help="summarise the files a previous run left in DIR (no runs, no times)")
    ap.add_argument("extra", nargs="*", help="more vorball cells options (after --)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    atoms = os.path.join(a.out, "atoms.tsv")
    cells = os.path.join(a.out, "vorball_cells.tsv")
    balls = os.path.join(a.out, "balls.txt")
    vol_v = os.path.join(a.out, "voronota_volumes")
    con_v = os.path.join(a.out, "voronota_contacts")

    if a.reuse:
        wall_b = cpu_b = wall_v = cpu_v = float("nan")
        err_b = ""
    else:
        wall_b, cpu_b, err_b = run_timed([a.vorball, "cells", a.input, "--probe", a.probe,
                                      "--threads", a.threads, "--atoms", atoms, "-o", cells,
                                      "--stats", "--quiet"] + a.extra)
        sph = table(atoms)
        with open(balls, "w") as f:
            for s in sph:
                f.write(f"{s['x']} {s['y']} {s['z']} {s['r']}\n")
        with open(balls) as fin, open(con_v, "w") as fout:
            wall_v, cpu_v, _ = run_timed([a.voronota, "calculate-contacts", "--probe", a.probe,
                                          "--volumes-output", vol_v], stdin=fin, stdout=fout)
    vv, sv = {}, {}
    with open(vol_v) as f:
        for l in f:
            t = l.split()
            if len(t) >= 2:
                vv[int(t[0])] = float(t[1])
    with open(con_v) as f:
        for l in f:
            t = l.split()
            if len(t) >= 3 and t[0] == t[1]:
                sv[int(t[0])] = float(t[2])
    rows = table(cells)
    out = []
    for row in rows:
        i = int(row["id"])
        b = {k: float(row[k]) for k in ("volume", "volume_lo", "volume_hi", "sas", "sas_lo", "sas_hi")}
        v, s = vv.get(i, 0.0), sv.get(i, 0.0)
        out.append((i, row, b, v, s))
    with open(os.path.join(a.out, "compare.tsv"), "w") as f:
        f.write("id\tchain\tresname\tresseq\tatom\tvolume\tvolume_width\tvoronota_volume\tdvolume"
                "\tvolume_in\tsas\tsas_width\tvoronota_sas\tdsas\tsas_in\n")
        for i, row, b, v, s in out:
            f.write(f"{i}\t{row['chain']}\t{row['resname']}\t{row['resseq']}\t{row['atom']}"
                    f"\t{b['volume']:.6f}\t{b['volume_hi'] - b['volume_lo']:.3g}\t{v:.6f}"
                    f"\t{v - b['volume']:.6f}\t{int(b['volume_lo'] <= v <= b['volume_hi'])}"
                    f"\t{b['sas']:.6f}\t{b['sas_hi'] - b['sas_lo']:.3g}\t{s:.6f}"
                    f"\t{s - b['sas']:.6f}\t{int(b['sas_lo'] <= s <= b['sas_hi'])}\n")

    def summary(name, key, vor):
        d = [vor(o) - o[2][key] for o in out]
        ad = [abs(x) for x in d]
        rel = [abs(x) / o[2][key] for x, o in zip(d, out) if o[2][key] > 1e-9]
        w = [o[2][key + "_hi"] - o[2][key + "_lo"] for o in out]
        relw = [wi / o[2][key] for wi, o in zip(w, out) if o[2][key] > 1e-9]
        worst = sorted(range(len(out)), key=lambda k: -ad[k])[:5]
        print(f"{name}: vorball sum {sum(o[2][key] for o in out):.4f} "
              f"[{sum(o[2][key + '_lo'] for o in out):.6f}, {sum(o[2][key + '_hi'] for o in out):.6f}], "
              f"Voronota sum {sum(vor(o) for o in out):.4f}")
        print(f"  |Voronota - vorball|: median {statistics.median(ad):.4g}, max {max(ad):.4g}; "
              f"relative median {statistics.median(rel):.3g}, max {max(rel):.3g}; "
              f"Voronota inside vorball's enclosure: {sum(1 for o in out if o[2][key + '_lo'] <= vor(o) <= o[2][key + '_hi'])}/{len(out)}")
        print(f"  vorball widths: median {statistics.median(w):.3g} (relative {statistics.median(relw):.3g}), "
              f"max {max(w):.3g} (relative {max(relw):.3g})")
        for k in worst:
            i, row, b, v, s = out[k]
            print(f"    atom {i} {row['resname']}{row['resseq']} {row['atom']}: vorball {b[key]:.6f} "
                  f"[{b[key + '_lo']:.6f}, {b[key + '_hi']:.6f}], Voronota {vor(out[k]):.6f}, "
                  f"diff {d[k]:+.6f}")

    print(f"{len(out)} atoms; balls in {balls}")
    summary("volume", "volume", lambda o: o[3])
    summary("sas", "sas", lambda o: o[4])
    last = [l for l in err_b.splitlines() if l.startswith("cells:")]
    print(f"vorball cells --threads {a.threads}: wall {wall_b:.2f} s, CPU {cpu_b:.2f} s"
          + (f" ({last[-1]})" if last else ""))
    print(f"Voronota calculate-contacts --probe {a.probe} --volumes-output: wall {wall_v:.2f} s, "
          f"CPU {cpu_v:.2f} s")


if __name__ == "__main__":
    main()
