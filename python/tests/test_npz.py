"""`vorball vertices --output-format npz` is read by NumPy as it is
(np.load, no pickle) and holds the tsv file's vertices bit for bit: the
members (ids split by start), the doubles of xyz and t, the status and the
header (the certificate) as its comment."""
import numpy as np
import pytest

from conftest import cli, corpus, parse_vertices


@pytest.mark.parametrize("case", ["degree5_vertex", "contained_sphere", "cubic_lattice"])
def test_npz_equals_tsv(case, tmp_path):
    path = corpus("inputs", case + ".xyzr")
    npz = tmp_path / (case + ".npz")
    tsv, _ = cli("vertices", "--device", "ref", path, provenance=True)
    cli("vertices", "--device", "ref", "--output-format", "npz", "-o", npz, path)
    ids, xyz, t = parse_vertices(tsv)
    with np.load(npz, allow_pickle=False) as z:
        assert sorted(z.files) == ["comment", "ids", "start", "status", "t", "xyz"]
        assert z["ids"].dtype == np.uint32 and z["start"].dtype == np.uint64
        assert z["xyz"].dtype == np.float64 and z["xyz"].shape == (len(ids), 3)
        start = z["start"]
        assert start[0] == 0 and start[-1] == len(z["ids"]) and len(start) == len(ids) + 1
        got = [z["ids"][start[k]:start[k + 1]] for k in range(len(ids))]
        assert all(np.array_equal(a, b) for a, b in zip(got, ids))
        assert np.array_equal(z["xyz"], xyz) and np.array_equal(z["t"], t)
        assert (z["status"] == 1).all()  # certified
        header = [l[2:] for l in tsv.splitlines()
                  if l.startswith("# ") and l not in ("# vorball vertices",) and not l.startswith("# ids")]
        # The same header but the options line, which names --output-format npz.
        comment = str(z["comment"]).split("\n")
        assert [l for l in comment if not l.startswith("options: ")] == \
            [l for l in header if not l.startswith("options: ")]
        assert "options: vertices --output-format npz " in comment[2]
    if case == "degree5_vertex":
        assert max(np.diff(start)) >= 5


def test_npz_is_not_read_back(tmp_path):
    npz = tmp_path / "v.npz"
    path = corpus("inputs", "cubic_lattice.xyzr")
    cli("vertices", "--device", "ref", "--output-format", "npz", "-o", npz, path)
    _, err = cli("verify", path, npz, rc=19)
    assert "E109" in err and "np.load" in err


def test_npz_from_python(tmp_path):
    """Result.write(path, 'npz') is the command's archive: the same arrays,
    the comment the certificate (the command's adds its provenance)."""
    import vorball
    path = corpus("inputs", "degree5_vertex.xyzr")
    npz = tmp_path / "cmd.npz"
    cli("vertices", "--device", "ref", "--output-format", "npz", "-o", npz, path)
    r = vorball.vertices(path, device="ref")
    mine = tmp_path / "py.npz"
    r.write(mine, "npz")
    assert mine.read_bytes() == r.to_bytes("npz")
    with np.load(npz, allow_pickle=False) as a, np.load(mine, allow_pickle=False) as b:
        assert sorted(a.files) == sorted(b.files)
        for k in ("ids", "start", "xyz", "t", "status"):
            assert a[k].dtype == b[k].dtype and np.array_equal(a[k], b[k])
        assert str(b["comment"]) in str(a["comment"])
    with pytest.raises(vorball.VorballError):
        r.to_text("npz")
