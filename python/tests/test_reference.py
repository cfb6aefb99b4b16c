"""vorball.reference and vorball.devices as the commands: every vertex
exactly by brute force, as `vorball reference` finds them (the same
numbers, bit for bit), its size policy (E130 above 500 spheres unless
force) from the library, and the device table of `vorball devices`."""
import json

import numpy as np
import pytest
import vorball

from conftest import cli, corpus, same_vertices


@pytest.mark.parametrize("case", ["degree5_vertex", "bcc_lattice", "crambin_fragment"])
def test_reference_as_the_command(case):
    path = corpus("inputs", case + ".xyzr")
    out, _ = cli("reference", path)
    r = vorball.reference(path)
    same_vertices(r, out)
    assert len(r.t) > 0 and len(r.offsets) == len(r.t) + 1
    # The pipeline's certified vertices are the reference's.
    v = vorball.vertices(path, device="ref")
    assert np.array_equal(v.ids_flat, r.ids_flat) and np.array_equal(v.xyz, r.xyz)


def test_reference_size_policy():
    rng = np.random.default_rng(7)
    xyz = rng.uniform(0.0, 60.0, size=(501, 3))
    with pytest.raises(vorball.VorballError) as e:
        vorball.reference(xyz, np.full(501, 1.5))
    assert e.value.number == 130


def test_devices_as_the_command():
    out, _ = cli("devices")
    text = vorball.devices()
    assert text == out
    assert text.splitlines()[-1].startswith("#auto\t")


def test_reference_stats_as_the_command():
    path = corpus("inputs", "bcc_lattice.xyzr")
    _, err = cli("reference", path, "--stats")
    s = vorball.reference(path).stats
    assert ("quadruples: %d, refuted by the filter %d\n" % (s["quadruples"], s["refuted"])) in err
    assert ("filter: %d calls, %d undecided" % (s["filter_calls"], s["undecided"])) in err
    assert ("exact evaluations %d\n" % s["exact_evals"]) in err
    assert s["quadruples"] > 0 and s["filter_calls"] > 0 and s["seconds"] > 0


def test_bench_figures_from_an_engine():
    """`vorball bench`'s row from the calls: an Engine opened once (its
    set-up apart, as bench's default), a run's counts and stage times."""
    path = corpus("inputs", "crambin_fragment.xyzr")
    out, _ = cli("bench", path, "--device", "ref", "--json")
    row = json.loads(out)[0]
    with vorball.Engine(device="ref") as e:
        assert e.setup_seconds is None
        r = e.vertices(path)
        assert e.setup_seconds is not None and e.setup_seconds >= 0
    assert len(r.t) == row["vertices"] and len(r.spheres) == row["atoms"]
    assert (r.backend, r.device) == (row["backend"], row["device"])
    stages = {"cull": "cull", "upload": "upload", "envelope": "envelope",
              "vertices_s": "vertices", "matching": "matching", "targeted": "targeted",
              "tangent": "tangent", "completion": "completion", "certification": "certify",
              "setup": "setup", "setup_wait": "setup_wait", "total": "total"}
    for key, mine in stages.items():
        assert key in row and r.times[mine] >= 0
    assert r.times["total"] > 0
