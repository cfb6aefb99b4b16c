"""vorball.cells computes what `vorball cells` computes: the same tables
byte for byte, arrays that print as the TSV's fields, enclosures of the
two-ball closed forms, and the command's errors for bad options."""
import math
import os

import numpy as np
import pytest
import vorball

from conftest import cli, corpus, strip_provenance

FAST = dict(tolerance=1e-2, max_patches=300)
FAST_ARGS = ["--tolerance", "1e-2", "--max-patches", "300"]


def tsv(text):
    return [line.split("\t") for line in text.splitlines()[1:]]


def g12(x):
    return "%.12g" % x


def text_lo(x):
    """The TSV's lower end: moved down by 1e-11 of itself, then 12 digits."""
    return "0" if x <= 0 else g12(math.nextafter(x - x * 1e-11, -math.inf))


def text_hi(x):
    return g12(0.0 if x <= 0 else math.nextafter(x + x * 1e-11, math.inf))


def fields(mid, lo, hi):
    return [g12(mid), text_lo(lo), text_hi(hi)]


@pytest.mark.parametrize("case", ["contained_sphere", "internally_tangent", "hexagonal_ring",
                                  "intersecting_spheres"])
def test_corpus_case_same_as_command(case, tmp_path):
    path = corpus("inputs", case + ".xyzr")
    contacts = tmp_path / "c.tsv"
    out, _ = cli("cells", path, *FAST_ARGS, "--threads", "2", "--contacts", contacts)
    c = vorball.cells(path, contacts=True, **FAST)
    # the library's writers, the same bytes
    assert c.to_text() == out
    assert c.contacts_text() == strip_provenance(contacts.read_text())
    # the arrays, printed as the TSV prints them, are its fields
    rows = tsv(out)
    assert len(rows) == len(c) > 0
    for k, r in enumerate(rows):
        assert int(r[0]) == k
        assert r[5:8] == fields(c.volume[k], c.volume_lo[k], c.volume_hi[k])
        assert r[8:11] == fields(c.sas[k], c.sas_lo[k], c.sas_hi[k])
    crows = tsv(strip_provenance(contacts.read_text()))
    assert len(crows) == len(c.id1)
    for k, r in enumerate(crows):
        assert [int(r[0]), int(r[1])] == [c.id1[k], c.id2[k]]
        assert r[2:5] == fields(c.area[k], c.area_lo[k], c.area_hi[k])
    assert np.all(c.volume_lo <= c.volume) and np.all(c.volume <= c.volume_hi)
    assert np.all(c.sas_lo <= c.sas) and np.all(c.sas <= c.sas_hi)
    if case == "contained_sphere":
        assert c.empty.any() and np.all(c.volume_hi[c.empty] == 0)
        assert any(w.number == 850 for w in c.warnings)


def test_two_balls_closed_form():
    """Two unit balls 1.5 apart and one far (probe 1.4, R = 2.4): each cell
    is the ball less the cap beyond the bisector plane, the contact the
    disk on it; the lone ball is whole. Arrays in, the same as the file."""
    xyz = np.array([[0, 0, 0], [1.5, 0, 0], [0, 9, 0]], dtype=float)
    r = np.array([1.0, 1.0, 1.2])
    c = vorball.cells(xyz, r, tolerance=1e-4, contacts=True, threads=2)
    R, h = 2.4, 2.4 - 0.75
    vol = 4 / 3 * math.pi * R**3 - math.pi * h * h * (3 * R - h) / 3
    sas = 4 * math.pi * R * R - 2 * math.pi * R * h
    area = math.pi * (R * R - 0.75**2)
    for k in (0, 1):
        assert c.volume_lo[k] <= vol <= c.volume_hi[k]
        assert c.sas_lo[k] <= sas <= c.sas_hi[k]
        assert c.volume_hi[k] - c.volume_lo[k] <= 1e-4 * vol
    assert c.volume_lo[2] <= 4 / 3 * math.pi * 2.6**3 <= c.volume_hi[2]
    assert c.sas_lo[2] <= 4 * math.pi * 2.6**2 <= c.sas_hi[2]
    assert list(c.id1) == [0] and list(c.id2) == [1]
    assert c.area_lo[0] <= area <= c.area_hi[0]
    assert not c.loose.any() and not c.empty.any()


def test_two_balls_file_same_as_command(tmp_path):
    p = tmp_path / "two.xyzr"
    p.write_text("0 0 0 1.0\n1.5 0 0 1.0\n")
    out, _ = cli("cells", p, "--tolerance", "1e-5", "--probe", "0.5")
    assert vorball.cells(str(p), tolerance=1e-5, probe=0.5).to_text() == out


def test_no_contacts_unless_asked():
    c = vorball.cells(corpus("inputs", "hexagonal_ring.xyzr"), **FAST)
    assert c.id1 is None and c.contacts_text() is None


@pytest.mark.parametrize("kw,number", [(dict(probe=-1.0), 7), (dict(tolerance=1.0), 7),
                                       (dict(max_patches=10), 7), (dict(threads=-1), 7)])
def test_bad_options(kw, number):
    with pytest.raises(vorball.VorballError) as e:
        vorball.cells(corpus("inputs", "hexagonal_ring.xyzr"), **kw)
    assert e.value.number == number


def test_stats_and_page_as_the_command(tmp_path):
    """--stats' counts and the --html page (the library's page writer: the
    same bytes) of one structure."""
    path = corpus("inputs", "hexagonal_ring.xyzr")
    page = tmp_path / "cmd.html"
    _, err = cli("cells", path, *FAST_ARGS, "--contacts", tmp_path / "c.tsv", "--stats",
                 "--html", page)
    mine = tmp_path / "py.html"
    c = vorball.cells(path, contacts=True, html=mine, title="vorball cells %s" % path, **FAST)
    assert mine.read_bytes() == page.read_bytes()
    line = [x for x in err.splitlines() if x.startswith("cells: ")][0]
    s = c.stats
    want = ("cells: %d atoms, %d patches, %d empty, %d loose, %d contacts, "
            % (s["atoms"], s["patches"], s["empty"], s["loose"], s["contacts"]))
    assert line.startswith(want) and line.endswith(", %d atoms in closed form" % s["closed"])
    assert s["atoms"] == len(c) > 0 and s["contacts"] == len(c.id1) and s["seconds"] > 0
    # The default title is the command's for a file given by its path.
    other = tmp_path / "default.html"
    vorball.cells(path, contacts=True, html=other, **FAST)
    assert other.read_bytes() == page.read_bytes()


def test_frames_as_the_command(tmp_path):
    """cells_frames is `cells --traj --frames`: the same rows (less the
    frame column) for each frame of an XTC over its PDB topology."""
    top, xtc = corpus("data", "ngl_md_ascii_trj.pdb"), corpus("data", "ngl_md_10frames.xtc")
    out, contacts = tmp_path / "a.tsv", tmp_path / "c.tsv"
    cli("cells", top, "--traj", xtc, "--frames", "1:4:2", *FAST_ARGS, "-o", out,
        "--contacts", contacts)
    got = vorball.cells_frames(top, xtc, start=1, stop=4, step=2, contacts=True, **FAST)
    assert [c.frame for c in got] == [1, 3]
    for table, text in ((out, lambda c: c.to_text()), (contacts, lambda c: c.contacts_text())):
        want = [r for r in tsv(strip_provenance(table.read_text()))]
        mine = [[str(c.frame)] + r for c in got for r in tsv(strip_provenance(text(c)))]
        assert mine == want and len(mine) > 0
    with pytest.raises(vorball.VorballError) as e:
        vorball.cells_frames(top, xtc, start=20)
    _, err = cli("cells", top, "--traj", xtc, "--frames", "20:", rc=e.value.exit_status)
    assert "E%d" % e.value.number in err
