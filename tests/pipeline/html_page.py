#!/usr/bin/env python3
"""The results page (`channels --html`) as a user opens it: headless Chromium
with every network name unresolvable (the page must open offline) loads the
page, its script draws the molecule and the channels with the embedded viewer,
and the page then says what it drew. Checked:
  - the page finished drawing (body data-ready), without an error shown;
  - the viewer read every atom (data-view-atoms = the input's atom count);
  - the channels drawn and the figures shown equal the CSV table's rows
    (counts of pores/channels/cavities, each row's bottleneck and length);
  - a trajectory's page has one frame per table frame and shows the slider;
  - the screenshot's 3D view is not blank (many colours, a visible share of
    non-background pixels).
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

shot = os.path.join(work, "gramicidin.png")
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
check(len(colours) >= 50, f"gramicidin: the 3D view has {len(colours)} colours (>= 50)")
check(ink >= 0.02 * total, f"gramicidin: {100.0 * ink / total:.1f} % of the 3D view drawn (>= 2 %)")

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

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
