#!/usr/bin/env python3
"""The results pages (`channels --html`, `cells --html`, `vertices --html`) as a
user opens them: headless Chromium
with every network name unresolvable (the page must open offline) loads the
page, its script draws the molecule and the channels with the embedded viewer,
and the page then says what it drew. Checked:
  - the page finished drawing (body data-ready), without an error shown;
  - the viewer read every atom (data-view-atoms = the input's atom count);
  - the channels drawn and the figures shown equal the CSV table's rows
    (counts of pores/channels/cavities, each row's bottleneck and length);
  - a trajectory's page has one frame per table frame and shows the slider;
  - the screenshot's 3D view is not blank (many colours, a visible share of
    non-background pixels);
  - cells: the counts shown (atoms, contacts) equal the TSVs' rows, the
    selector offers volume, SAS and contact area and colours by the one
    chosen, each atom's volume on the page is the TSV's rounded, and a
    trajectory's page has the slider and one frame per table frame;
  - vertices: the vertices drawn and the count shown equal the table's
    lines; over 2000 spheres E133 (exit 43) and no page left.
Usage: html_page.py VORBALL SOURCE_DIR WORK_DIR"""
import csv
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import zlib

vorball, source, work = sys.argv[1:4]
data = os.path.join(source, "corpus", "data")
gramicidin = os.path.join(data, "1grm_single_hole2.pdb")
os.makedirs(work, exist_ok=True)
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    sys.exit("FAIL: no Chromium on this machine (.ci/deps installs the Debian package)")


BROWSER = chromium()
OFFLINE = ["--headless=new", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader",
           "--enable-unsafe-swiftshader", "--host-resolver-rules=MAP * ~NOTFOUND",
           "--proxy-server=127.0.0.1:9", "--window-size=1200,800",
           "--virtual-time-budget=20000", "--user-data-dir=" + os.path.join(work, "chromium")]


def browse(page, *what):
    r = subprocess.run([BROWSER] + OFFLINE + list(what) + ["file://" + os.path.abspath(page)],
                       capture_output=True, text=True, timeout=300)
    return r.stdout


def body_attrs(dom):
    m = re.search(r"<body([^>]*)>", dom)
    attrs = dict(re.findall(r'data-([a-z-]+)="([^"]*)"', m.group(1) if m else ""))
    return {k: v.replace("&quot;", '"').replace("&amp;", "&") for k, v in attrs.items()}


def png_pixels(path):
    """(width, height, rows of RGB(A) bytes) of an 8-bit RGB/RGBA PNG."""
    raw = open(path, "rb").read()
    assert raw[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, w = 8, b"", 0
    while pos < len(raw):
        n, kind = struct.unpack(">I4s", raw[pos:pos + 8])
        body = raw[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6)
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    flat, rows, prev, stride = zlib.decompress(idat), [], bytearray(w * bpp), w * bpp
    for y in range(h):
        f, line = flat[y * (stride + 1)], bytearray(flat[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, bpp, rows


def run_channels(tag, *args):
    table, page = os.path.join(work, tag + ".csv"), os.path.join(work, tag + ".html")
    for p in (table, page):
        if os.path.exists(p):
            os.remove(p)
    r = subprocess.run([vorball, "channels"] + list(args) + ["-o", table, "--html", page],
                       capture_output=True, text=True)
    check(r.returncode == 0, f"{tag}: vorball channels exits 0 ({r.stderr.strip()[-300:]})")
    rows = list(csv.DictReader(open(table)))
    return rows, page


# 1. One structure: gramicidin A, as the README runs it.
rows, page = run_channels("gramicidin", gramicidin)
dom = browse(page, "--dump-dom")
attrs = body_attrs(dom)
check(attrs.get("ready") == "1", f"gramicidin: the page drew frame 1 (data-ready={attrs.get('ready')})")
err = re.search(r'<p id="error">([^<]*)</p>', dom)
check(err is not None and err.group(1) == "", "gramicidin: no error shown on the page")
natoms = sum(1 for line in open(gramicidin) if line.startswith(("ATOM", "HETATM")))
check(attrs.get("view-atoms") == str(natoms),
      f"gramicidin: the viewer read {attrs.get('view-atoms')} atoms of {natoms}")
check(attrs.get("drawn-paths") == str(len(rows)),
      f"gramicidin: {attrs.get('drawn-paths')} channels drawn, {len(rows)} table rows")
facts = dict(json.loads(attrs.get("facts", "[]")))
for kind, key in (("pore", "pores"), ("channel", "channels"), ("cavity", "cavities")):
    n = sum(1 for r in rows if r["kind"] == kind)
    check(facts.get(key) == str(n), f"gramicidin: page shows {key} = {facts.get(key)}, table has {n}")
for r in rows:
    name = f"{r['kind']} {r['channel']}"
    check(facts.get(f"{name}: bottleneck radius (Å)") == r["bottleneck_A"],
          f"gramicidin: {name} bottleneck {facts.get(name + ': bottleneck radius (Å)')} = table {r['bottleneck_A']}")
    check(facts.get(f"{name}: length (Å)") == r["length_A"], f"gramicidin: {name} length = table {r['length_A']}")
check(re.search(r"<polyline[^>]*points=\"[0-9]", dom) is not None, "gramicidin: the pore's profile is plotted")



def screenshot_drawn(tag, page):
    """The 3D view of the page's screenshot is drawn: many colours, and a
    visible share of non-white pixels."""
    shot = os.path.join(work, tag + ".png")
    if os.path.exists(shot):
        os.remove(shot)
    browse(page, "--screenshot=" + shot)
    w, h, bpp, px = png_pixels(shot)
    colours, ink, total = set(), 0, 0
    for y in range(60, h - 20, 2):  # the 3D view: left of the side panel, below the header
        row = px[y]
        for x in range(10, int(w * 0.6), 2):
            c = bytes(row[x * bpp:x * bpp + 3])
            colours.add(c)
            total += 1
            ink += c != b"\xff\xff\xff"
    check(len(colours) >= 50, f"{tag}: the 3D view has {len(colours)} colours (>= 50)")
    check(ink >= 0.02 * total, f"{tag}: {100.0 * ink / total:.1f} % of the 3D view drawn (>= 2 %)")


screenshot_drawn("gramicidin", page)

# 2. A trajectory: three models of an MD run read as frames, the slider shown.
traj = os.path.join(data, "ngl_md_ascii_trj.pdb")
if os.path.exists(traj):
    rows, page = run_channels("trajectory", traj, "--frames", "0:3", "--grid", "64")
    frames = sorted({r["frame"] for r in rows}, key=int)
    text = open(page, encoding="utf-8").read()
    blob = re.search(r'<script type="application/json" id="vb-data">(.*?)</script>', text, re.S)
    pdata = json.loads(blob.group(1))
    check(len(pdata["frames"]) == 3, f"trajectory: {len(pdata['frames'])} frames on the page (3)")
    check(all(len(f["xyz"]) == 3 * pdata["atoms"] for f in pdata["frames"]), "trajectory: every frame has coordinates")
    check(pdata["frames"][0]["xyz"] != pdata["frames"][2]["xyz"], "trajectory: the atoms move between frames")
    for k, f in enumerate(pdata["frames"]):
        n = sum(1 for r in rows if r["frame"] == frames[k]) if k < len(frames) else 0
        check(len(f["paths"]) == n, f"trajectory: frame {k}: {len(f['paths'])} channels on the page, {n} in the table")
    dom = browse(page, "--dump-dom")
    check('id="frames" class="shown"' in dom, "trajectory: the frame slider is shown")
    check(body_attrs(dom).get("ready") == "1", "trajectory: the page drew frame 1")
else:
    failures.append("the trajectory " + traj + " is missing")



def page_data(page):
    text = open(page, encoding="utf-8").read()
    blob = re.search(r'<script type="application/json" id="vb-data">(.*?)</script>', text, re.S)
    return json.loads(blob.group(1))


def tsv_rows(path):
    """The rows of a TSV as dicts, its provenance lines ('#') left out."""
    lines = [line for line in open(path) if not line.startswith("#")]
    return list(csv.DictReader(lines, delimiter="\t"))


def run_tool(tag, cmd, *args, rc=0):
    r = subprocess.run([vorball, cmd] + list(args), capture_output=True, text=True)
    check(r.returncode == rc, f"{tag}: vorball {cmd} exits {r.returncode}, expected {rc} "
                              f"({r.stderr.strip()[-300:]})")
    return r


# 3. Cells of one structure (model 1 of the MD run, 183 atoms), contacts too.
FAST = ["--tolerance", "1e-2", "--max-patches", "96", "--threads", "2"]
# 300 patches: every contact bounded (96 leave some with hi = inf), 7 s on 2 cores
BOUNDED = ["--tolerance", "1e-2", "--max-patches", "300", "--threads", "2"]
md = os.path.join(data, "ngl_md_ascii_trj.pdb")
cells_tsv, cells_c, cells_page = (os.path.join(work, "cells" + e) for e in (".tsv", "_c.tsv", ".html"))
run_tool("cells", "cells", md, "--model", "1", *BOUNDED, "-o", cells_tsv, "--contacts", cells_c,
         "--html", cells_page)
atoms, contacts = tsv_rows(cells_tsv), tsv_rows(cells_c)
dom = browse(cells_page, "--dump-dom")
attrs = body_attrs(dom)
check(attrs.get("ready") == "1", f"cells: the page drew frame 1 (data-ready={attrs.get('ready')})")
err = re.search(r'<p id="error">([^<]*)</p>', dom)
check(err is not None and err.group(1) == "", "cells: no error shown on the page")
check(attrs.get("view-atoms") == str(len(atoms)), f"cells: the viewer read {attrs.get('view-atoms')} atoms "
                                                  f"of the table's {len(atoms)}")
facts = dict(json.loads(attrs.get("facts", "[]")))
check(facts.get("atoms") == str(len(atoms)), f"cells: page shows atoms = {facts.get('atoms')}, TSV {len(atoms)}")
check(facts.get("contacts") == str(len(contacts)),
      f"cells: page shows contacts = {facts.get('contacts')}, contacts TSV {len(contacts)}")
names = json.loads(attrs.get("measures", "[]"))
check(names == ["volume (Å³)", "SAS area (Å²)", "contact area (Å²)"], f"cells: the selector offers {names}")
check(attrs.get("measure") == "volume (Å³)", f"cells: coloured by {attrs.get('measure')} at first")
check('id="measures" class="shown"' in dom, "cells: the measure selector is shown")
pdata = page_data(cells_page)
vol = pdata["frames"][0]["measures"][0]["v"]
check(len(vol) == len(atoms) and all(abs(v - float(a["volume"])) <= 1e-5 * abs(float(a["volume"])) + 1e-9
                                     for v, a in zip(vol, atoms)),
      "cells: each atom's volume on the page is the TSV's (6 digits)")
area = pdata["frames"][0]["measures"][2]["v"]
sums = [0.0] * len(atoms)
for c in contacts:
    sums[int(c["id1"])] += float(c["area"])
    sums[int(c["id2"])] += float(c["area"])
check(len(area) == len(sums) and all(a is not None and abs(a - b) <= 1e-5 * b + 1e-9
                                     for a, b in zip(area, sums)),
      "cells: each atom's contact area on the page is the sum of its contacts TSV rows")
screenshot_drawn("cells", cells_page)

# 4. Cells over frames 0, 2 and 4: the slider, one frame per table frame.
run_tool("cells-frames", "cells", md, "--frames", "0:5:2", *FAST, "-o", cells_tsv, "--html", cells_page)
rows = tsv_rows(cells_tsv)
frames = sorted({r["frame"] for r in rows}, key=int)
pdata = page_data(cells_page)
check(len(pdata["frames"]) == len(frames) == 3, f"cells-frames: {len(pdata['frames'])} frames on the page, "
                                                f"{len(frames)} in the table (3)")
for k, f in enumerate(pdata["frames"]):
    n = sum(1 for r in rows if r["frame"] == frames[k]) if k < len(frames) else -1
    shown = dict(f["facts"]).get("atoms")
    check(shown == str(n), f"cells-frames: frame {k}: atoms = {shown}, the table has {n} rows")
check(pdata["frames"][0]["xyz"] != pdata["frames"][1]["xyz"], "cells-frames: the atoms move between frames")
check(pdata["frames"][0]["measures"][0]["v"] != pdata["frames"][1]["measures"][0]["v"],
      "cells-frames: the volumes change between frames")
dom = browse(cells_page, "--dump-dom")
check('id="frames" class="shown"' in dom, "cells-frames: the frame slider is shown")
check(body_attrs(dom).get("ready") == "1", "cells-frames: the page drew frame 1")

# 5. Vertices of crambin (327 atoms): every certified vertex drawn.
crambin = os.path.join(data, "1crn.pdb")
vtsv, vpage = os.path.join(work, "vertices.tsv"), os.path.join(work, "vertices.html")
run_tool("vertices", "vertices", crambin, "--threads", "2", "-o", vtsv, "--html", vpage)
nvert = sum(1 for line in open(vtsv) if not line.startswith("#"))
dom = browse(vpage, "--dump-dom")
attrs = body_attrs(dom)
facts = dict(json.loads(attrs.get("facts", "[]")))
check(attrs.get("ready") == "1", "vertices: the page drew frame 1")
check(facts.get("vertices") == str(nvert), f"vertices: page shows {facts.get('vertices')}, table has {nvert}")
check(facts.get("spheres") == "327", f"vertices: page shows {facts.get('spheres')} spheres (327)")
check(attrs.get("drawn-points") == str(nvert), f"vertices: {attrs.get('drawn-points')} vertices drawn of {nvert}")
screenshot_drawn("vertices", vpage)

# 6. Over 2000 spheres: E133, exit 43, no page and no table left.
big = os.path.join(data, "1chb_hole2.pdb")
bpage, btsv = os.path.join(work, "big.html"), os.path.join(work, "big.tsv")
for p in (bpage, btsv):
    if os.path.exists(p):
        os.remove(p)
r = run_tool("vertices-big", "vertices", big, "-o", btsv, "--html", bpage, rc=43)
check("E133" in r.stderr, f"vertices-big: E133 named ({r.stderr.strip()[-200:]})")
check(not os.path.exists(bpage) and not os.path.exists(btsv), "vertices-big: no page and no table left")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
