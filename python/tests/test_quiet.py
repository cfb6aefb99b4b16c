"""Nothing prints unless asked; warnings are collected with their numbers;
the one exception class; the catalogue; runs in threads."""
import pickle
import threading

import numpy as np
import pytest
import vorball

from conftest import cli, corpus

CONTAINED = corpus("inputs", "contained_sphere.xyzr")


def test_silent_by_default_and_verbose_prints(capfd):
    res = vorball.vertices(CONTAINED, device="gpu")  # no GPU here: W760, or a GPU: nothing
    s = vorball.read(corpus("data", "1crn.pdb"), water=False)
    vorball.channels(s, grid=16, device="ref")
    out, err = capfd.readouterr()
    assert out == "" and err == ""
    numbers = {w.number for w in res.warnings}
    assert res.backend != "ref" or 760 in numbers  # fell back to the reference: said so
    vorball.vertices(CONTAINED, device="cpu")       # PoCL's OpenCL: silent too
    out, err = capfd.readouterr()
    assert out == "" and err == ""
    assert 701 in numbers  # the contained sphere, as the command warns
    _, cli_err = cli("vertices", "--device", "ref", CONTAINED)
    assert [l for l in cli_err.splitlines() if "W701" in l] == \
        [str(w) for w in res.warnings if w.number == 701]
    loud = vorball.vertices(CONTAINED, device="ref", verbose=True)
    out, err = capfd.readouterr()
    # Exactly the collected warnings, each once, as the command prints them.
    assert out == "" and "vorball: W701: " in err
    assert err.splitlines() == [str(w) for w in loud.warnings] == \
        [l for l in cli_err.splitlines() if l.startswith("vorball: W")]


def test_one_exception_class():
    e = pytest.raises(vorball.VorballError, vorball.vertices, np.eye(3), 1.0).value
    assert isinstance(e, Exception) and str(e).startswith("E106: ")
    again = pickle.loads(pickle.dumps(e))
    assert (again.number, again.message, again.exit_status) == (106, e.message, 16)


def test_catalogue_is_the_libraries():
    cat = vorball.catalogue()
    assert cat[("E", 104)].exit_status == 14 and cat[("E", 104)].name == "INPUT_DUPLICATE"
    assert cat[("W", 701)].exit_status == 0
    assert cat[("W", 740)].exit_status is None  # retired
    # Every error a test here met has its entry, and the README lists them all.
    readme = open(corpus("..", "README.md")).read()
    for (kind, number), entry in cat.items():
        assert "| %s%d |" % (kind, number) in readme


def test_threads_run_concurrently_with_the_same_result():
    s = vorball.read(corpus("inputs", "crambin_fragment.xyzr"))
    want = vorball.vertices(s, device="ref").to_text()
    got = [None] * 4

    def work(k):
        got[k] = vorball.vertices(s, device="ref", threads=1).to_text()

    ts = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert got == [want] * 4


def test_result_pickles():
    res = vorball.vertices(corpus("inputs", "cubic_lattice.xyzr"), device="ref")
    back = pickle.loads(pickle.dumps(res))
    ids, xyz, t = back
    assert np.array_equal(xyz, res.xyz) and back.certificate == res.certificate
    assert back.to_text() == res.to_text() and back.spheres is None
