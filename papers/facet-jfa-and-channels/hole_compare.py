#!/usr/bin/env python3
"""HOLE's pore against `vorball channels` on one structure (hole_compare.sh runs both).

usage: hole_compare.py radii RADFILE OUT.radii
         HOLE's .rad file -> vorball --radii file (one radius per element, from the
         general 'VDWR X??? ???' records); prints what cannot be carried over
       hole_compare.py table OUTDIR NAME...
         Markdown tables from compare's outputs: the minimum radii side by side, and
         each profile at 15 axial positions where both have a point
       hole_compare.py compare NAME HOLE_STDOUT HOLE.sph VORBALL.json OUTDIR [HOLE_STDOUT...]
         writes OUTDIR/NAME_summary.json, NAME_hole_profile.tsv, NAME_vorball_profile.tsv,
         NAME_profiles.tsv (side by side on HOLE's axial positions); further HOLE
         outputs (other random seeds) give the spread of HOLE's own minimum radius
Axial position s = p . CVECT (HOLE's cenxyz.cvec, CVECT as HOLE found or was given).
The vorball channel compared is its pore (kind "pore", HOLE's measure), else the one
whose centreline covers most of HOLE's centre line (points within COVER_A = 1.5 A of it). Standard library only.
"""
import json
import math
import os
import re
import sys

COVER_A = 1.5


def rad_to_radii(src, dst):
    general, other = {}, []
    for line in open(src):
        f = line.split()
        if len(f) >= 4 and f[0].upper() == "VDWR":
            name, res, r = f[1], f[2], f[3]
            if res == "???" and len(name) >= 2 and name[0].isalpha() and set(name[1:]) == {"?"}:
                general.setdefault(name[0].upper(), r)
            else:
                other.append("%s %s %s" % (name, res, r))
    with open(dst, "w") as f:
        f.write("# from %s: its general VDWR records, one radius per element\n" % os.path.basename(src))
        for el, r in general.items():
            f.write("%s %s\n" % (el, r))
    if other:
        print("hole_compare: %s: records not carried over (atom/residue specific): %s"
              % (src, "; ".join(other)), file=sys.stderr)


def parse_hole(path):
    text = open(path, errors="replace").read()
    out = {"file": path}
    m = re.search(r"TAG\s+\d+\s+Rmin=\s*(\S+)\s+Gmacro=\s*(\S+)\s+Conn_Gmacro=\s*(\S+)", text)
    if m:
        out["rmin_A"], out["gmacro_pS"], out["conn_gmacro_pS"] = (float(v) for v in m.groups())
    m = re.search(r"Minimum radius found:\s*(\S+)", text)
    if m:
        out["rmin_printed_A"] = float(m.group(1))
    for key in ("CPOINT", "CVECT"):
        ms = re.findall(r"^\s*%s\s+(\S+)\s+(\S+)\s+(\S+)\s*$" % key, text, re.M | re.I)
        if ms:
            out[key.lower()] = [float(v) for v in ms[-1]]
    m = re.search(r"seed.*?(-?\d+)\s*$", text, re.M | re.I)
    prof = []
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.strip().startswith("cenxyz.cvec"):
            for row in lines[i + 1:]:
                f = row.split()
                if len(f) < 4:
                    break
                try:
                    prof.append({"s": float(f[0]), "radius": float(f[1]), "cen_line_D": float(f[2]),
                                 "sum_s_area": float(f[3]), "kind": "mid-point" if "mid" in row else "sampled"})
                except ValueError:
                    break
            break
    out["profile"] = prof
    out["normal_completion"] = "HOLE: normal completion" in text
    return out


def parse_sph(path):
    pts = []
    for line in open(path, errors="replace"):
        if not line.startswith("ATOM"):
            continue
        try:
            res = int(line[22:26])
            x, y, z = float(line[30:38]), float(line[38:46]), float(line[46:54])
            r = float(line[54:60])
        except ValueError:
            continue
        if res in (-999, -888):  # Connolly spheres and capsule/end markers, not centre-line points
            continue
        pts.append((x, y, z, r, res))
    return pts


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def dist(a, b):
    return math.sqrt((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 + (a[2] - b[2]) ** 2)


def seg_dist(p, a, b):
    ab = [b[i] - a[i] for i in range(3)]
    l2 = dot(ab, ab)
    t = 0.0 if l2 == 0 else max(0.0, min(1.0, dot([p[i] - a[i] for i in range(3)], ab) / l2))
    return dist(p, [a[i] + t * ab[i] for i in range(3)])


def poly_dist(p, line):
    if len(line) == 1:
        return dist(p, line[0])
    return min(seg_dist(p, line[i], line[i + 1]) for i in range(len(line) - 1))


def nearest_r(pts, s, within=0.5):
    """Radius of the point nearest in s (None when none lies within `within` A)."""
    if not pts:
        return None
    q = min(pts, key=lambda w: abs(w["s"] - s))
    return q["radius"] if abs(q["s"] - s) <= within else None


def compare(name, hole_out, sph, vjson, outdir, more):
    h = parse_hole(hole_out)
    cvec = h.get("cvect", [0.0, 0.0, 1.0])
    n = math.sqrt(dot(cvec, cvec)) or 1.0
    u = [c / n for c in cvec]
    centres = parse_sph(sph)
    hole_pts = sorted(({"s": dot(p[:3], u), "x": p[0], "y": p[1], "z": p[2], "radius": p[3]}
                       for p in centres), key=lambda q: q["s"])
    hmin = min(hole_pts, key=lambda q: q["radius"]) if hole_pts else None
    v = json.load(open(vjson))
    frame = v["frames"][0]
    chans = frame.get("channels", [])
    best, best_cov, cov_all = None, -1.0, []
    for c in chans:
        line = [q[:3] for q in c.get("centreline", [])]
        if not line or not hole_pts:
            cov_all.append({"id": c["id"], "coverage": 0.0})
            continue
        near = sum(1 for q in hole_pts if poly_dist((q["x"], q["y"], q["z"]), line) <= COVER_A)
        cov = near / len(hole_pts)
        cov_all.append({"id": c["id"], "kind": c.get("kind"), "coverage": round(cov, 4),
                        "bottleneck_A": c.get("bottleneck_A"), "length_A": c.get("length_A")})
        # The pore row (HOLE's own measure) is the one compared whenever there is one.
        if best is None or (c.get("kind") == "pore") > (best.get("kind") == "pore") or \
                ((c.get("kind") == "pore") == (best.get("kind") == "pore") and cov > best_cov):
            best, best_cov = c, cov
    vpts = []
    if best:
        vpts = sorted(({"s": dot(q[:3], u), "x": q[0], "y": q[1], "z": q[2], "radius": q[3]}
                       for q in best["centreline"]), key=lambda q: q["s"])
    vmin = None
    if best:
        b = best.get("bottleneck_at")
        vmin = {"radius": best.get("bottleneck_A"), "x": b[0], "y": b[1], "z": b[2], "s": dot(b, u)} if b else None
    spread = []
    for path in more:
        o = parse_hole(path)
        if "rmin_A" in o:
            spread.append({"file": path, "rmin_A": o["rmin_A"], "gmacro_pS": o["gmacro_pS"]})
    summary = {
        "name": name,
        "hole": {k: h.get(k) for k in ("rmin_A", "rmin_printed_A", "gmacro_pS", "conn_gmacro_pS", "cpoint",
                                        "cvect", "normal_completion", "file")},
        "hole_min_at": hmin, "hole_centre_points": len(hole_pts),
        "hole_other_seeds": spread,
        "vorball": {"input": v.get("input"), "probe_A": v.get("probe_A"), "grid": v.get("grid"),
                    "device": v.get("device"), "voxel_A": frame.get("voxel_A"), "channels": len(chans),
                    "matched_channel": best.get("id") if best else None,
                    "matched_coverage": round(best_cov, 4) if best else None,
                    "bottleneck": vmin, "length_A": best.get("length_A") if best else None,
                    "through": best.get("through") if best else None,
                    "kind": best.get("kind") if best else None,
                    "pore": frame.get("pore")},
        "channels_coverage": cov_all,
        # A symmetric pore (gramicidin's dimer) has its narrowest point twice: each
        # tool's radius where the other has its minimum tells the same place apart.
        "vorball_radius_at_hole_min": nearest_r(vpts, hmin["s"]) if hmin else None,
        "hole_radius_at_vorball_min": nearest_r(hole_pts, vmin["s"]) if vmin else None,
        "delta_rmin_A": (vmin["radius"] - h["rmin_A"]) if vmin and "rmin_A" in h else None,
        "delta_s_A": (vmin["s"] - hmin["s"]) if vmin and hmin else None,
    }
    if spread:
        rs = [h["rmin_A"]] + [q["rmin_A"] for q in spread] if "rmin_A" in h else [q["rmin_A"] for q in spread]
        summary["hole_rmin_range_A"] = [min(rs), max(rs)]
    os.makedirs(outdir, exist_ok=True)
    with open(os.path.join(outdir, name + "_summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
        f.write("\n")
    for tag, pts in (("hole", hole_pts), ("vorball", vpts)):
        with open(os.path.join(outdir, "%s_%s_profile.tsv" % (name, tag)), "w") as f:
            f.write("# s = p . (%.4f, %.4f, %.4f)\ts\tradius\tx\ty\tz\n" % tuple(u))
            for q in pts:
                f.write("\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\n" % (q["s"], q["radius"], q["x"], q["y"], q["z"]))
    with open(os.path.join(outdir, name + "_profiles.tsv"), "w") as f:
        f.write("# HOLE centre points; vorball: its matched channel's centreline point nearest in s"
                " (within 0.5 A in s), lateral = its distance from HOLE's centre off the axis\n")
        f.write("s\thole_radius\tvorball_radius\tvorball_s\tlateral_A\n")
        for q in hole_pts:
            near = min(vpts, key=lambda w: abs(w["s"] - q["s"])) if vpts else None
            if near and abs(near["s"] - q["s"]) <= 0.5:
                d = [near[a] - q[a] for a in "xyz"]
                ds = dot(d, u)
                lat = math.sqrt(max(0.0, dot(d, d) - ds * ds))
                f.write("%.3f\t%.3f\t%.3f\t%.3f\t%.3f\n" % (q["s"], q["radius"], near["radius"], near["s"], lat))
            else:
                f.write("%.3f\t%.3f\t\t\t\n" % (q["s"], q["radius"]))
    hm = summary["hole"]
    print("%s: HOLE Rmin %s A at s %s (Gmacro %s pS); vorball channel %s (coverage %s) bottleneck %s A at s %s"
          % (name, hm.get("rmin_A"), "%.3f" % hmin["s"] if hmin else None, hm.get("gmacro_pS"),
             summary["vorball"]["matched_channel"], summary["vorball"]["matched_coverage"],
             vmin["radius"] if vmin else None, "%.3f" % vmin["s"] if vmin else None), file=sys.stderr)


def table(outdir, names, rows=15):
    """Markdown: one summary row per structure, then each profile at `rows` axial positions."""
    out = ["| structure | atoms | HOLE Rmin (A) | HOLE s (A) | HOLE Rmin, 5 seeds | vorball (A) | vorball s (A) |"
           " vorball - HOLE (A) | vorball at HOLE's s (A) | voxel (A) | axis | HOLE Gmacro (pS) | vorball Gmacro (pS) |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    profiles = []
    for name in names:
        s = json.load(open(os.path.join(outdir, name + "_summary.json")))
        h, v = s["hole"], s["vorball"]
        hm, vb = s.get("hole_min_at") or {}, v.get("bottleneck") or {}
        pore = v.get("pore") or {}
        vj = json.load(open(os.path.join(outdir, name + "_vorball.json")))
        rng = s.get("hole_rmin_range_A")
        at = s.get("vorball_radius_at_hole_min")
        out.append("| %s | %s | %.3f | %.2f | %s | %.3f | %.2f | %+.3f | %s | %.3f | %s | %.0f | %s |" % (
            name, vj["frames"][0].get("atoms"), h["rmin_A"], hm["s"],
            "%.3f-%.3f" % tuple(rng) if rng else "", vb["radius"], vb["s"], s["delta_rmin_A"],
            "" if at is None else "%.3f" % at, v["voxel_A"], pore.get("axis_from", v.get("kind")), h["gmacro_pS"],
            "%.0f" % pore["g_macro_pS"] if pore.get("g_macro_pS") else ""))
        both = []
        for line in open(os.path.join(outdir, name + "_profiles.tsv")):
            f = line.rstrip("\n").split("\t")
            if len(f) >= 3 and f[2] and not line.startswith(("#", "s\t")):
                both.append((float(f[0]), float(f[1]), float(f[2])))
        if both:
            pick = sorted({round(k * (len(both) - 1) / (rows - 1)) for k in range(rows)})
            profiles.append((name, [both[i] for i in pick]))
    for name, pts in profiles:
        out += ["", "%s: radius (A) against s (A), HOLE's axial coordinate (p . CVECT)" % name, "",
                "| s | " + " | ".join("%.1f" % p[0] for p in pts) + " |",
                "|---|" + "---|" * len(pts),
                "| HOLE | " + " | ".join("%.2f" % p[1] for p in pts) + " |",
                "| vorball | " + " | ".join("%.2f" % p[2] for p in pts) + " |"]
    print("\n".join(out))


def main(argv):
    if len(argv) >= 3 and argv[0] == "table":
        table(argv[1], argv[2:])
    elif len(argv) >= 3 and argv[0] == "radii":
        rad_to_radii(argv[1], argv[2])
    elif len(argv) >= 6 and argv[0] == "compare":
        compare(argv[1], argv[2], argv[3], argv[4], argv[5], argv[6:])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
