"""The vertex flow with its completion (arc closure, faces and edges, the
certificate) through the library's one call: the same bytes, counts, faces
and edges as `vorball vertices --arcs --topology FILE`."""
import re

import numpy as np
import pytest
import vorball

from conftest import cli, corpus, same_vertices


def read_topology(path):
    """(faces, edges, edge_spheres) of a topology file, as int64 arrays."""
    faces, edges, spheres = [], [], []
    for line in open(path):
        f = line.rstrip("\n").split("\t")
        if f[0] == "face":
            faces.append([int(f[1]), int(f[2])])
        elif f[0] == "edge":
            edges.append([int(f[1]), int(f[2])])
            spheres.append([int(v) for v in f[3].split(",")])
    return (np.array(faces, dtype=np.int64).reshape(-1, 2),
            np.array(edges, dtype=np.int64).reshape(-1, 2),
            np.array(spheres, dtype=np.int64).reshape(-1, 3))


ARCS_LINE = re.compile(r"# arcs: every arc closed exactly: (\d+) vertices, (\d+) half arcs: "
                       r"(\d+) closed at a vertex, (\d+) to infinity, (\d+) closed loops, "
                       r"(\d+) undecided; (\d+) vertices added by tracing; (\d+) connected")


@pytest.mark.parametrize("case", ["cubic_lattice", "degree5_vertex", "crambin_fragment"])
def test_arcs_and_topology_as_the_command(case, tmp_path):
    path = corpus("inputs", case + ".xyzr")
    topo = tmp_path / "topo.tsv"
    out, _ = cli("vertices", "--device", "ref", "--arcs", "--topology", topo, path)
    res = vorball.vertices(path, device="ref", arcs=True, topology=True)
    assert res.to_text() == out
    same_vertices(res, out)
    a = res.arcs
    m = ARCS_LINE.search(out)
    assert m, out[:400]
    assert [a.vertices, a.half_arcs, a.closed, a.infinite, a.loops, a.undecided, a.added,
            a.components] == [int(v) for v in m.groups()]
    # The cover found every vertex: tracing adds none, and every arc closes.
    assert a.complete and a.added == 0 and a.vertices == len(res.t)
    assert a.half_arcs == a.closed + a.infinite + a.loops
    faces, edges, spheres = read_topology(topo)
    assert res.topology_text() == topo.read_text()  # the library's writer, the same bytes
    t = res.topology
    assert t.exact and t.unresolved == 0
    assert np.array_equal(t.faces, faces) and np.array_equal(t.edges, edges)
    assert np.array_equal(t.edge_spheres, spheres)
    # An edge between two vertices is counted from both ends; one to infinity once.
    finite = int((t.edges[:, 1] >= 0).sum())
    if a.loops == 0:
        assert not np.any(t.edges[:, 0] == t.edges[:, 1])
        assert a.closed == 2 * finite
    assert a.infinite == len(t.edges) - finite
    assert res.stats["arc_half_arcs"] == a.half_arcs


def test_cubic_lattice_numbers():
    """27 balls of a 3x3x3 lattice: 8 vertices (the cube centres), each of
    degree 8, 24 edges to infinity and 12 between them."""
    res = vorball.vertices(corpus("inputs", "cubic_lattice.xyzr"), device="ref", topology=True)
    assert res.arcs is not None  # topology implies arc closure
    assert (res.arcs.vertices, res.arcs.half_arcs, res.arcs.components) == (8, 48, 1)
    assert len(res.topology.faces) == 54 and len(res.topology.edges) == 36
    assert "# arcs: every arc closed exactly" not in res.certificate.text.splitlines()[0]
    assert res.certificate.text.splitlines()[1].startswith("arcs: every arc closed exactly")


def test_sampled_topology_without_arcs(tmp_path):
    """proposer='sampling' and topology alone: the sampling's evidence in
    doubles, as the command's (no arc closure)."""
    path = corpus("inputs", "crambin_fragment.xyzr")
    topo = tmp_path / "topo.tsv"
    out, _ = cli("vertices", "--device", "ref", "--proposer", "sampling", "--topology", topo,
                 path)
    res = vorball.vertices(path, device="ref", proposer="sampling", topology=True)
    assert res.to_text() == out
    assert res.arcs is None and not res.topology.exact
    faces, edges, spheres = read_topology(topo)
    assert np.array_equal(res.topology.faces, faces) and len(faces) > 0
    assert np.array_equal(res.topology.edges, edges)
    assert np.array_equal(res.topology.edge_spheres, spheres)


def test_sampling_with_arcs_same_bytes():
    """The sampling proposer with arc closure: the vertices its rays missed
    are added by tracing, as the command adds them."""
    path = corpus("data", "1crn_apbs.pqr")
    out, _ = cli("vertices", "--device", "ref", "--proposer", "sampling", "--samples", "8",
                 "--arcs", path)
    res = vorball.vertices(path, device="ref", proposer="sampling", samples=8, arcs=True)
    assert res.to_text() == out
    assert res.topology is None and res.arcs.undecided == 0
    m = ARCS_LINE.search(out)
    assert m and int(m.group(7)) == res.arcs.added


def test_engine_completes_as_the_call():
    path = corpus("inputs", "degree5_vertex.xyzr")
    with vorball.Engine(device="ref") as e:
        a = e.vertices(path, arcs=True, topology=True)
    b = vorball.vertices(path, device="ref", arcs=True, topology=True)
    assert a.to_text() == b.to_text() and a.arcs == b.arcs
    assert np.array_equal(a.topology.edges, b.topology.edges)


def test_no_completion_by_default():
    res = vorball.vertices(corpus("inputs", "cubic_lattice.xyzr"), device="ref")
    assert res.arcs is None and res.topology is None
    assert "arcs:" not in res.certificate.text


def test_verify_arcs_finds_what_a_file_misses(tmp_path):
    """verify(..., arcs=True) is `vorball verify --arcs`: three vertex lines
    cut from the cover's file are found again by arc closure, with the
    command's text and JSON."""
    path = corpus("inputs", "crambin_fragment.xyzr")
    full, _ = cli("vertices", "--device", "ref", path)
    lines = full.splitlines(keepends=True)
    body = [line for line in lines if not line.startswith("#")]
    dropped = [body[10], body[20], body[30]]
    cut = tmp_path / "cut.tsv"
    cut.write_text("".join(line for line in lines if line not in dropped))
    out, _ = cli("verify", path, cut, "--arcs", rc=1)
    js, _ = cli("verify", path, cut, "--arcs", "--json", rc=1)
    rep = vorball.verify(path, str(cut), arcs=True, threads=2)
    assert rep.text == out and rep.json == js
    assert not rep.ok and not rep.arcs.complete
    assert rep.arcs.added == 3 and rep.arcs.undecided == 0
    assert rep.arcs.vertices == len(body)
    want = sorted(tuple(int(v) for v in line.split("\t")[0].split(",")) for line in dropped)
    assert sorted(tuple(int(i) for i in ids) for ids in rep.arcs_missing[0]) == want
    assert rep.to_json()["arcs"]["added"] == 3
    # The whole list, in memory: closed, nothing added; without arcs, None.
    res = vorball.vertices(path, device="ref")
    whole = vorball.verify(path, res, arcs=True)
    assert whole.ok and whole.arcs.complete and whole.arcs.added == 0
    assert len(whole.arcs_missing[0]) == 0
    assert vorball.verify(path, res).arcs is None
