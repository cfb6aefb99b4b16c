"""Nothing prints unless asked; warnings are collected with their numbers;
the one exception class; the catalogue; runs in threads."""
import pickle
import subprocess
import sys
import threading
import warnings

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


def test_warnings_through_the_warnings_module():
    """Not verbose: each warning is also a VorballWarning carrying its
    number, ignored unless a filter shows it; the records, not text."""
    with warnings.catch_warnings(record=True) as got:
        warnings.simplefilter("always", vorball.VorballWarning)
        res = vorball.vertices(CONTAINED, device="ref")
    w = [x.message for x in got if issubclass(x.category, vorball.VorballWarning)]
    assert 701 in [m.number for m in w]
    assert [m.number for m in w] == [d.number for d in res.warnings]
    assert [str(m) for m in w] == [str(d) for d in res.warnings]
    assert w[0].diagnostic == res.warnings[0]
    with warnings.catch_warnings():
        warnings.simplefilter("error", vorball.VorballWarning)
        e = pytest.raises(vorball.VorballWarning, vorball.vertices, CONTAINED, device="ref")
    assert e.value.number == 701
    # Outside pytest (which shows every warning), the package's filter
    # ignores them: a plain program prints nothing; a filter of its own shows them.
    prog = "import vorball; vorball.vertices(%r, device='ref')" % CONTAINED
    quiet = subprocess.run([sys.executable, "-c", prog], capture_output=True, text=True)
    assert quiet.returncode == 0 and quiet.stderr == ""
    show = "import warnings, vorball; warnings.simplefilter('always', vorball.VorballWarning); "
    loud = subprocess.run([sys.executable, "-c", show + prog], capture_output=True, text=True)
    assert "VorballWarning: vorball: W701: " in loud.stderr


def test_error_record_apart(tmp_path):
    """An error keeps the library's record: number, code, file and line
    beside the message the command prints."""
    p = tmp_path / "bad.xyzr"
    p.write_text("0 0 0 1\n4 0 0 1\n0 4 0 -1\n0 0 4 1\n4 4 4 1\n")
    e = pytest.raises(vorball.VorballError, vorball.vertices, str(p), device="ref").value
    assert (e.number, e.code, e.file, e.line) == (103, 1 | (3 << 8), str(p), 3)
    _, err = cli("vertices", "--device", "ref", p, rc=13)
    assert err == "vorball: E103: %s\n" % e.message
    again = pickle.loads(pickle.dumps(e))
    assert (again.file, again.line, again.row, again.code) == (e.file, 3, None, e.code)


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
