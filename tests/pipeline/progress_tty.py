#!/usr/bin/env python3
"""Progress as a user sees it (issue 35): `vorball vertices` with stderr on a
pseudo-terminal draws one updating line per stage, "stage: done/total (pct%),
rate/s, ~Ns left", and erases it; with stderr a plain pipe, or with --quiet,
nothing is drawn; the output file is the same bytes in every case. Checked:
  - on the terminal (the plain-C cover of the 26,430-atom capsid on one
    thread: 4 s on the idle 2-core machine; 3pqr took 0.5 s there by stop 47,
    under the line's 1 s delay, and drew nothing): progress
    lines of the cover, the done counts of each stage drawn never decreasing
    and its last one equal to its total, at most ~4 drawings a second, the
    line erased at the end; with VORBALL_PROGRESS=1 (every stage drawn from
    its start) the certification's too;
  - `verify --arcs` on the terminal: the arcs stage ends at its total;
  - on a pipe, and with --quiet on the terminal (even with
    VORBALL_PROGRESS=1): no progress line;
  - the vertex files are byte-identical with and without progress (the
    capsid on the terminal and forced; 3pqr on a pipe and with --quiet);
  - a warning printed while the status line is drawn erases it first
    (`channels`, W808): every warning starts a line of its own.
Usage: progress_tty.py VORBALL SOURCE_DIR WORK_DIR"""
import os
import pty
import re
import subprocess
import sys
import time

vorball, source, work = sys.argv[1:4]
spheres = os.path.join(source, "corpus", "data", "3pqr.pqr")
slow = os.path.join(source, "corpus", "data", "4yvs_ev71_capsid.cif")
os.makedirs(work, exist_ok=True)
failures = []
LINE = re.compile(r"([a-z]+): (\d+)/(\d+) \(\d+\.\d%\)(, [0-9.e+]+/s)?(, ~\d+s left)?$")


def env(**more):
    e = {k: v for k, v in os.environ.items() if k not in ("VORBALL_PROGRESS",
                                                          "VORBALL_NO_PROGRESS")}
    e.update(more)
    return e


def on_tty(args, **more):
    """Runs vorball with stderr on a pseudo-terminal; (exit status, the bytes
    the terminal received, seconds)."""
    master, slave = pty.openpty()
    t0 = time.time()
    p = subprocess.Popen([vorball, *args], stdin=subprocess.DEVNULL,
                         stdout=subprocess.DEVNULL, stderr=slave, env=env(**more))
    os.close(slave)
    got = bytearray()
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # EIO: every writer closed the terminal
            break
        if not chunk:
            break
        got += chunk
    os.close(master)
    return p.wait(), bytes(got), time.time() - t0


DRAW = b"\r\033[K"   # how every drawing and the erasing start (a terminal
                      # turns the "\n" of diagnostics into "\r\n": not those)


def drawings(raw):
    """The progress lines drawn: (stage, done, total) in order."""
    out = []
    for piece in raw.decode("utf-8", "replace").replace("\033[K", "").split("\r"):
        m = LINE.match(piece.strip())
        if m:
            out.append((m.group(1), int(m.group(2)), int(m.group(3))))
    return out


def check_stages(name, lines, want):
    stages = {}
    for s, d, t in lines:
        stages.setdefault(s, []).append((d, t))
    for s in want:
        if s not in stages:
            failures.append("%s: no '%s' progress line in %r" % (name, s, lines[:5]))
            continue
        seq = stages[s]
        dones = [d for d, _ in seq]
        if any(b < a for a, b in zip(dones, dones[1:])):
            failures.append("%s: %s done counts decrease: %s" % (name, s, dones))
        if seq[-1][0] != seq[-1][1] or seq[-1][1] == 0:
            failures.append("%s: %s ends at %d of %d" % (name, s, seq[-1][0], seq[-1][1]))
    return stages


# 1. A terminal: the line is drawn (no VORBALL_PROGRESS), and erased.
tty_out = os.path.join(work, "tty.tsv")
RUN = ["--device", "ref", "--threads", "1"]
rc, raw, secs = on_tty(["vertices", slow, *RUN, "-o", tty_out])
if rc != 0:
    failures.append("vertices on a terminal exited %d: %r" % (rc, raw[-400:]))
lines = drawings(raw)
stages = check_stages("vertices on a terminal", lines, ["cover"])
# at most ~4 drawings a second, plus each stage's last count
if len(lines) > 4 * secs + 2 * len(stages) + 2:
    failures.append("%d drawings in %.1f s: more than 4 a second" % (len(lines), secs))
if DRAW not in raw or raw.rfind(DRAW) < raw.rfind(b"(100.0%)"):
    failures.append("the progress line is not erased at the end: %r" % raw[-80:])
print("terminal: %d drawings in %.1f s, stages %s" % (
    len(lines), secs, {s: v[-1] for s, v in stages.items()}))

# 1b. Forced: the certification is drawn too, from its start to its total.
rc, raw_f, _ = on_tty(["vertices", slow, *RUN, "-o", os.path.join(work, "forced.tsv")],
                      VORBALL_PROGRESS="1")
check_stages("vertices, VORBALL_PROGRESS=1", drawings(raw_f), ["cover", "certify"])

# 2. A pipe: nothing drawn, the same bytes.
pipe_out = os.path.join(work, "pipe.tsv")
p = subprocess.run([vorball, "vertices", spheres, *RUN, "-o", pipe_out],
                   capture_output=True, env=env())
if p.returncode != 0:
    failures.append("vertices on a pipe exited %d" % p.returncode)
if b"\r" in p.stderr or drawings(p.stderr):
    failures.append("progress drawn on a pipe: %r" % p.stderr[:200])

# 3. --quiet on a terminal: nothing drawn, the same bytes.
quiet_out = os.path.join(work, "quiet.tsv")
rc, raw_q, _ = on_tty(["vertices", "--quiet", spheres, *RUN, "-o", quiet_out],
                      VORBALL_PROGRESS="1")
if rc != 0 or DRAW in raw_q or drawings(raw_q):
    failures.append("--quiet: exit %d, terminal got %r" % (rc, raw_q[:200]))

for pair in (("tty.tsv", "forced.tsv"), ("pipe.tsv", "quiet.tsv")):
    blobs = [open(os.path.join(work, f), "rb").read() for f in pair]
    if not blobs[0] or blobs[1] != blobs[0]:
        failures.append("vertex files differ with and without progress (%s: %s)" %
                        (pair, [len(b) for b in blobs]))

# 4. verify --arcs on a terminal (VORBALL_PROGRESS=1: a short run drawn too).
rc, raw_a, _ = on_tty(["verify", spheres, pipe_out, "--arcs"], VORBALL_PROGRESS="1")
if rc != 0:
    failures.append("verify --arcs exited %d: %r" % (rc, raw_a[-400:]))
check_stages("verify --arcs", drawings(raw_a), ["arcs"])

# 5. A warning while the status line is drawn: `channels` on adenylate
# kinase (3,341 atoms) at grid 256 (the plain-C reference: 0.7 s on the idle
# 2-core machine), whose W808 (no pore) comes at the end of the frame; with
# VORBALL_PROGRESS=1 the status line is drawn from the start (otherwise after
# 1 s, which a fast machine may not reach). The line is erased first: the
# warning starts a line of its own, never after the status text.
rc, raw_w, secs = on_tty(["channels", os.path.join(source, "corpus", "data", "adk_open.pdb.gz"),
                          "--grid", "256", "--device", "ref",
                          "-o", os.path.join(work, "warn.csv")], VORBALL_PROGRESS="1")
if rc != 0:
    failures.append("channels on a terminal exited %d: %r" % (rc, raw_w[-400:]))
at = raw_w.find(b"vorball: W808")
if at < 0 or not re.search(rb"\[\d+ s\]", raw_w[:max(at, 0)]):
    failures.append("channels: no W808 after a drawn status line (%.1f s): %r" % (secs, raw_w[:300]))
for m in re.finditer(rb"vorball: W\d+", raw_w):
    before = raw_w[:m.start()]
    if before and not before.endswith((b"\n", DRAW)):
        failures.append("a warning printed after the progress text: %r" % raw_w[max(0, m.start() - 60):m.end()])
print("warning on a terminal: %.1f s, %d warnings" % (secs, len(re.findall(rb"vorball: W\d+", raw_w))))

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
