#!/usr/bin/env python3
"""Turns a run.sh table into Markdown and a plot.

usage: make_table.py results/NAME.tsv      writes results/NAME.md and results/NAME.png

The Markdown has every row of the TSV (time, peak RSS in MiB, vertices, the header's
'complete', cover quadruples, exact evaluations, verify --arcs, CGAL), then per
crystal size the ratio of each exact or jittered lattice's time to its random
counterpart's (issue 27's target: at most 2). The plot: wall time against balls,
log-log, one panel per lattice (fcc, bcc, sc: exact, each jitter, random) and one
for the Song 2022 sets and the cospherical balls; a run past its limit is drawn at
the limit with an open marker. matplotlib if Python has it, else gnuplot (a .gp
script and its data are kept beside the PNG). Standard library otherwise.
"""
import csv
import shutil
import subprocess
import sys
from pathlib import Path

TAGS = ["exact", "j1e-12", "j1e-9", "j1e-6", "j1e-3", "random"]
KINDS = ["fcc", "bcc", "sc"]


def read(path):
    head, rows = [], []
    with open(path) as f:
        lines = [l for l in f]
    head = [l[2:].rstrip("\n") for l in lines if l.startswith("# ")]
    body = [l for l in lines if not l.startswith("#")]
    for r in csv.DictReader(body, delimiter="\t"):
        rows.append(r)
    return head, rows


def seconds(r):
    """(seconds, timed_out) or None for rows that did not run."""
    w = r["wall_s"]
    if w.startswith(">"):
        return float(w[1:]), True
    try:
        return float(w), False
    except ValueError:
        return None


def mib(kib):
    try:
        return "%.0f" % (int(kib) / 1024)
    except ValueError:
        return kib


def num(s):
    try:
        return "{:,}".format(int(s))
    except ValueError:
        return s


def tag_of(r):
    name = r["input"]
    for t in TAGS:
        if name.endswith("-" + t):
            return t
    return None


def markdown(head, rows):
    out = ["Measured by `run.sh` (" + "; ".join(head) + ").", ""]
    cols = ["set", "input", "balls", "status", "time (s)", "peak RSS (MiB)", "vertices", "complete",
            "cover quadruples", "exact evals", "verify --arcs", "CGAL", "CGAL (s)"]
    out.append("| " + " | ".join(cols) + " |")
    out.append("|" + "---|" * len(cols))
    for r in rows:
        status = r["status"]
        out.append("| " + " | ".join([
            r["set"], r["input"], num(r["balls"]), status, r["wall_s"], mib(r["peak_rss_kib"]),
            num(r["vertices"]), r["complete"], num(r["cover_quadruples"]), num(r["exact_evals"]),
            r["arcs"], r["cgal"], r["cgal_s"]]) + " |")
    # Ratio to the random counterpart of the same lattice and size.
    by = {}
    for r in rows:
        t = tag_of(r)
        if r["set"] in KINDS and t:
            by.setdefault((r["set"], int(r["balls"])), {})[t] = r
    if by:
        out += ["", "Time over the random counterpart's (same count, box and radius; issue 27's target"
                " is at most 2; '>' where the run hit its limit, '-' where it was skipped):", ""]
        out.append("| lattice | balls | random (s) | " + " | ".join(TAGS[:-1]) + " |")
        out.append("|---|---|---|" + "---|" * (len(TAGS) - 1))
        for (kind, n) in sorted(by, key=lambda k: (KINDS.index(k[0]), k[1])):
            d = by[(kind, n)]
            base = seconds(d["random"]) if "random" in d else None
            cells = []
            for t in TAGS[:-1]:
                s = seconds(d[t]) if t in d else None
                if s is None or base is None or base[0] <= 0:
                    cells.append("-")
                else:
                    q = s[0] / base[0]
                    cells.append("%s%.*f" % (">" if s[1] else "", 1 if q < 10 else 0, q))
            out.append("| %s | %s | %s | %s |" % (kind, num(str(n)), d["random"]["wall_s"] if "random" in d else "-",
                                                  " | ".join(cells)))
    return "\n".join(out) + "\n"


def series(rows):
    """{panel: {label: [(balls, seconds, timed_out)]}}"""
    panels = {k: {} for k in KINDS}
    panels["Song 2022 and cospherical"] = {}
    for r in rows:
        s = seconds(r)
        if s is None:
            continue
        if r["set"] in KINDS:
            panel, label = r["set"], tag_of(r)
        else:
            panel, label = "Song 2022 and cospherical", r["set"]
        panels[panel].setdefault(label, []).append((int(r["balls"]), s[0], s[1]))
    return panels


def plot_matplotlib(panels, png, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    for ax, (name, lines) in zip(axes.flat, panels.items()):
        for label, pts in lines.items():
            pts.sort()
            done = [(n, s) for n, s, t in pts if not t]
            p = ax.plot([n for n, _ in done], [s for _, s in done], "o-" if name in KINDS else "o",
                        label=label, ms=4)
            late = [(n, s) for n, s, t in pts if t]
            if late:
                ax.plot([n for n, _ in late], [s for _, s in late], "o", mfc="none", color=p[0].get_color())
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(name)
        ax.set_xlabel("balls")
        ax.set_ylabel("wall time (s)")
        ax.grid(True, which="both", alpha=0.3)
        if lines:
            ax.legend(fontsize=7)
    fig.suptitle(title + " (open markers: past the time limit)", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def plot_gnuplot(panels, png, title):
    gp = png.with_suffix(".gp")
    data = png.with_suffix(".plotdata")
    blocks, plots = [], []
    k = 0
    for name, lines in panels.items():
        cmds = []
        for colour, (label, pts) in enumerate(lines.items(), 1):
            pts.sort()
            blocks.append("# %s / %s\n" % (name, label) +
                          "".join("%d %g %d\n" % (n, s, t) for n, s, t in pts) + "\n\n")
            style = "linespoints" if name in KINDS else "points"
            cmds.append("'%s' index %d using 1:($3==0?$2:1/0) with %s lc %d pt 7 ps 0.6 title '%s'"
                        % (data.name, k, style, colour, label))
            cmds.append("'%s' index %d using 1:($3==1?$2:1/0) with points lc %d pt 6 ps 1 notitle"
                        % (data.name, k, colour))
            k += 1
        plots.append((name, cmds))
    data.write_text("".join(blocks))
    script = ["set terminal pngcairo size 1100,850 font ',9'" if terminal_ok("pngcairo") else
              "set terminal png size 1100,850",
              "set output '%s'" % png.name, "set termoption noenhanced",
              "set multiplot layout 2,2 title \"%s (open circles: past the time limit)\"" % title.replace('"', "'"),
              "set logscale xy", "set xlabel 'balls'", "set ylabel 'wall time (s)'", "set grid",
              "set key top left font ',7'"]
    for name, cmds in plots:
        script.append("set title '%s'" % name)
        if cmds:
            script.append("set xrange [300:20000]" if name in KINDS else "set autoscale x")
            script.append("set autoscale y")
            script.append("plot " + ", ".join(cmds))
        else:  # an empty panel: a line outside fixed ranges
            script += ["set xrange [100:100000]", "set yrange [0.01:100]", "plot 1e9 notitle"]
    script.append("unset multiplot")
    gp.write_text("\n".join(script) + "\n")
    subprocess.run(["gnuplot", gp.name], cwd=png.parent, check=True)


def terminal_ok(name):
    try:
        out = subprocess.run(["gnuplot", "-e", "set terminal"], capture_output=True, text=True).stderr
        return name in out
    except OSError:
        return False


def main(argv):
    if len(argv) != 1:
        sys.exit(__doc__)
    tsv = Path(argv[0])
    head, rows = read(tsv)
    md = tsv.with_suffix(".md")
    md.write_text(markdown(head, rows))
    png = tsv.with_suffix(".png")
    title = tsv.stem + ": " + (head[1] if len(head) > 1 else "")
    panels = series(rows)
    try:
        import matplotlib  # noqa: F401
        have_matplotlib = True
    except ImportError:
        have_matplotlib = False
    if have_matplotlib:
        plot_matplotlib(panels, png, title)
    elif shutil.which("gnuplot"):
        plot_gnuplot(panels, png, title)
    else:
        print("make_table.py: neither matplotlib nor gnuplot: no plot", file=sys.stderr)
        print("wrote %s" % md)
        return
    print("wrote %s and %s" % (md, png))


if __name__ == "__main__":
    main(sys.argv[1:])
