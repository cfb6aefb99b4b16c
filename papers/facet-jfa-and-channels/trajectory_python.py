#!/usr/bin/env python3
"""Per-frame certified Voronoi vertices and pore profiles of a trajectory,
through the vorball Python package, plotted.

usage: trajectory_python.py [TOPOLOGY [TRAJECTORY]] [--frames N] [--grid N]
                            [--device D] [--out DIR] [--no-plot]

TOPOLOGY defaults to corpus/data/ngl_md_ascii_trj.pdb (51 models of an MD
run). With MDAnalysis installed, frames come from it (mda.Universe(TOPOLOGY,
TRAJECTORY): any format it reads; positions are float32, which vorball reads
as their shortest decimals, i.e. the PDB's own numbers); without it, from
vorball.frames (the models of a file, or a DCD TRAJECTORY). Radii are
vorball's element table for the topology's atoms. One device is opened for
all frames (vorball.Engine). Writes OUT/frames.tsv (per frame: certified
vertices, completeness, channels, the longest channel's bottleneck and
length), OUT/profiles.tsv (the longest channel's clearance r along its
centreline s) and OUT/profiles.png (matplotlib if installed, else gnuplot
if on PATH, else no picture).
"""
import argparse
import os
import shutil
import subprocess
import sys

import vorball

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT = os.path.join(HERE, "..", "..", "corpus", "data", "ngl_md_ascii_trj.pdb")


def frames_of(top, traj, count):
    """(index, xyz, r) per frame: MDAnalysis if it is installed, else vorball."""
    try:
        import MDAnalysis as mda
    except ImportError:
        mda = None
    if mda is not None:
        u = mda.Universe(top, traj) if traj else mda.Universe(top)
        radii = vorball.read(top, water=True).r  # the element table, topology order
        if len(radii) != len(u.atoms):
            sys.exit("%s: %d atoms for MDAnalysis, %d for vorball (altlocs?)" % (
                top, len(u.atoms), len(radii)))
        for ts in u.trajectory[:count]:
            yield ts.frame, u.atoms.positions, radii
    else:
        for f in vorball.frames(top, traj, stop=count):
            yield f.index, f, None


def plot(out, rows, profiles):
    png = os.path.join(out, "profiles.png")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        plt = None
    if plt is not None:
        fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
        a.plot([r[0] for r in rows], [r[2] for r in rows], "o-", label="certified vertices")
        a.set_xlabel("frame")
        a.set_ylabel("certified vertices")
        a2 = a.twinx()
        a2.plot([r[0] for r in rows], [r[5] for r in rows], "s-", color="C1")
        a2.set_ylabel("bottleneck of the longest channel (A)")
        for frame, s, r in profiles:
            b.plot(s, r, label="frame %d" % frame)
        b.set_xlabel("distance along the centreline (A)")
        b.set_ylabel("clearance radius (A)")
        b.legend(fontsize="small")
        fig.tight_layout()
        fig.savefig(png, dpi=120)
        return png
    if shutil.which("gnuplot"):
        gp = os.path.join(out, "profiles.gp")
        with open(gp, "w") as f:
            f.write("set terminal png size 1100,400\nset output '%s'\nset multiplot layout 1,2\n"
                    "set xlabel 'frame'\nset ylabel 'certified vertices'\nset y2label "
                    "'bottleneck (A)'\nset y2tics\nplot '%s' u 1:3 w lp t 'vertices', '' u 1:6 "
                    "axes x1y2 w lp t 'bottleneck'\nunset y2tics\nunset y2label\n"
                    "set xlabel 'distance along the centreline (A)'\nset ylabel "
                    "'clearance radius (A)'\nplot '%s' u 3:4:1 w l lc var t 'profiles'\n"
                    "unset multiplot\n" % (png, os.path.join(out, "frames.tsv"),
                                          os.path.join(out, "profiles.tsv")))
        subprocess.run(["gnuplot", gp], check=True)
        return png
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("topology", nargs="?", default=DEFAULT)
    ap.add_argument("trajectory", nargs="?")
    ap.add_argument("--frames", type=int, default=10, help="frames to analyse (default 10)")
    ap.add_argument("--grid", type=int, default=64, help="channel grid side (default 64)")
    ap.add_argument("--device", default="auto")
    ap.add_argument("--out", default="trajectory_python_out")
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows, profiles = [], []
    with vorball.Engine(device=a.device) as eng:
        for index, xyz, r in frames_of(a.topology, a.trajectory, a.frames):
            res = eng.vertices(xyz, r)
            ch = eng.channels(xyz, r, grid=a.grid)
            t = ch.table
            nan = float("nan")  # no channel in this frame: a gap in the plot
            bott, length = (t["bottleneck_A"][0], t["length_A"][0]) if len(t) else (nan, nan)
            rows.append((index, len(ch.spheres), len(res.t), int(res.certificate.complete),
                         len(t), bott, length))
            if len(t):
                s, rr = ch.profile(0)
                profiles.append((index, s, rr))
            print("frame %d: %d certified vertices%s, %d channel(s), bottleneck %.3f A" % (
                index, len(res.t), " (complete)" if res.certificate.complete else "", len(t),
                bott))
        opened = eng.warnings  # the device's fallback warnings, if any
    with open(os.path.join(a.out, "frames.tsv"), "w") as f:
        f.write("# frame\tatoms\tvertices\tcomplete\tchannels\tbottleneck_A\tlength_A\n")
        for row in rows:
            f.write("%d\t%d\t%d\t%d\t%d\t%.4f\t%.4f\n" % row)
    with open(os.path.join(a.out, "profiles.tsv"), "w") as f:
        f.write("# frame\tchannel\ts_A\tr_A\n")
        for frame, s, rr in profiles:
            for x, y in zip(s, rr):
                f.write("%d\t1\t%.4f\t%.4f\n" % (frame, x, y))
            f.write("\n")
    for w in opened:
        print(w, file=sys.stderr)
    png = None if a.no_plot else plot(a.out, rows, profiles)
    print("wrote %s%s" % (os.path.join(a.out, "frames.tsv"), ", " + png if png else ""))


if __name__ == "__main__":
    main()
