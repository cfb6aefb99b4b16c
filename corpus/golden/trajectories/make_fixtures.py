#!/usr/bin/env python3
"""Writes the expected coordinates of the XTC and TRR files in corpus/data as
MDAnalysis reads them, for tests/core/test_trajectories.c; and the two
trajectories it writes itself from corpus/data/ngl_md_ascii_trj.pdb.

Run once, by hand, in a throwaway virtual environment (MDAnalysis is not a
dependency of vorball; the files it writes are committed):

    python3 -m venv /tmp/mda && /tmp/mda/bin/pip install MDAnalysis
    /tmp/mda/bin/python corpus/golden/trajectories/make_fixtures.py

Each .expect file: a header line, then per frame
    frame K natoms N step S time T precision P
    box b0 .. b8
    atom I x y z        (every atom of files of 20 atoms or fewer; atoms 0, 1, 2 and every
                         97th and the last of larger ones)
    sum SX SY SZ        (the coordinates summed in index order, in double)
Coordinates are in nm as stored (MDAnalysis' raw libmdaxdr values, float32
or float64), printed with 17 significant digits so they read back exactly.
"""
import os
import sys

import numpy as np
import MDAnalysis as mda
from MDAnalysis.lib.formats.libmdaxdr import TRRFile, XTCFile

here = os.path.dirname(os.path.abspath(__file__))
data = os.path.join(here, '..', '..', 'data')


def g(v):
    return '%.17g' % float(v)


def write_expect(path, frames, source):
    with open(path, 'w') as out:
        out.write('# %s as read by MDAnalysis %s (libmdaxdr)\n' % (source, mda.__version__))
        for k, (fr, x) in enumerate(frames):
            n = x.shape[0]
            prec = getattr(fr, 'prec', 0.0)
            out.write('frame %d natoms %d step %d time %s precision %s\n'
                      % (k, n, fr.step, g(fr.time), g(prec)))
            out.write('box %s\n' % ' '.join(g(v) for v in np.asarray(fr.box).ravel()))
            pick = range(n) if n <= 20 else sorted(set([0, 1, 2, n - 1] + list(range(0, n, 97))))
            for i in pick:
                out.write('atom %d %s %s %s\n' % (i, g(x[i, 0]), g(x[i, 1]), g(x[i, 2])))
            s = [0.0, 0.0, 0.0]
            for i in range(n):
                for a in range(3):
                    s[a] += float(x[i, a])
            out.write('sum %s %s %s\n' % (g(s[0]), g(s[1]), g(s[2])))


def expect_xtc(name):
    with XTCFile(os.path.join(data, name)) as f:
        frames = [(fr, fr.x.copy()) for fr in f]
    write_expect(os.path.join(here, name + '.expect'), frames, name)


def expect_trr(name):
    with TRRFile(os.path.join(data, name)) as f:
        frames = [(fr, fr.x.copy()) for fr in f if fr.hasx]
    write_expect(os.path.join(here, name + '.expect'), frames, name)


def write_ngl():
    """The first 10 frames of the NGL MD trajectory (a GROMACS run written
    as PDB by trjconv) as XTC (precision 1000/nm, GROMACS' default) and TRR
    (float), by MDAnalysis' writers."""
    u = mda.Universe(os.path.join(data, 'ngl_md_ascii_trj.pdb'))
    for ext in ('xtc', 'trr'):
        with mda.Writer(os.path.join(data, 'ngl_md_10frames.' + ext), u.atoms.n_atoms) as w:
            for ts in u.trajectory[:10]:
                w.write(u.atoms)


if __name__ == '__main__':
    write_ngl()
    for name in ('xtc_10x10.xtc', 'cobrotoxin_frame1.xtc', 'ngl_md_10frames.xtc'):
        expect_xtc(name)
    for name in ('trr_10x10.trr', 'ngl_md_10frames.trr'):
        expect_trr(name)
    sys.exit(0)
