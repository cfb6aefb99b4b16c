"""vorball.reference and vorball.devices as the commands: every vertex
exactly by brute force, as `vorball reference` finds them (the same
numbers, bit for bit), its size policy (E130 above 500 spheres unless
force) from the library, and the device table of `vorball devices`."""
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
