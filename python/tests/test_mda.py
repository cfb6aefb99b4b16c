"""vorball.mda.VorballAnalysis, an MDAnalysis analysis class: per-frame
certified vertex counts and the first channel's bottleneck of corpus
trajectories (a multi-model PDB, PSF+DCD, PDB+XTC) against the command's
per-frame output, the same on MDAnalysis's serial, multiprocessing and dask
backends; the radii from the library's element table. Needs MDAnalysis
2.8 or later and dask (.ci/test installs them from PyPI into the test
environment; the module is skipped without them, which .ci/test counts as
a failure)."""
import csv
import decimal
import io
import os
import shutil
import warnings

import numpy as np
import pytest

mda = pytest.importorskip("MDAnalysis")
pytest.importorskip("dask")

from vorball.mda import VorballAnalysis, library_radii  # noqa: E402

from conftest import cli, corpus  # noqa: E402

PDB = corpus("data", "ngl_md_ascii_trj.pdb")
XTC = corpus("data", "ngl_md_10frames.xtc")
PSF = corpus("data", "adk_natom.psf.gz")
DCD = corpus("data", "adk_dims_2frames.dcd")
GRID = 64


@pytest.fixture(autouse=True)
def quiet_mdanalysis():
    # MDAnalysis warns about the PDB's missing elements and the DCD reader's
    # copies; neither is the subject here.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


def cli_channels(*args):
    """Per frame of the command's channel table (--no-pore, the binding's
    table): (rows, bottleneck_A and length_A of channel 1 as printed)."""
    out, _ = cli("channels", "--no-pore", "--grid", GRID, "--device", "ref", *args)
    per = {}
    for row in csv.DictReader(io.StringIO(out)):
        f = per.setdefault(int(row["frame"]), [0, None, None])
        f[0] += 1
        if row["channel"] == "1":
            f[1], f[2] = row["bottleneck_A"], row["length_A"]
    return per


def printed(x):
    return None if np.isnan(x) else "%.3f" % x


def same_channels(a, per):
    for k, frame in enumerate(a.frames):
        rows, bott, length = per.get(int(frame), [0, None, None])
        assert a.results.channels[k] == rows, frame
        assert printed(a.results.bottleneck[k]) == bott, frame
        assert printed(a.results.length[k]) == length, frame


def test_backends_listed():
    assert VorballAnalysis.get_supported_backends() == ("serial", "multiprocessing", "dask")
    assert VorballAnalysis._analysis_algorithm_is_parallelizable


@pytest.fixture(scope="module")
def pdb_runs():
    """The first 10 models of the PDB on each backend (device ref)."""
    runs = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        u = mda.Universe(PDB)
        for backend, workers in (("serial", 1), ("multiprocessing", 2), ("dask", 2)):
            a = VorballAnalysis(u.atoms, device="ref", grid=GRID)
            runs[backend] = a.run(stop=10, backend=backend, n_workers=workers)
    return runs


def test_pdb_models_against_the_command(pdb_runs):
    """Per model: as many certified vertices as `vorball vertices --model
    N` writes, all complete; channels, bottleneck and length of channel 1
    as `vorball channels --no-pore` prints them."""
    a = pdb_runs["serial"]
    assert list(a.frames) == list(range(10))
    for k in range(10):
        out, _ = cli("vertices", "--device", "ref", "--model", k + 1, PDB)
        lines = [l for l in out.splitlines() if l and not l.startswith("#")]
        assert all(l.endswith("\tcertified") for l in lines)
        assert a.results.vertices[k] == len(lines) > 1000, k
    assert a.results.complete.all()
    same_channels(a, cli_channels("--frames", "0:10", PDB))
    # Real channels: most frames have one, and a frame without is NaN.
    assert (a.results.channels > 0).sum() >= 8 and np.isnan(a.results.bottleneck).sum() <= 2


@pytest.mark.parametrize("backend", ["multiprocessing", "dask"])
def test_parallel_same_as_serial(pdb_runs, backend):
    s, p = pdb_runs["serial"], pdb_runs[backend]
    assert np.array_equal(p.frames, s.frames)
    for name in ("vertices", "complete", "channels"):
        assert np.array_equal(p.results[name], s.results[name]), name
    for name in ("bottleneck", "length"):
        assert np.array_equal(p.results[name], s.results[name], equal_nan=True), name


def test_opencl_device_spawns_workers():
    """On an OpenCL device (PoCL) the multiprocessing workers are spawned:
    after a serial run has used PoCL in this process, the parallel run
    still finishes, with the same numbers."""
    u = mda.Universe(PDB)
    s = VorballAnalysis(u.atoms, device="cpu", grid=GRID).run(stop=4)
    p = VorballAnalysis(u.atoms, device="cpu", grid=GRID).run(stop=4, backend="multiprocessing",
                                                             n_workers=2)
    for name in ("vertices", "channels"):
        assert np.array_equal(p.results[name], s.results[name]), name
    assert np.array_equal(p.results.bottleneck, s.results.bottleneck, equal_nan=True)
    ref = VorballAnalysis(u.atoms, device="ref", grid=GRID).run(stop=4)
    assert np.array_equal(s.results.vertices, ref.results.vertices)


def test_dcd_over_psf_against_the_command():
    """PSF + DCD (3341 atoms, 2 frames), radii from the PSF's elements as
    the library infers them: channel 1 as the command's --traj; the vertex
    counts as the library's own DCD frames give them."""
    import vorball
    u = mda.Universe(PSF, DCD)
    a = VorballAnalysis(u.atoms, device="ref", grid=GRID).run(backend="multiprocessing",
                                                              n_workers=2)
    same_channels(a, cli_channels(PSF, "--traj", DCD))
    assert (a.results.channels > 5).all()
    with vorball.frames(PSF, DCD) as fr:
        counts = [len(vorball.vertices(f, device="ref").t) for f in fr]
    assert list(a.results.vertices) == counts and min(counts) > 10000
    assert a.results.complete.all()


def test_xtc_over_pdb_against_the_command(tmp_path):
    # A copy: MDAnalysis leaves an offsets file beside an XTC it reads.
    xtc = tmp_path / os.path.basename(XTC)
    shutil.copyfile(XTC, xtc)
    u = mda.Universe(PDB, str(xtc))
    a = VorballAnalysis(u.atoms, device="ref", grid=GRID, vertices=False).run(
        backend="multiprocessing", n_workers=2)
    assert len(a.frames) == 10 and (a.results.vertices == -1).all()
    same_channels(a, cli_channels(PDB, "--traj", XTC))


def test_radii_from_the_library():
    """The topology path (the library reads the file) and the elements path
    (a Universe without a file: the library's table by element) agree;
    a table replaces the library's value for its elements; radii given
    are used as given."""
    u = mda.Universe(corpus("data", "1crn.pdb"))
    r = library_radii(u.atoms)
    assert r.dtype == object and len(r) == u.atoms.n_atoms
    want = {"C": "1.70", "N": "1.55", "O": "1.52", "S": "1.80"}
    for el, v in want.items():
        assert set(r[u.atoms.elements == el]) == {decimal.Decimal(v)}, el
    merged = mda.Merge(u.atoms)
    assert not getattr(merged, "filename", None)
    assert list(library_radii(merged.atoms)) == list(r)
    t = library_radii(u.atoms, table={"C": "1.9"})
    c = u.atoms.elements == "C"
    assert set(t[c]) == {decimal.Decimal("1.9")} and list(t[~c]) == list(r[~c])
    a = VorballAnalysis(u.atoms, device="ref", grid=GRID).run()
    b = VorballAnalysis(u.atoms, radii=np.array([str(v) for v in r]), device="ref",
                        grid=GRID).run()
    out, _ = cli("vertices", "--device", "ref", corpus("data", "1crn.pdb"))
    assert a.results.vertices[0] == b.results.vertices[0] == out.count("\tcertified\n")
    with pytest.raises(ValueError, match="radii"):
        VorballAnalysis(u.atoms, radii=[1.5, 1.6])
