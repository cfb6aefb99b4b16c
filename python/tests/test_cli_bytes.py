"""The package computes what the command computes: the same vertex bytes
on the corpus, the same counters, from files and from arrays."""
import glob
import os

import numpy as np
import pytest
import vorball

from conftest import cli, corpus, parse_vertices, same_vertices

CASES = sorted(os.path.basename(p)[:-5] for p in glob.glob(corpus("inputs", "*.xyzr")))


def test_corpus_has_cases():
    assert len(CASES) >= 10


@pytest.mark.parametrize("case", CASES)
def test_corpus_case_same_bytes(case):
    path = corpus("inputs", case + ".xyzr")
    out, _ = cli("vertices", "--device", "ref", path)
    res = vorball.vertices(path, device="ref")
    assert res.to_text() == out
    same_vertices(res, out)
    # The golden answer of the case, as its pipeline test reads it.
    gold = parse_vertices(open(corpus("golden", case + ".tsv")).read())
    assert len(res.ids) == len(gold[0])


@pytest.mark.parametrize("case", ["degree5_vertex", "contained_sphere", "large_offset"])
def test_arrays_of_a_file_same_bytes(case):
    """The doubles of a file's spheres, as float64 arrays: repr gives the
    file's decimals back, so the vertices are the command's."""
    path = corpus("inputs", case + ".xyzr")
    s = vorball.read(path)
    out, _ = cli("vertices", "--device", "ref", path)
    assert vorball.vertices(s.xyz, s.r, device="ref").to_text() == out


def test_crambin_pdb_same_bytes_and_formats():
    path = corpus("data", "1crn.pdb")
    out, _ = cli("vertices", "--device", "ref", path)
    res = vorball.vertices(vorball.read(path), device="ref")
    assert res.to_text() == out
    assert len(res.t) == 1996 and res.certificate.complete
    assert res.certificate.certified == 1996
    assert res.certificate.text in out
    # The counters are the numbers of the certificate line.
    c = res.certificate
    assert c.quadruples > 0 and c.cover_cells > 0
    assert "direction cover of %d cells, %d quadruples," % (c.cover_cells, c.quadruples) in c.text
    for fmt in ("json", "voronota"):
        o, _ = cli("vertices", "--device", "ref", "--output-format", fmt, path)
        assert res.to_text(fmt) == o


def test_crambin_float32_like_mdanalysis_same_bytes():
    """MDAnalysis keeps positions as float32: the shortest float32 decimals
    are the PDB's 3-decimal coordinates, so the command's bytes again."""
    path = corpus("data", "1crn.pdb")
    s = vorball.read(path)
    xyz32 = s.xyz.astype(np.float32)
    out, _ = cli("vertices", "--device", "ref", path)
    res = vorball.vertices(xyz32, s.r.astype(np.float32), device="ref")
    assert res.to_text() == out


def test_stats_are_the_commands():
    path = corpus("inputs", "crambin_fragment.xyzr")
    _, err = cli("vertices", "--device", "ref", "--proposer", "sampling", "--stats", path)
    res = vorball.vertices(path, device="ref", proposer="sampling")
    # The command's own process clock (process_*_s: reading, writing the file,
    # freeing) has no counterpart in a call that writes no file.
    want = dict(line.split("\t", 1) for line in err.splitlines()
                if "\t" in line and not line.startswith("process_"))
    got = {k: str(v) for k, v in res.stats.items()}
    # The numbers parse to the same values (str of a parsed float may differ in form);
    # the seconds (keys ending in _s) differ run to run: only their presence counts.
    assert want.keys() == got.keys()
    for k, v in want.items():
        if not k.endswith("_s"):
            assert str(vorball._vertices._number(v)) == got[k], k
    assert res.stats["certified_vertices"] == len(res.t)
    assert not res.certificate.complete and res.certificate.text == ""


def test_sampling_and_cover_same_vertices():
    path = corpus("inputs", "jittered_lattice.xyzr")
    a = vorball.vertices(path, device="ref")
    b = vorball.vertices(path, device="ref", proposer="sampling", samples=40)
    assert len(a.ids) == len(b.ids) > 0
    assert all(np.array_equal(x, y) for x, y in zip(a.ids, b.ids))
    assert np.array_equal(a.xyz, b.xyz) and np.array_equal(a.t, b.t)


def test_pocl_device_same_bytes():
    """The OpenCL CPU device (PoCL) gives the reference's bytes, as the
    command does (or falls back with W760 where there is none)."""
    path = corpus("inputs", "crambin_fragment.xyzr")
    ref = vorball.vertices(path, device="ref")
    cpu = vorball.vertices(path, device="cpu")
    assert cpu.to_text() == ref.to_text()
    assert cpu.backend == "opencl" or any(w.number == 760 for w in cpu.warnings)


def test_threads_do_not_change_bytes():
    path = corpus("inputs", "bcc_lattice.xyzr")
    texts = {vorball.vertices(path, device="ref", threads=t).to_text() for t in (1, 3)}
    assert len(texts) == 1
