#!/usr/bin/env python3
"""Turns the JSON lines of run_bench.sh into results/table1.md (ours beside
the paper's Table 1) and results/fig13.dat + fig13.png (samples vs vertices,
gnuplot). usage: make_report.py RESULTS_DIR"""
import glob
import json
import os
import subprocess
import sys

# Table 1 of the seed paper (seconds; NVIDIA Quadro 6000, 2012).
PAPER = {
    "1crn-PDB (327)": [2.02, 3.06, 3.85, 4.21],
    "1crn-PQR (642)": [3.85, 5.83, 7.05, 7.82],
    "1bh8-PQR (2161)": [23.3, 35.4, 41.2, 45.9],
    "1JD0-PDB (4195)": [50.2, 81.4, 93.6, 102.0],
}
OURS = [("1crn", "1crn-PDB (327)"), ("1crn_apbs", "1crn-PQR (642)"),
        ("1chb_hole2", "1JD0-PDB (4195)"), ("3pqr", "1bh8-PQR (2161)")]
SAMPLES = [30, 60, 80, 100]


def load(path):
    with open(path) as f:
        return json.load(f)


def table1(res):
    out = ["# Table 1: total time (s) of the certified pipeline, ours beside the paper's\n",
           "Paper: Quadro 6000, times without exact certification. Ours: `vorball bench`,"
           " total = culling + upload + envelope + vertices + matching + certification.\n"]
    for path in sorted(glob.glob(os.path.join(res, "table1_*_1crn.json"))):
        device = os.path.basename(path).split("_")[1]
        rows = []
        for stem, paper_key in OURS:
            p = os.path.join(res, "table1_%s_%s.json" % (device, stem))
            if not os.path.exists(p):
                continue
            runs = {r["samples"]: r for r in load(p)}
            name = "%s (%d atoms)" % (stem, next(iter(runs.values()))["atoms"])
            dev = next(iter(runs.values()))["device"]
            cells = []
            for k, s in enumerate(SAMPLES):
                r = runs.get(s)
                cells.append("%.3f / %s (%d v)" % (r["total"], PAPER[paper_key][k], r["vertices"])
                             if r else "-")
            rows.append("| %s | %s | %s |" % (name, paper_key, " | ".join(cells)))
        out.append("\n## %s: %s\n\n" % (device, dev))
        out.append("| our input | paper's column | " + " | ".join("%d^2 ours / paper" % s for s in SAMPLES)
                   + " |\n|" + "---|" * (2 + len(SAMPLES)) + "\n")
        out.append("\n".join(rows) + "\n")
        out.append("\nStages at 100^2 (s): cull, upload, envelope, vertices, matching, certification\n\n")
        for stem, _ in OURS:
            p = os.path.join(res, "table1_%s_%s.json" % (device, stem))
            if os.path.exists(p):
                for r in load(p):
                    if r["samples"] == 100:
                        out.append("- %s: %.3f, %.3f, %.3f, %.3f, %.3f, %.3f (total %.3f)\n" % (
                            stem, r["cull"], r["upload"], r["envelope"], r["vertices_s"],
                            r["matching"], r["certification"], r["total"]))
    with open(os.path.join(res, "table1.md"), "w") as f:
        f.write("".join(out))


def fig13(res):
    files = sorted(glob.glob(os.path.join(res, "fig13_*.json")))
    if not files:
        return
    series = []
    with open(os.path.join(res, "fig13.dat"), "w") as f:
        f.write("# input samples first_cell from_sampling certified\n")
        for p in files:
            stem = os.path.basename(p)[len("fig13_"):-len(".json")].split("_", 1)[1]
            runs = load(p)
            f.write("# %s\n" % stem)
            for r in runs:
                f.write("%s %d %d %d %d\n" % (stem, r["samples"], r["first_cell"],
                                             r["from_sampling"], r["vertices"]))
            f.write("\n\n")
            series.append(stem)
    plot = os.path.join(res, "fig13.gp")
    with open(plot, "w") as g:
        g.write('set terminal pngcairo size 1200,500 noenhanced\nset output "%s"\n' %
                os.path.join(res, "fig13.png"))
        g.write("set multiplot layout 1,2\nset key bottom right\nset xlabel 'samples S (S x S per face)'\n")
        g.write("set title 'first cell (sphere 0): vertices found by sampling'\nset ylabel 'vertices'\n")
        g.write("plot " + ", ".join("'%s' index %d using 2:3 with linespoints title '%s'" %
                                    (os.path.join(res, "fig13.dat"), k, s)
                                    for k, s in enumerate(series)) + "\n")
        g.write("set title 'whole diagram: from sampling / certified'\nset logscale y\n")
        g.write("plot " + ", ".join(
            "'%s' index %d using 2:4 with linespoints title '%s sampled', "
            "'%s' index %d using 2:5 with lines dashtype 2 title '%s certified'" %
            (os.path.join(res, "fig13.dat"), k, s, os.path.join(res, "fig13.dat"), k, s)
            for k, s in enumerate(series)) + "\nunset multiplot\n")
    subprocess.run(["gnuplot", plot], check=True)


if __name__ == "__main__":
    res = sys.argv[1]
    table1(res)
    fig13(res)
