#!/usr/bin/env python3
"""Synthesizes a long multi-model PDB trajectory from a short one, for frame
throughput and strong-scaling runs of `vorball channels`.

usage: synth_trajectory.py IN.pdb FRAMES OUT.pdb [--amplitude A] [--seed S]

Frame k (0-based) of OUT is model (k mod M) of IN's M models with every atom
coordinate moved by a pseudo-random offset, uniform in [-A, A] Angstrom
(default A = 0.100) in steps of 0.001: the coordinates stay 3-decimal PDB
numbers and are computed on integers of thousandths, never floats, so OUT is
the same bytes on every machine. The offset of (frame, atom, axis) comes from
splitmix64 of (S, k, atom, axis) (default S = 19), independent of the order
of evaluation. Everything else of an ATOM/HETATM line is kept; each frame is
MODEL k+1 ... TER, ENDMDL; the file ends with END. The corpus's 51-frame
ngl_md_ascii_trj.pdb (183 atoms) makes a 500-frame file of about 7.6 MB.
Standard library only.
"""
import sys

MASK = (1 << 64) - 1


def splitmix64(x):
    x = (x + 0x9E3779B97F4A7C15) & MASK
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & MASK
    return x ^ (x >> 31)


def offset(seed, frame, atom, axis, amp):
    """An integer in [-amp, amp] (thousandths), a function of its arguments."""
    h = splitmix64(seed & MASK)
    for v in (frame, atom, axis):
        h = splitmix64(h ^ v)
    return (h % (2 * amp + 1)) - amp


def thousandths(field, where):
    """'  32.020' -> 32020, exactly (a PDB coordinate has 3 decimals)."""
    s = field.strip()
    neg = s.startswith("-")
    body = s[1:] if neg or s.startswith("+") else s
    whole, dot, frac = body.partition(".")
    if not dot or len(frac) != 3 or not (whole or "0").isdigit() or not frac.isdigit():
        sys.exit("synth_trajectory: %s: coordinate '%s' is not a 3-decimal number" % (where, s))
    v = int(whole or "0") * 1000 + int(frac)
    return -v if neg else v


def field8(v):
    """Thousandths as an 8-wide %8.3f field, without floating point."""
    sign = "-" if v < 0 else ""
    a = abs(v)
    text = "%s%d.%03d" % (sign, a // 1000, a % 1000)
    if len(text) > 8:
        sys.exit("synth_trajectory: coordinate %s does not fit PDB's 8 columns" % text)
    return text.rjust(8)


def read_models(path):
    models, cur = [], None
    with open(path) as f:
        for lineno, line in enumerate(f, 1):
            rec = line[:6]
            if rec.startswith("MODEL"):
                cur = []
            elif rec.startswith("ENDMDL"):
                if cur:
                    models.append(cur)
                cur = None
            elif rec in ("ATOM  ", "HETATM"):
                if cur is None:  # a single-model file without MODEL records
                    cur = []
                line = line.rstrip("\n")
                if len(line) < 54:
                    sys.exit("synth_trajectory: %s:%d: ATOM line shorter than 54 columns" % (path, lineno))
                xyz = [thousandths(line[30 + 8 * a:38 + 8 * a], "%s:%d" % (path, lineno)) for a in range(3)]
                cur.append((line, xyz))
    if cur:
        models.append(cur)
    if not models:
        sys.exit("synth_trajectory: no atoms in " + path)
    return models


def main(argv):
    args = list(argv)
    amp, seed = 100, 19
    for opt in ("--amplitude", "--seed"):
        if opt in args:
            k = args.index(opt)
            val = args[k + 1]
            del args[k:k + 2]
            if opt == "--seed":
                seed = int(val)
            else:
                amp = thousandths(val if "." in val else val + ".000", "--amplitude")
                if "." in val and len(val.split(".")[1]) != 3:
                    sys.exit("synth_trajectory: --amplitude needs 3 decimals, e.g. 0.100")
    if len(args) != 3:
        sys.exit(__doc__)
    src, frames, dst = args[0], int(args[1]), args[2]
    if frames < 1 or amp < 0:
        sys.exit("synth_trajectory: FRAMES must be >= 1 and the amplitude >= 0")
    models = read_models(src)
    with open(dst, "w") as out:
        out.write("REMARK    synth_trajectory.py: %d frames from the %d models of %s, "
                  "offsets up to %s A, seed %d\n" % (frames, len(models), src.split("/")[-1],
                                                     field8(amp).strip(), seed))
        for k in range(frames):
            out.write("MODEL %8d\n" % (k + 1))
            for atom, (line, xyz) in enumerate(models[k % len(models)]):
                moved = "".join(field8(xyz[a] + offset(seed, k, atom, a, amp)) for a in range(3))
                out.write(line[:30] + moved + line[54:] + "\n")
            out.write("TER\nENDMDL\n")
        out.write("END\n")
    sys.stderr.write("synth_trajectory: %d frames of %d atoms to %s\n" %
                     (frames, len(models[0]), dst))


if __name__ == "__main__":
    main(sys.argv[1:])
