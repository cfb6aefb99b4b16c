"""vorball for MDAnalysis: certified Voronoi vertices and the channel
bottleneck of an AtomGroup, frame by frame, on MDAnalysis's serial,
multiprocessing and dask backends (MDAnalysis 2.8 or later).

    import MDAnalysis as mda
    from vorball.mda import VorballAnalysis
    u = mda.Universe("top.pdb", "traj.xtc")
    a = VorballAnalysis(u.atoms, grid=128).run(backend="multiprocessing", n_workers=2)
    a.results.vertices, a.results.bottleneck          # one value per frame

Per frame, on the positions of the group (MDAnalysis's float32, which
vorball reads as their shortest decimals: a PDB's own numbers) and fixed
radii, through one vorball.Engine per process:
  results.vertices    certified vertices (vorball.vertices)
  results.complete    whether the certificate proves the set complete
  results.channels    channels found (vorball.channels, the table of
                      `vorball channels --no-pore`)
  results.bottleneck  bottleneck radius (A) of the first-ranked channel
                      (the longest; NaN in a frame without a channel)
  results.length      its length (A)
beside AnalysisBase's frames and times. The pore sweep (HOLE-style radii
below the probe) is the command's only for now: the bottleneck is the
channel table's.

Radii: an array of the group's radii; else the library's element table,
read by the library itself: from the Universe's topology file when vorball
reads it (PDB, PQR, mmCIF, GRO, or a PSF with its DCD/XTC/TRR: the elements
inferred as the command infers them, so the radii are those of `vorball
... TOPOLOGY`), else from the atoms' elements (topology attribute
`elements`). A mapping {element: radius} in `table` replaces the library's
value for those elements (as `--radii FILE`).
"""
from __future__ import annotations

import decimal
import os
import tempfile
from typing import Any, Mapping, Optional

import numpy as np
from numpy.typing import ArrayLike

from MDAnalysis.analysis.backends import BackendMultiprocessing
from MDAnalysis.analysis.base import AnalysisBase
from MDAnalysis.analysis.results import ResultsGroup

from ._errors import VorballError
from ._spheres import frames, read
from ._vertices import Engine

__all__ = ["VorballAnalysis", "library_radii"]

_PER_FRAME = ("vertices", "complete", "channels", "bottleneck", "length")


def _write_table(table: Mapping[str, Any], folder: str) -> str:
    """A radii file ('ELEMENT RADIUS' lines) of the table, in folder."""
    path = os.path.join(folder, "radii.txt")
    with open(path, "w", encoding="ascii") as f:
        for el, r in table.items():
            f.write("%s %s\n" % (str(el).strip().upper(), r))
    return path


def _radii_of(s) -> np.ndarray:
    """The radii of a Spheres as exact decimals where it has them."""
    d = s.decimals
    return np.array(d[:, 3], dtype=object) if d is not None else np.array(s.r, dtype=np.float64)


def _from_topology(u, radii_file):
    """The radii of every atom of u as the library reads u's topology file,
    or None when vorball does not read it or counts other atoms."""
    top = getattr(u, "filename", None)
    if not top or not os.path.exists(top):
        return None
    try:
        s = read(top, water=True, radii=radii_file)
    except VorballError:
        traj = getattr(u.trajectory, "filename", None)
        if not traj or traj == top:
            return None
        try:
            with frames(top, traj, stop=1, water=True, radii=radii_file) as fr:
                s = next(iter(fr))
        except (VorballError, StopIteration):
            return None
    return _radii_of(s) if len(s) == u.atoms.n_atoms else None


def _from_elements(ag, radii_file, folder):
    """The radii of the group's elements from the library's table: one
    HETATM record per distinct element, its element in columns 77-78,
    read by the library."""
    els = [str(e).strip().upper() for e in ag.elements]
    if not all(els):
        return None
    distinct = sorted(set(els))
    path = os.path.join(folder, "elements.pdb")
    with open(path, "w", encoding="ascii") as f:
        for k, el in enumerate(distinct):
            f.write("HETATM%5d %-4s UNL A   1    %8.3f%8.3f%8.3f  1.00  0.00          %2s\n"
                    % (k + 1, el[:4], 3.0 * k, 0.0, 0.0, el[:2]))
    s = read(path, water=True, radii=radii_file)
    if len(s) != len(distinct):
        return None
    by = dict(zip(distinct, _radii_of(s)))
    return np.array([by[e] for e in els], dtype=object)


def library_radii(atomgroup: Any, table: Optional[Mapping[str, Any]] = None) -> np.ndarray:
    """The radii of the atoms of atomgroup by the library's element table
    (see the module's text): an object array of decimal.Decimal (or
    float64 where the library holds doubles only). table: {element:
    radius} replacing the library's values. Raises ValueError when neither
    the topology file nor the atoms' elements give them."""
    with tempfile.TemporaryDirectory(prefix="vorball-radii-") as folder:
        radii_file = _write_table(table, folder) if table else None
        r = _from_topology(atomgroup.universe, radii_file)
        if r is not None:
            return r[atomgroup.indices]
        if hasattr(atomgroup, "elements"):
            r = _from_elements(atomgroup, radii_file, folder)
            if r is not None:
                return r
    raise ValueError("no radii for these atoms: vorball does not read the Universe's topology "
                     "file (or counts other atoms there) and the atoms have no elements; give "
                     "radii= (one per atom)")


def _as_radii(radii, n):
    a = np.asarray(radii)
    if a.shape != (n,):
        raise ValueError("radii: %d values for %d atoms" % (a.size, n))
    if a.dtype.kind == "O":
        return np.array([decimal.Decimal(str(v)) if not isinstance(v, decimal.Decimal) else v
                         for v in a], dtype=object)
    return a


class _SpawnedPool(BackendMultiprocessing):
    """MDAnalysis's multiprocessing backend on fresh interpreters (spawn):
    PoCL's threads do not survive fork, so a forked worker of a process
    that has run an OpenCL device hangs on its first kernel."""

    def apply(self, func, computations):
        import multiprocessing
        with multiprocessing.get_context("spawn").Pool(processes=self.n_workers) as pool:
            return pool.map(func, computations)


class VorballAnalysis(AnalysisBase):
    """Certified Voronoi vertices and the first channel's bottleneck per
    frame of an AtomGroup (see the module's text for the results).

    atomgroup   the atoms (all frames of its Universe's trajectory)
    radii       one radius per atom (floats, str or Decimal), or None for
                the library's element table (library_radii)
    table       {element: radius} over the library's table (radii=None)
    vertices, channels   which of the two to compute (both by default)
    device      auto, gpu, cpu or ref, for both (one Engine per process)
    samples     vorball.vertices' samples
    grid, probe, min_length, min_radius, jfa   vorball.channels' options
    Any other keyword goes to AnalysisBase (verbose).

    Runs with run(backend="serial" | "multiprocessing" | "dask",
    n_workers=N); the results are the same on each. Each worker opens its
    own Engine. On an OpenCL device (any but "ref") the multiprocessing
    workers are spawned, not forked (PoCL's threads do not survive fork):
    as with dask, a script then runs its analysis under
    `if __name__ == "__main__":`. device="ref" forks.
    """

    _analysis_algorithm_is_parallelizable = True

    @classmethod
    def get_supported_backends(cls):
        return ("serial", "multiprocessing", "dask")

    def __init__(self, atomgroup: Any, radii: Optional[ArrayLike] = None, *,
                 table: Optional[Mapping[str, Any]] = None, vertices: bool = True,
                 channels: bool = True, device: str = "auto", samples: int = 30,
                 grid: int = 128, probe: float = 1.4, min_length: float = 5.0,
                 min_radius: float = 0.0, jfa: str = "exact", **kwargs: Any) -> None:
        super().__init__(atomgroup.universe.trajectory, **kwargs)
        if not (vertices or channels):
            raise ValueError("nothing to compute: vertices and channels both False")
        self.atomgroup = atomgroup
        self.radii = (library_radii(atomgroup, table) if radii is None
                      else _as_radii(radii, atomgroup.n_atoms))
        self._vertices, self._channels = bool(vertices), bool(channels)
        self._device, self._samples, self._jfa = device, samples, jfa
        # The channel table without the pore sweep (`vorball channels
        # --no-pore`): since the binding sweeps the pore by default, say so.
        self._channel_kw = dict(grid=grid, probe=probe, min_length=min_length,
                                min_radius=min_radius, no_pore=True)
        self._engine: Optional[Engine] = None

    def _configure_backend(self, backend, n_workers, unsupported_backend=False):
        executor = super()._configure_backend(backend, n_workers,
                                              unsupported_backend=unsupported_backend)
        if type(executor) is BackendMultiprocessing and self._device != "ref":
            return _SpawnedPool(n_workers=executor.n_workers)
        return executor

    def __getstate__(self):
        # The engine holds a device: never pickled (a worker opens its own,
        # and the copy a worker sends back leaves its own behind).
        state = dict(self.__dict__)
        state["_engine"] = None
        return state

    def _prepare(self):
        n = self.n_frames
        self.results.vertices = np.full(n, -1, dtype=np.int64)
        self.results.complete = np.zeros(n, dtype=bool)
        self.results.channels = np.full(n, -1, dtype=np.int64)
        self.results.bottleneck = np.full(n, np.nan)
        self.results.length = np.full(n, np.nan)

    def _single_frame(self):
        if self._engine is None:
            self._engine = Engine(device=self._device, jfa=self._jfa)
        k = self._frame_index
        xyz = self.atomgroup.positions
        if self._vertices:
            res = self._engine.vertices(xyz, self.radii, self._samples)
            self.results.vertices[k] = len(res.t)
            self.results.complete[k] = bool(res.certificate.complete)
        if self._channels:
            ch = self._engine.channels(xyz, self.radii, **self._channel_kw)
            self.results.channels[k] = len(ch)
            if len(ch):
                self.results.bottleneck[k] = ch.table["bottleneck_A"][0]
                self.results.length[k] = ch.table["length_A"][0]
        if k == self.n_frames - 1:  # the last frame of this process's share
            self._close()

    def _close(self):
        if self._engine is not None:
            self._engine.close()
            self._engine = None

    def _conclude(self):
        self._close()

    def _get_aggregator(self):
        return ResultsGroup(lookup={name: ResultsGroup.ndarray_hstack for name in _PER_FRAME})

