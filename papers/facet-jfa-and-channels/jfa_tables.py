#!/usr/bin/env python3
"""Turns the JSON files of jfa_run.sh into the tables of results/jfa/README
parts and the data file of the speed-up plot (jfa_speedup.gp).

    python3 jfa_tables.py RESULTS_DIR [ERRORS_DIR] > tables.md
                                            (writes RESULTS_DIR/jfa_speedup.dat)

Runs made without --check (jfa_run.sh with JFA_CHECK=) carry times only; their
error figures are taken from ERRORS_DIR, an earlier run of the same
configurations (same grid, seeds and variant), which is valid only while the
kernels return the same labels bit for bit (test_jfa checks that on the device).
"""
import json
import os
import sys


ERROR_KEYS = ["wrong", "wrong_rate", "max_err", "mean_err", "boundary_exact",
              "boundary_found", "boundary_missed", "boundary_extra"]
ERRORS_DIR = None


def read(d, name):
    p = os.path.join(d, name + ".json")
    if not os.path.exists(p):
        return None
    with open(p) as f:
        return json.load(f)


def load(d, name):
    doc = read(d, name)
    if doc is None or all("wrong_rate" in r for r in doc["runs"]):
        return doc
    old = read(ERRORS_DIR, name) if ERRORS_DIR else None
    if old is None:
        sys.exit("%s: no error figures (run with --check or give ERRORS_DIR)" % name)
    for k in ("dim", "n", "seeds", "source"):
        if os.path.basename(str(old[k])) != os.path.basename(str(doc[k])):
            sys.exit("%s: %s differs from the error run's" % (name, k))
    errs = {r["variant"]: r for r in old["runs"]}
    for r in doc["runs"]:
        if "wrong_rate" not in r:
            r.update({k: errs[r["variant"]][k] for k in ERROR_KEYS})
    return doc


def runs(doc):
    return {r["variant"]: r for r in doc["runs"]}


def main():
    global ERRORS_DIR
    d = sys.argv[1]
    ERRORS_DIR = sys.argv[2] if len(sys.argv) > 2 else None
    out = []
    sizes = [256, 512, 1024, 2048, 4096]
    seeds = [10, 100, 1000, 10000, 100000]
    device = None
    dat = ["# n seeds jfa+1_ms facet_ms speedup facet_m facet_pixels jfa+1_pixels exact_ms "
           "exact_speedup (JFA+1 over exact; 0 without an exact run)"]
    out.append("### 2D: Facet-JFA against JFA+1 (uniform seeds, mean of 10 runs)\n")
    out.append("| n | seeds | JFA ms | JFA+1 ms | Facet ms | speed-up vs JFA+1 | m | "
               "pixels JFA+1 / Facet | wrong JFA+1 | wrong Facet | max err Facet (px) | "
               "exact ms | wrong exact |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n in sizes:
        for k in seeds:
            doc = load(d, "fig2d_n%d_k%d" % (n, k))
            if not doc:
                continue
            device = doc["device"]
            r = runs(doc)
            j, j1, fa = r["jfa"], r["jfa+1"], r["facet"]
            sp = j1["time_ms"] / fa["time_ms"]
            ratio = j1["pixels_processed"] / max(fa["pixels_processed"], 1)
            ex = r.get("exact")
            out.append("| %d | %d | %.3f | %.3f | %.3f | %.2f | %d | %.1f | %.2e | %.2e | %.2f | %s | %s |" % (
                n, k, j["time_ms"], j1["time_ms"], fa["time_ms"], sp, fa["m"], ratio,
                j1["wrong_rate"], fa["wrong_rate"], fa["max_err"],
                "%.3f" % ex["time_ms"] if ex else "-",
                ex.get("wrong", "-") if ex else "-"))
            dat.append("%d %d %.4f %.4f %.4f %d %d %d %.4f %.4f" % (
                n, k, j1["time_ms"], fa["time_ms"], sp, fa["m"], fa["pixels_processed"],
                j1["pixels_processed"], ex["time_ms"] if ex else 0,
                j1["time_ms"] / ex["time_ms"] if ex and ex["time_ms"] > 0 else 0))
        dat.append("")
        dat.append("")
    with open(os.path.join(d, "jfa_speedup.dat"), "w") as f:
        f.write("\n".join(dat) + "\n")

    out.append("\n### 3D\n")
    out.append("| case | variant | ms (wall) | ms (GPU) | m | pixels processed | wrong rate | "
               "max err (px) | mean err (px) | boundary missed / extra (of exact) |")
    out.append("|---|---|---|---|---|---|---|---|---|---|")
    cases = ["target3d", "fig3d_n512_k1000", "fig3d_n128_k1000", "dist3d_uniform",
             "dist3d_clustered", "dist3d_shell", "protein_3pqr", "protein_4yvs",
             "dist2d_uniform", "dist2d_clustered", "dist2d_shell"]
    for c in cases:
        doc = load(d, c)
        if not doc:
            continue
        src = doc["source"].replace(os.path.dirname(os.path.dirname(os.path.abspath(d))), "")
        src = src.split("corpus/data/")[-1] if "corpus/data/" in src else src
        label = "%s: %u^%d, %d seeds (%s)" % (c, doc["n"], doc["dim"], doc["seeds"], src)
        for r in doc["runs"]:
            out.append("| %s | %s | %.3f | %.3f | %d | %d | %.2e | %.2f | %.2e | %d / %d (%d) |" % (
                label, r["variant"], r["time_ms"], r["gpu_ms"], r["m"], r["pixels_processed"],
                r["wrong_rate"], r["max_err"], r["mean_err"], r["boundary_missed"],
                r["boundary_extra"], r["boundary_exact"]))
            label = ""
    print("Device: %s\n" % device)
    print("\n".join(out))


if __name__ == "__main__":
    main()
