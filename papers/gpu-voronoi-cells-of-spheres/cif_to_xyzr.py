#!/usr/bin/env python3
"""Writes the spheres vorball reads from an mmCIF file as XYZR lines 'x y z r'.

usage: cif_to_xyzr.py IN.cif OUT.xyzr [--water] [--no-hydrogens] [--model N]

vorball has no command that prints the spheres it reads, so this mirrors its
mmCIF reader (core/input/read_mmcif.c, input_atoms.c, radii.c): the first
_atom_site loop; the first model (or model N by pdbx_PDB_model_num); water
(HOH, WAT, ...) dropped unless --water; per residue only the first alternate
location; element from type_symbol (else from the atom name); radius from
vorball's built-in element table (Bondi), 1.70 for an unknown element.
Coordinates are copied as the exact decimals of the file (Python decimal,
never floats); radii are the table's decimal strings. Order = file order, so
line i (0-based) is sphere i of `vorball ... IN.cif`.
Standard library only.
"""
import sys
from decimal import Decimal, InvalidOperation

# core/input/radii.c, builtin[] (keep in step with it).
RADII = {
    "H": "1.20", "D": "1.20", "C": "1.70", "N": "1.55", "O": "1.52", "S": "1.80",
    "P": "1.80", "F": "1.47", "CL": "1.75", "BR": "1.85", "I": "1.98", "SE": "1.90",
    "NA": "2.27", "MG": "1.73", "K": "2.75", "CA": "2.31", "FE": "1.40", "ZN": "1.39",
    "CU": "1.40", "MN": "1.40", "CO": "1.40", "NI": "1.63", "B": "1.92", "AL": "1.84",
    "SI": "2.10", "AS": "1.85", "HE": "1.40", "NE": "1.54", "AR": "1.88", "KR": "2.02",
    "XE": "2.16", "LI": "1.82",
}
DEFAULT_RADIUS = "1.70"
# core/input/input_atoms.c, vbi_is_water().
WATER = {"HOH", "WAT", "DOD", "H2O", "TIP", "TIP3", "TIP4", "SOL", "T3P", "T4P", "SPC"}
TWO_LETTER = {"CL", "BR", "SE", "NA", "MG", "CA", "FE", "ZN", "CU", "MN", "CO", "NI", "AL",
              "SI", "AS", "LI", "CD"}


def tokens(text):
    """CIF tokens in order: (kind, value); kind 'tag', 'loop', 'value', 'other'."""
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith(";"):  # text field up to a line starting with ';'
            buf = [line[1:]]
            i += 1
            while i < len(lines) and not lines[i].startswith(";"):
                buf.append(lines[i])
                i += 1
            yield ("value", "\n".join(buf))
            i += 1
            continue
        p, n = 0, len(line)
        while p < n:
            c = line[p]
            if c in " \t\r":
                p += 1
                continue
            if c == "#":
                break
            if c in "'\"":  # quoted: closes at the quote followed by blank or end
                q = p + 1
                while q < n and not (line[q] == c and (q + 1 == n or line[q + 1] in " \t\r")):
                    q += 1
                yield ("value", line[p + 1:q])
                p = q + 1
                continue
            q = p
            while q < n and line[q] not in " \t\r":
                q += 1
            word = line[p:q]
            p = q
            low = word.lower()
            if word.startswith("_"):
                yield ("tag", word)
            elif low == "loop_":
                yield ("loop", word)
            elif low.startswith("data_") or low.startswith("save_") or low in ("global_", "stop_"):
                yield ("other", word)
            else:
                yield ("value", word)
        i += 1


def element_from_name(name4):
    """vbi_element_from_name on a 4-column PDB name."""
    i = 0
    while i < 4 and i < len(name4) and not name4[i].isalpha():
        i += 1
    if i >= 4 or i >= len(name4):
        return ""
    a = name4[i].upper()
    b = name4[i + 1].upper() if i + 1 < min(4, len(name4)) else ""
    if i == 0 and a != "H" and (a + b) in TWO_LETTER:
        return a + b
    return a


def element_from_bare_name(name):
    return element_from_name((" " + name[:3]).ljust(4))


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    opts = argv[:]
    keep_water = "--water" in opts
    drop_h = "--no-hydrogens" in opts
    model_want = 0
    if "--model" in opts:
        k = opts.index("--model")
        model_want = int(opts[k + 1])
        args.remove(opts[k + 1])
    if len(args) != 2:
        sys.exit(__doc__)
    src, dst = args
    with open(src, encoding="utf-8", errors="replace") as f:
        text = f.read()
    it = tokens(text)
    cols = None
    for kind, val in it:
        if kind != "loop":
            continue
        kind, val = next(it, ("end", ""))
        if kind != "tag" or not val.lower().startswith("_atom_site."):
            continue
        cols = []
        while kind == "tag":
            cols.append(val.lower()[len("_atom_site."):])
            kind, val = next(it, ("end", ""))
        first = (kind, val)
        break
    if cols is None:
        sys.exit("cif_to_xyzr: no _atom_site loop in " + src)

    def col(name):
        return cols.index(name) if name in cols else -1

    cx, cy, cz = col("cartn_x"), col("cartn_y"), col("cartn_z")
    if min(cx, cy, cz) < 0:
        sys.exit("cif_to_xyzr: _atom_site loop lacks Cartn_x/y/z")
    ctype, cmodel, calt = col("type_symbol"), col("pdbx_pdb_model_num"), col("label_alt_id")
    catom = col("auth_atom_id") if col("auth_atom_id") >= 0 else col("label_atom_id")
    ccomp = [c for c in (col("auth_comp_id"), col("label_comp_id")) if c >= 0]
    casym = [c for c in (col("auth_asym_id"), col("label_asym_id")) if c >= 0]
    cseq = [c for c in (col("auth_seq_id"), col("label_seq_id")) if c >= 0]
    cicode = col("pdbx_pdb_ins_code")

    def null(v):
        return v in (".", "?")

    def pick(row, cs):
        for c in cs:
            if not null(row[c]):
                return row[c]
        return ""

    out = []
    stats = {"water": 0, "altloc": 0, "other_models": 0, "hydrogens": 0, "unknown": {}}
    taking, seen_model, found, last_model = True, False, False, None
    alt_key, alt_kept = None, " "
    row = []

    def take(row):
        nonlocal taking, seen_model, found, last_model, alt_key, alt_kept
        if cmodel >= 0 and not null(row[cmodel]):
            m = int(row[cmodel]) if row[cmodel].lstrip("-").isdigit() else 0
            if not seen_model or m != last_model:
                seen_model = True
                last_model = m
                taking = (not found) and (model_want == 0 or m == model_want)
                found = found or taking
        if not taking:
            stats["other_models"] += 1
            return
        resname = pick(row, ccomp)[:7]
        if not keep_water and resname in WATER:
            stats["water"] += 1
            return
        chain, seq = pick(row, casym)[:7], pick(row, cseq)
        icode = row[cicode] if cicode >= 0 and len(row[cicode]) == 1 and not null(row[cicode]) else " "
        alt = row[calt] if calt >= 0 and len(row[calt]) == 1 and not null(row[calt]) else " "
        key = (chain, seq, icode)
        if key != alt_key:
            alt_key, alt_kept = key, " "
        if alt != " ":
            if alt_kept == " ":
                alt_kept = alt
            if alt != alt_kept:
                stats["altloc"] += 1
                return
        t = row[ctype] if ctype >= 0 and not null(row[ctype]) else ""
        if t and len(t) <= 3:
            el = t.upper()
        else:
            name = row[catom] if catom >= 0 and not null(row[catom]) else ""
            el = element_from_bare_name(name[:7])
        if drop_h and el in ("H", "D"):
            stats["hydrogens"] += 1
            return
        r = RADII.get(el)
        if r is None:
            stats["unknown"][el] = stats["unknown"].get(el, 0) + 1
            r = DEFAULT_RADIUS
        xyz = []
        for c in (cx, cy, cz):
            try:
                d = Decimal(row[c])
            except InvalidOperation:
                sys.exit("cif_to_xyzr: coordinate %r is not a number" % row[c])
            xyz.append(format(d, "f"))
        out.append("%s %s %s %s\n" % (xyz[0], xyz[1], xyz[2], r))

    kind, val = first
    while kind == "value":
        row.append(val)
        if len(row) == len(cols):
            take(row)
            row = []
        kind, val = next(it, ("end", ""))
    if row:
        sys.exit("cif_to_xyzr: _atom_site loop ends inside a row")
    if model_want and not found:
        sys.exit("cif_to_xyzr: model %d is not in the input" % model_want)
    with open(dst, "w") as f:
        f.writelines(out)
    dropped = ", ".join("%s %d" % (k, v) for k, v in stats.items() if k != "unknown" and v)
    unk = ", ".join("%s x%d" % kv for kv in sorted(stats["unknown"].items()))
    print("cif_to_xyzr: %s: %d spheres%s%s" % (src, len(out), "; dropped: " + dropped if dropped else "",
                                               "; unknown elements (radius 1.70): " + unk if unk else ""),
          file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
