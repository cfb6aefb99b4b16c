#!/usr/bin/env python3
"""Table of one peer_bench.sh input: OUTDIR/NAME/summary.json and rows of OUTDIR/peer_bench.tsv.

usage: peer_summary.py DIR TSV TOOL...
Reads DIR/run.json, measure_TOOL.json, verify_TOOL.json, verify_union.json and
the tools' own reports (vorball_bench.json, vorball.stats, apo.json). Standard library only.
"""
import json
import os
import sys

COLUMNS = ["input", "spheres", "tool", "threads", "rc", "timed_out", "wall_s", "max_rss_mib",
           "tool_time_s", "tool_time_what", "lines", "groups", "certified", "not_a_vertex",
           "wrong_coordinates", "missing_members", "duplicate", "missed_complete",
           "union_vertices", "missed_vs_union", "verify_ok", "verify_wall_s"]


def load(path):
    try:
        with open(path) as f:
            text = f.read()
    except OSError:
        return None
    try:
        return json.loads(text)
    except ValueError:
        # several JSON documents (e.g. a truncated run): take the last that parses
        for line in reversed(text.splitlines()):
            try:
                return json.loads(line)
            except ValueError:
                continue
        return None


def stats_file(path):
    out = {}
    try:
        with open(path) as f:
            for line in f:
                k, sep, v = line.rstrip("\n").partition("\t")
                if sep:
                    out[k] = v
    except OSError:
        pass
    return out


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    d, tsv, tools = argv[0], argv[1], argv[2:]
    run = load(os.path.join(d, "run.json")) or {}
    union = load(os.path.join(d, "verify_union.json"))
    union_groups = union["groups"] if union else None
    summary = {"run": run, "union": union["counts"] if union else None,
               "union_groups": union_groups, "tools": {}}
    rows = []
    extra = ["apo_joggled"] if os.path.exists(os.path.join(d, "verify_apo_joggled.json")) else []
    for t in tools + extra:
        m = load(os.path.join(d, "measure_%s.json" % t)) or {}
        v = load(os.path.join(d, "verify_%s.json" % t)) or {}
        mv = load(os.path.join(d, "measure_verify_%s.json" % t)) or {}
        c = v.get("counts", {})
        rec = {"measure": m, "verify_counts": c, "verify_lines": v.get("lines"),
               "verify_groups": v.get("groups"), "verify_complete": v.get("complete"),
               "verify_ok": v.get("ok"), "verify_wall_s": mv.get("wall_s")}
        tool_time, what = None, ""
        if t == "vorball":
            b = load(os.path.join(d, "vorball_bench.json"))
            if isinstance(b, list) and b:
                rec["bench"] = b[0]
                tool_time, what = b[0].get("total"), "vorball bench total (best of REPEAT, device open)"
            rec["stats"] = stats_file(os.path.join(d, "vorball.stats"))
        elif t.startswith("apo"):
            a = load(os.path.join(d, "%s.json" % t))
            if a:
                rec["apo"] = a
                tool_time, what = a.get("build_ms_min", 0) / 1000.0, "apo build() CUDA events (best of REPEAT)"
        elif t.startswith("voronota"):
            tool_time, what = m.get("wall_s"), "wall"
        missed_union = None
        if union_groups is not None and v.get("groups") is not None and t in tools:
            missed_union = union_groups - v["groups"]
        rec["missed_vs_union"] = missed_union
        summary["tools"][t] = rec
        rss = m.get("max_rss_kib")
        rows.append({
            "input": run.get("input", d), "spheres": run.get("spheres"), "tool": t,
            "threads": 1 if t == "voronota1" else run.get("threads"), "rc": m.get("rc"),
            "timed_out": m.get("timed_out"), "wall_s": m.get("wall_s"),
            "max_rss_mib": round(rss / 1024.0, 1) if rss is not None else None,
            "tool_time_s": round(tool_time, 6) if tool_time is not None else None,
            "tool_time_what": what, "lines": v.get("lines"), "groups": v.get("groups"),
            "certified": c.get("certified"), "not_a_vertex": c.get("not_a_vertex"),
            "wrong_coordinates": c.get("wrong_coordinates"),
            "missing_members": c.get("missing_members"), "duplicate": c.get("duplicate"),
            "missed_complete": c.get("missed"), "union_vertices": union_groups,
            "missed_vs_union": missed_union, "verify_ok": v.get("ok"),
            "verify_wall_s": mv.get("wall_s")})
    with open(os.path.join(d, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
        f.write("\n")
    new = not os.path.exists(tsv) or os.path.getsize(tsv) == 0
    with open(tsv, "a") as f:
        if new:
            f.write("\t".join(COLUMNS) + "\n")
        for r in rows:
            f.write("\t".join("" if r[k] is None else str(r[k]) for k in COLUMNS) + "\n")
    for r in rows:
        print("%-12s %-10s wall %8s s  rss %8s MiB  lines %8s  certified %8s  missed %s/%s" % (
            os.path.basename(d), r["tool"], r["wall_s"], r["max_rss_mib"], r["lines"], r["certified"],
            r["missed_complete"], r["missed_vs_union"]), file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
