"""Exact judgement through the package: the command's report for files,
the same verdicts for vertices in memory, planted faults named."""
import numpy as np
import pytest
import vorball

from conftest import cli, corpus

CUBIC = corpus("inputs", "cubic_lattice.xyzr")
GOLDEN = corpus("golden", "cubic_lattice.tsv")


def test_files_same_report_as_the_command():
    out, _ = cli("verify", CUBIC, GOLDEN)
    rep = vorball.verify(CUBIC, GOLDEN)
    assert rep.text == out and rep.ok
    j, _ = cli("verify", CUBIC, GOLDEN, "--json")
    assert rep.json == j
    assert rep.counts["lines"] == rep.counts["certified"] == 8


def test_result_verifies_in_memory():
    s = vorball.read(corpus("inputs", "degree5_vertex.xyzr"))
    res = vorball.vertices(s, device="ref")
    for rep in (vorball.verify(s, res), vorball.verify(s.xyz, s.r, res),
                vorball.verify(s, None, tuple(res)), vorball.verify(s, vertices=res)):
        assert rep.ok and rep.counts["certified"] == len(res.t)
        assert np.array_equal(rep.line, np.arange(1, len(res.t) + 1))
        assert np.all(rep.problems == 0) and np.all(rep.dist < 1e-12)


def test_planted_faults_named():
    s = vorball.read(CUBIC)
    ids, xyz, t = vorball.vertices(s, device="ref")
    moved = xyz.copy()
    moved[0, 0] += 1e-7
    rep = vorball.verify(s, (ids, moved, t), tol=1e-8)
    assert not rep.ok and rep.problems[0] == vorball.WRONG_COORDS
    assert rep.classes(0) == ["wrong coordinates"] and abs(rep.dist[0] - 1e-7) < 1e-9
    assert vorball.verify(s, (ids, moved, t)).ok  # within the default tol 1e-6
    # A member dropped from the degree-8 vertex.
    cut = [ids[0][:-1]] + ids[1:]
    rep = vorball.verify(s, (cut, xyz, t))
    assert rep.problems[0] == vorball.MISSING and rep.counts["missing"] == 1
    # A vertex left out: found missing with complete (exact reference).
    rep = vorball.verify(s, (ids[1:], xyz[1:], t[1:]), complete=True)
    assert not rep.ok and rep.counts["missed"] == 1
    m_ids, m_xyz, m_t = rep.missed
    assert np.array_equal(m_ids[0], ids[0]) and np.array_equal(m_xyz[0], xyz[0])
    # Not a vertex: a sphere cuts the tangent sphere.
    rep = vorball.verify(s, ([np.array([0, 1, 2, 3])], np.array([[0.5, 0.5, 0.5]]),
                             np.array([0.6])))
    assert rep.problems[0] & vorball.NOT_VERTEX
    # The same line twice.
    rep = vorball.verify(s, (ids[:1] * 2, np.repeat(xyz[:1], 2, 0), np.repeat(t[:1], 2)))
    assert rep.problems[1] == vorball.DUPLICATE


def test_verify_errors():
    s = vorball.read(CUBIC)
    with pytest.raises(vorball.VorballError) as e:
        vorball.verify(s, ([], np.zeros((0, 3)), np.zeros(0)))
    assert e.value.number == 105 and e.value.exit_status == 15
    with pytest.raises(vorball.VorballError) as e:
        vorball.verify(s, ([np.array([0, 1, 1, 2])], np.zeros((1, 3)), np.zeros(1)))
    assert e.value.number == 101
    with pytest.raises(vorball.VorballError) as e:
        vorball.verify(s)
    assert e.value.number == 7
    with pytest.raises(vorball.VorballError) as e:
        vorball.verify(s, GOLDEN, tol=0)
    assert e.value.number == 7


def test_voronota_quadruples_grouped_in_memory():
    """Voronota's form of a degree-8 vertex is 5 quadruple lines; with
    format='voronota' they are judged as one vertex, as the command does."""
    s = vorball.read(CUBIC)
    res = vorball.vertices(s, device="ref")
    ids, xyz, t = [], [], []
    for line in res.to_text("voronota").splitlines():
        f = line.split()
        ids.append(np.array([int(v) for v in f[:4]]))
        xyz.append([float(v) for v in f[4:7]])
        t.append(float(f[7]))
    rep = vorball.verify(s, (ids, np.array(xyz), np.array(t)), format="voronota")
    assert rep.ok and rep.counts["lines"] == len(ids) > len(res.t)
    assert rep.counts["groups"] == len(res.t)
    alone = vorball.verify(s, (ids, np.array(xyz), np.array(t)))  # as tsv lines: each misses members
    assert not alone.ok and alone.counts["missing"] > 0
