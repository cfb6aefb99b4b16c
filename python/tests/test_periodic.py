"""Periodic boxes through the package (issue 34): vorball.vertices(...,
periodic=True / box=...), vorball.cells(..., box=...) and
vorball.periodic_frames give the bytes and the numbers of `vorball
vertices --periodic`, `vorball cells --periodic` and `--frames`, the
members' image shifts as arrays; a bad box raises E120."""
import os
import re
import subprocess
import sys

import numpy as np
import pytest
import vorball

from conftest import ROOT, cli

CHECK = os.path.join(ROOT, "tests", "pipeline", "periodic_check.py")
MEMBER = re.compile(r"(\d+)@\((-?\d+),(-?\d+),(-?\d+)\)")


def generated(case, tmp_path):
    """(path of the box's atoms, the --box tokens) of periodic_check.py's case."""
    subprocess.run([sys.executable, CHECK, "gen", case, str(tmp_path)], check=True)
    box = open(tmp_path / (case + ".box")).read().split()
    return str(tmp_path / (case + ".xyzr")), box


def parse_periodic(text):
    """(ids, shifts, xyz, t) of a periodic tsv: lists of arrays, then arrays."""
    ids, shifts, xyz, t = [], [], [], []
    for line in text.splitlines():
        if line.startswith("#") or not line:
            continue
        f = line.split("\t")
        m = MEMBER.findall(f[0])
        assert ",".join("%s@(%s,%s,%s)" % g for g in m) == f[0]
        ids.append(np.array([int(g[0]) for g in m]))
        shifts.append(np.array([[int(v) for v in g[1:]] for g in m]).reshape(-1, 3))
        xyz.append([float(v) for v in f[1:4]])
        t.append(float(f[4]))
    return ids, shifts, np.array(xyz).reshape(-1, 3), np.array(t)


def same_periodic(res, text):
    ids, shifts, xyz, t = parse_periodic(text)
    assert len(res.ids) == len(ids) > 0
    assert all(np.array_equal(a, b) for a, b in zip(res.ids, ids))
    assert all(np.array_equal(a, b) for a, b in zip(res.shifts, shifts))
    assert np.array_equal(res.xyz, xyz) and np.array_equal(res.t, t)


@pytest.mark.parametrize("case", ["fcc", "random", "triclinic"])
def test_vertices_as_the_command(case, tmp_path):
    path, box = generated(case, tmp_path)
    out, _ = cli("vertices", "--periodic", "--box", *box, "--device", "ref", path)
    res = vorball.vertices(path, device="ref", box=box)
    assert isinstance(res, vorball.PeriodicResult)
    assert res.to_text() == out
    same_periodic(res, out)
    assert res.atoms == len(open(path).read().split("\n")) - 1
    assert res.spheres > res.atoms and res.rho > 0
    assert re.search(r"^# complete: \d+ certified vertices of the periodic diagram", out, re.M)
    # Some vertex reaches across the box: a member with a non-zero shift.
    assert any(np.any(s != 0) for s in res.shifts)
    # Every vertex's canonical translate has a member of its smallest id at shift 0.
    for i, s in zip(res.ids, res.shifts):
        assert np.any((i == i.min()) & np.all(s == 0, axis=1))
    ids, shifts, xyz, t = res
    assert len(ids) == len(shifts) == len(xyz) == len(t)


def test_json_and_box_spellings(tmp_path):
    path, box = generated("fcc", tmp_path)  # box "4 4 4"
    out, _ = cli("vertices", "--box", *box, "--output-format", "json", "--device", "ref", path)
    a = vorball.vertices(path, device="ref", box=box)
    assert a.to_text("json") == out
    # Numbers, a 3x3 matrix and right angles spell the same box.
    for spelled in ((4, 4, 4), (4.0, 4.0, 4.0), np.diag([4.0, 4.0, 4.0]),
                    (4, 4, 4, 90, 90, 90)):
        b = vorball.vertices(path, device="ref", box=spelled)
        assert b.to_text() == a.to_text()
        assert np.array_equal(b.box, np.diag([4.0, 4.0, 4.0]))
    p = tmp_path / "fcc.tsv"
    a.write(p)
    assert p.read_text() == a.to_text()


GRO = """three waters, a triclinic box
 6
    1SOL     OW    1   0.131   0.152   0.120
    1SOL    HW1    2   0.201   0.088   0.097
    2SOL     OW    3   0.497   0.423   0.318
    2SOL    HW1    4   0.571   0.470   0.296
    3SOL     OW    5   0.289   0.611   0.604
    3SOL    HW1    6   0.237   0.662   0.541
   0.80000   0.75000   0.70000   0.00000   0.00000   0.10000   0.00000   0.05000  -0.05000
"""


def test_the_files_box(tmp_path):
    """A GRO file's triclinic box (nm, its last line) is used with
    periodic=True, and equals the same box given as a matrix."""
    gro = tmp_path / "box.gro"
    gro.write_text(GRO)
    out, _ = cli("vertices", "--periodic", "--water", "--device", "ref", gro)
    s = vorball.read(gro, water=True)
    res = vorball.vertices(s, device="ref", periodic=True)
    assert res.to_text() == out
    same_periodic(res, out)
    assert np.array_equal(res.box, [[8, 0, 0], [1, 7.5, 0], [0.5, -0.5, 7]])
    m = vorball.vertices(s, device="ref", box=[["8", "0", "0"], [1, 7.5, 0], [0.5, -0.5, 7]])
    assert m.to_text() == res.to_text()


def test_frames_each_in_its_box(tmp_path):
    """Two GRO frames with different boxes: periodic_frames gives the
    command's `--frames` file, frame by frame."""
    second = GRO.replace("0.80000   0.75000   0.70000", "0.90000   0.80000   0.75000")
    gro = tmp_path / "two.gro"
    gro.write_text(GRO + second)
    out, _ = cli("vertices", "--periodic", "--frames", "0:2:1", "--water", "--device", "ref", gro)
    got = vorball.periodic_frames(gro, water=True, device="ref")
    head = out[:out.index("# frame ")]
    text = head + "".join("# frame %d (model %d)\n" % (r.frame, r.model) + r.to_text()
                          for r in got)
    assert [r.frame for r in got] == [0, 1]
    assert text == out
    assert not np.array_equal(got[0].box, got[1].box)
    assert got[1].box[0, 0] == 9.0


def test_engine_periodic_as_the_command(tmp_path):
    """An Engine (its device opened once) runs each GRO frame in the box
    the frame carries: the command's `--frames` bytes frame by frame, the
    same as vorball.vertices; an open run on the same engine between
    them changes nothing."""
    second = GRO.replace("0.80000   0.75000   0.70000", "0.90000   0.80000   0.75000")
    gro = tmp_path / "two.gro"
    gro.write_text(GRO + second)
    out, _ = cli("vertices", "--periodic", "--frames", "0:2:1", "--water", "--device", "ref", gro)
    head = out[:out.index("# frame ")]
    with vorball.Engine(device="ref") as eng:
        got = []
        for k, f in enumerate(vorball.frames(gro, water=True)):
            got.append(eng.vertices(f, periodic=True))
            assert isinstance(got[-1], vorball.PeriodicResult)
            assert got[-1].to_text() == vorball.vertices(f, device="ref", periodic=True).to_text()
            if k == 0:
                opened = eng.vertices(f)  # the open diagram, same engine
                assert not isinstance(opened, vorball.PeriodicResult) and len(opened.t) > 0
        boxed = eng.vertices(f, box=(9, 8, 7.5))
        with pytest.raises(vorball.VorballError):
            eng.vertices(f, periodic=True, arcs=True)
    text = head + "".join("# frame %d (model %d)\n" % (k, k + 1) + r.to_text()
                          for k, r in enumerate(got))
    assert text == out
    assert got[1].box[0, 0] == 9.0 and got[0].box[0, 0] == 8.0
    assert np.array_equal(boxed.box, np.diag([9.0, 8.0, 7.5]))


def contact_rows(text):
    rows = [line.split("\t") for line in text.splitlines() if line and not line.startswith("#")]
    return rows[1:] if rows and not rows[0][0].isdigit() else rows


def test_cells_as_the_command(tmp_path):
    path, box = generated("random", tmp_path)
    atoms, contacts = tmp_path / "atoms.tsv", tmp_path / "contacts.tsv"
    cli("cells", "--periodic", "--box", *box, "--contacts", contacts, "-o", atoms, path)
    c = vorball.cells(path, box=box, contacts=True)
    strip = lambda p: "".join(l for l in open(p) if not l.startswith(  # noqa: E731
        ("# tool: ", "# input: ", "# options: ")))
    assert c.to_text() == strip(atoms)
    assert c.contacts_text() == strip(contacts)
    rows = contact_rows(c.contacts_text())
    assert len(rows) == len(c.id1) > 0
    across = 0
    for row, i, j, s in zip(rows, c.id1, c.id2, c.shift2):
        assert int(row[0]) == i
        m = MEMBER.fullmatch(row[1])
        assert m and int(m.group(1)) == j
        assert [int(v) for v in m.groups()[1:]] == list(s)
        across += bool(np.any(s != 0))
    assert across > 0
    # Open cells have no shifts.
    assert vorball.cells(path, contacts=True).shift2 is None


@pytest.mark.parametrize("box", [(1, 2), tuple(range(1, 11)), (1, 0, 0, 2, 0, 0, 0, 0, 1),
                                 (4, 4, -4),
                                 (4, 4, 4, 90, 90, 200), ("4", "x", "4")])
def test_bad_box_is_e120(box, tmp_path):
    path, _ = generated("fcc", tmp_path)
    with pytest.raises(vorball.VorballError) as e:
        vorball.vertices(path, device="ref", box=box)
    assert e.value.number == 120
    with pytest.raises(vorball.VorballError) as e:
        vorball.cells(path, box=box)
    assert e.value.number == 120


def test_no_box_is_e120(tmp_path):
    path, _ = generated("fcc", tmp_path)
    for call in (lambda: vorball.vertices(path, device="ref", periodic=True),
                 lambda: vorball.cells(path, periodic=True)):
        with pytest.raises(vorball.VorballError) as e:
            call()
        assert e.value.number == 120


def test_verify_as_the_command(tmp_path):
    """verify(..., box=) judges a periodic file as `verify --periodic --json`
    does: a good file certified line by line, a tampered one flagged."""
    import json
    path, box = generated("triclinic", tmp_path)
    res = vorball.vertices(path, device="ref", box=box)
    good = tmp_path / "good.tsv"
    res.write(good)
    rows = res.to_text().splitlines(keepends=True)
    body = [k for k, line in enumerate(rows) if not line.startswith("#")]
    f = rows[body[0]].split("\t")
    f[4] = repr(float(f[4]) + 0.25)                        # a wrong radius
    rows[body[0]] = "\t".join(f)
    g = rows[body[1]].split("\t")
    m = MEMBER.findall(g[0])
    g[0] = ",".join("%s@(%d,%s,%s)" % (a, int(b) + 1, c, d) for a, b, c, d in m)  # a translate
    rows[body[1]] = "\t".join(g)
    bad = tmp_path / "bad.tsv"
    bad.write_text("".join(rows))
    for vertices, rc in ((good, 0), (bad, 1), (res, 0)):
        r = vorball.verify(path, vertices, box=box)
        assert isinstance(r, vorball.PeriodicReport)
        if not isinstance(vertices, vorball.PeriodicResult):
            out, _ = cli("verify", "--periodic", "--box", *box, "--json", path, vertices, rc=rc)
            want = json.loads(out)
            assert {k: want[k] for k in r.counts} == r.counts
            assert want["ok"] == r.ok
        assert r.counts["lines"] == len(res.t) == len(r.flags) == len(r.problems)
        assert r.ok == (vertices is not bad)
    assert r.ok and r.counts["certified"] == len(res.t)
    r = vorball.verify(path, bad, box=box)
    assert r.flags[1] & vorball.NOT_CANONICAL and r.problems[0] != 0
    assert r.line[0] == body[0] + 1
    with pytest.raises(vorball.VorballError) as e:
        vorball.verify(path, good, box=(1, 2))
    assert e.value.number == 120


def test_xtc_frames_in_their_boxes():
    """An MD trajectory (183 atoms, XTC): every frame in the box it carries,
    the bytes of `vertices --periodic --traj --frames`."""
    from conftest import corpus
    top, xtc = corpus("data", "ngl_md_ascii_trj.pdb"), corpus("data", "ngl_md_10frames.xtc")
    out, _ = cli("vertices", "--periodic", "--traj", xtc, "--frames", "0:10:3", "--water",
                 "--device", "ref", top)
    got = vorball.periodic_frames(top, xtc, start=0, stop=10, step=3, water=True, device="ref")
    assert [r.frame for r in got] == [0, 3, 6, 9]
    head = out[:out.index("# frame ")]
    assert head + "".join("# frame %d (model %d)\n" % (r.frame, r.model) + r.to_text()
                          for r in got) == out
    assert all(r.atoms == 183 and len(r.t) > 0 for r in got)
    assert len({r.box.tobytes() for r in got}) > 1  # the box changes from frame to frame
