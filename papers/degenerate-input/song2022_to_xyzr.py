#!/usr/bin/env python3
"""Converts the ball files of the Song 2022 benchmark (GitHub repository
vdrc/Benchmark-Dataset-for-the-Voronoi-Diagram-of-3D-Spherical-Balls) to
vorball's XYZR: one 'x y z r' line per ball, '#' comments.

usage: song2022_to_xyzr.py IN.txt OUT.xyzr
       song2022_to_xyzr.py IN_DIR OUT_DIR     (every *.txt below IN_DIR, same tree)

The data set's text files hold a first line with the ball count, then one
line per ball: 'id x y z r', separated by tabs and/or spaces, CRLF or LF
line ends, the last line with or without an end (ids start at 0 or 1 by
set). vorball numbers spheres 0, 1, ... in file order, so sphere k is the
k-th data line whatever its id; the header comment gives the first id.

Each number is copied as the file writes it, character for character (the
data set's decimals are what vorball reads exactly); nothing passes through
binary floating point. A token that is not a plain decimal
(-?digits[.digits]), a line without five fields, a radius that is not
positive or a count that does not match the first line stops the
conversion with a message naming the file and line. PROTEINSET's PDB files
need no conversion: vorball reads PDB directly (its element radii).
Standard library only.
"""
import re
import sys
from pathlib import Path

DECIMAL = re.compile(r"-?[0-9]+(\.[0-9]+)?\Z")


class FormatError(Exception):
    pass


def convert_text(text, name):
    """Returns the XYZR text of one data file's TEXT (its NAME in messages)."""
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    rows = [(k + 1, line.split()) for k, line in enumerate(lines)]
    rows = [(k, f) for k, f in rows if f]
    if not rows:
        raise FormatError("%s: empty file" % name)
    k, head = rows[0]
    if len(head) != 1 or not head[0].isdigit():
        raise FormatError("%s:%d: the first line must be the ball count, got %r" % (name, k, " ".join(head)))
    count = int(head[0])
    out, first_id = [], None
    for k, f in rows[1:]:
        if len(f) != 5:
            raise FormatError("%s:%d: expected 'id x y z r', got %d fields" % (name, k, len(f)))
        if first_id is None:
            first_id = f[0]
        for tok in f[1:]:
            if not DECIMAL.match(tok):
                raise FormatError("%s:%d: %r is not a plain decimal" % (name, k, tok))
        r = f[4].lstrip("-")
        if f[4].startswith("-") or not r.strip("0."):
            raise FormatError("%s:%d: radius %s is not positive" % (name, k, f[4]))
        out.append(" ".join(f[1:]))
    if len(out) != count:
        raise FormatError("%s: the first line says %d balls, the file has %d" % (name, count, len(out)))
    head = ["# %s (Song, Lee, Choi, Kim 2022 benchmark; song2022_to_xyzr.py)" % name,
            "# %d balls; sphere k is data line k (the file's ids start at %s); decimals as written" %
            (count, first_id)]
    return "\n".join(head + out) + "\n"


def convert_file(src, dst, name=None):
    text = Path(src).read_text(encoding="ascii")
    Path(dst).parent.mkdir(parents=True, exist_ok=True)
    Path(dst).write_text(convert_text(text, name or Path(src).name), encoding="ascii")


def main(argv):
    if len(argv) != 2:
        sys.exit(__doc__)
    src, dst = Path(argv[0]), Path(argv[1])
    try:
        if src.is_dir():
            files = sorted(src.rglob("*.txt"))
            if not files:
                sys.exit("song2022_to_xyzr.py: no *.txt below %s" % src)
            for f in files:
                rel = f.relative_to(src)
                convert_file(f, dst / rel.with_suffix(".xyzr"), str(rel))
            print("converted %d files into %s" % (len(files), dst))
        else:
            convert_file(src, dst)
    except FormatError as e:
        sys.exit("song2022_to_xyzr.py: %s" % e)


if __name__ == "__main__":
    main(sys.argv[1:])
