"""Cell measures (`vorball cells`): per-atom volume and SAS area of the
additively weighted cells inside the probe-expanded balls, and contact
areas, as proven enclosures."""
from __future__ import annotations

import json as _json
import numbers
import os
import time
from typing import Any, Dict, List, Optional, Union

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._errors import Diagnostic, emit, misuse, parse
from ._periodic import BoxInput, box_tokens
from ._spheres import PathLike, SphereInput, as_spheres, frame_range

# VB_MEASURES_MAX_PATCHES of verify/measures/vb_measures.h
MAX_PATCHES = 5000


class Cells:
    """The measures of every atom, each an enclosure lo <= exact <= hi
    (float64 ends as the library computed them; the value is the midpoint).

    volume, volume_lo, volume_hi   (n,) cell volume inside the expanded ball
    sas, sas_lo, sas_hi            (n,) SAS area (expanded sphere in the cell)
    empty, loose                   (n,) bool: empty cell (W850); a value left
                                   wider than asked (W851, patch budget spent)
    id1, id2, area, area_lo, area_hi  with contacts: (m,) the contact of each
                                   pair id1 < id2 whose hi > 0, else None
    shift2                         periodic with contacts: (m, 3) int64, the
                                   image shift of id2 (id2@(dx,dy,dz)), else None
    patches                        direction patches integrated, all atoms
    frame, model                   of cells_frames: the frame's index (from
                                   0) and model number
    stats                          the counts `vorball cells --stats` prints:
                                   atoms, patches, empty, loose, contacts,
                                   closed (atoms measured in closed form),
                                   seconds (this call's wall clock)
    to_text(), contacts_text()     the TSVs `vorball cells` writes (-o,
                                   --contacts): the same bytes
    json, to_json()                the --json document (per-atom rows and,
                                   for atom records, per-residue and
                                   per-chain sums), as text and as objects
    """

    volume: np.ndarray
    volume_lo: np.ndarray
    volume_hi: np.ndarray
    sas: np.ndarray
    sas_lo: np.ndarray
    sas_hi: np.ndarray
    empty: np.ndarray
    loose: np.ndarray
    id1: Optional[np.ndarray]
    id2: Optional[np.ndarray]
    area: Optional[np.ndarray]
    area_lo: Optional[np.ndarray]
    area_hi: Optional[np.ndarray]
    patches: int
    json: str
    stats: Dict[str, Union[int, float]]
    warnings: List[Diagnostic]

    def __init__(self, d: Dict[str, Any], warnings: List[Diagnostic],
                 seconds: float = 0.0, frame: int = 0, model: int = 1) -> None:
        self.warnings = warnings
        self.frame, self.model = frame, model
        f64 = lambda k: np.frombuffer(d[k], dtype=np.float64)  # noqa: E731
        self.volume_lo, self.volume_hi = f64("volume_lo"), f64("volume_hi")
        self.sas_lo, self.sas_hi = f64("sas_lo"), f64("sas_hi")
        # the midpoint as the library prints it: 0.5 lo + 0.5 hi
        self.volume = 0.5 * self.volume_lo + 0.5 * self.volume_hi
        self.sas = 0.5 * self.sas_lo + 0.5 * self.sas_hi
        self.empty = np.frombuffer(d["empty"], dtype=np.uint8).astype(bool)
        self.loose = np.frombuffer(d["loose"], dtype=np.uint8).astype(bool)
        self.patches = int(d["patches"])
        self.stats = {"atoms": len(self.volume_lo), "patches": self.patches,
                      "empty": int(d["nempty"]), "loose": int(d["nloose"]),
                      "contacts": int(d["ncontacts"]), "closed": int(d["nclosed"]),
                      "seconds": seconds}
        self._text, self._contacts_text, self.json = d["tables"]
        self.id1 = self.id2 = self.area = self.area_lo = self.area_hi = None
        self.shift2: Optional[np.ndarray] = None
        if "shift2" in d:
            self.shift2 = np.frombuffer(d["shift2"], dtype=np.int16).astype(np.int64).reshape(-1, 3)
        if "id1" in d:
            self.id1 = np.frombuffer(d["id1"], dtype=np.uint32).astype(np.int64)
            self.id2 = np.frombuffer(d["id2"], dtype=np.uint32).astype(np.int64)
            self.area_lo, self.area_hi = f64("area_lo"), f64("area_hi")
            self.area = 0.5 * self.area_lo + 0.5 * self.area_hi

    def to_text(self) -> str:
        """The per-atom TSV, as `vorball cells -o` writes it."""
        return self._text

    def to_json(self) -> Any:
        """The --json document as Python objects."""
        return _json.loads(self.json)

    def contacts_text(self) -> Optional[str]:
        """The contacts TSV, as `--contacts` writes it (None without contacts)."""
        return self._contacts_text

    def __len__(self) -> int:
        return len(self.volume)

    def __repr__(self) -> str:
        return "<vorball.Cells: %d atoms, %d empty, %d loose%s>" % (
            len(self), int(self.empty.sum()), int(self.loose.sum()),
            "" if self.id1 is None else ", %d contacts" % len(self.id1))


def _numbers(probe, tolerance, max_patches, threads):
    """The options' types; their ranges are the library's
    (vb_measure_options_check): the command's messages and numbers."""
    for name, v in (("probe", probe), ("tolerance", tolerance)):
        if not isinstance(v, numbers.Real) or isinstance(v, bool):
            raise misuse("%s must be a number, not %r" % (name, v))
    for name, v in (("max_patches", max_patches), ("threads", threads)):
        if not isinstance(v, numbers.Integral) or isinstance(v, bool):
            raise misuse("%s must be an integer, not %r" % (name, v))


def cells(xyz: SphereInput, r: Optional[ArrayLike] = None, *, probe: float = 1.4,
          tolerance: float = 1e-6, max_patches: int = MAX_PATCHES, contacts: bool = False,
          threads: int = 0, zero_radius: str = "auto", select: Optional[str] = None,
          periodic: bool = False, box: BoxInput = None, html: Optional[PathLike] = None,
          title: Optional[str] = None, verbose: bool = False) -> Cells:
    """Per-atom volume and SAS area (and contact areas) of the additively
    weighted cells inside the balls of radius R + probe, as `vorball cells`.

    xyz, r: the spheres (arrays, a Spheres or a file path). probe (>= 0),
    tolerance (relative width asked, in (0, 1)), max_patches (per atom,
    >= 96; past it a value stands wider than asked, W851), contacts (the
    contact areas too), threads (0: all CPUs; the values do not depend on
    it). select: only the atoms this expression selects (`--select`,
    Spheres.select). periodic, box: the atoms repeated by the box (`cells
    --periodic`, `--box`; box as vorball.vertices takes it, the file's box
    without it): each atom once, its cell cut by the images too; each
    periodic contact once, its second atom moved by shift2 (dx, dy, dz)
    times the box edges. html: write the results page of `--html` there
    (the molecule coloured by volume, SAS or contact area; titled title,
    by default "vorball cells " and the spheres' source, as the command
    titles it). Returns a Cells; raises VorballError (E7 for bad
    options, E118 for a bad or empty selection, E120 for no box or a bad
    one, E135 for a box too small).
    """
    _numbers(probe, tolerance, max_patches, threads)
    s, made = as_spheres(xyz, r, min_count=1, zero_radius=zero_radius, select=select)
    per = bool(periodic) or box is not None
    page = "" if html is None else os.fspath(html)
    if title is None:
        title = "vorball cells %s" % s.source
    t0 = time.perf_counter()
    d, diag = _core.cells_run(s._capsule, float(probe), float(tolerance), int(max_patches),
                              bool(contacts), int(threads), per, box_tokens(box), page, str(title))
    seconds = time.perf_counter() - t0
    w = made + parse(diag)
    emit(w, verbose)
    return Cells(d, w, seconds)


def cells_frames(path: PathLike, trajectory: Optional[PathLike] = None, start: int = 0,
                 stop: Optional[int] = None, step: int = 1, *, water: bool = False,
                 probe: float = 1.4, tolerance: float = 1e-6, max_patches: int = MAX_PATCHES,
                 contacts: bool = False, threads: int = 0, periodic: bool = False,
                 box: BoxInput = None, verbose: bool = False) -> List[Cells]:
    """The measures of every selected frame, as `vorball cells PATH
    [--traj TRAJECTORY] [--frames A:B:S]` (vb_cells_run_frames): the models
    of path, or the frames of a DCD/XTC/TRR trajectory over path as its
    topology; a binary frame's floats become their shortest decimals, as
    the command reads them. water keeps water (`--water`); the options as
    vorball.cells; periodic/box: each frame in the box it carries, or box
    for all (`--periodic`, `--box`). Returns a Cells per frame with .frame
    and .model (each table as `-o` writes it for one frame, less the
    command's `frame` column)."""
    rng = frame_range(start, stop, step)
    _numbers(probe, tolerance, max_patches, threads)
    traj = None if trajectory is None else os.fspath(trajectory)
    per = bool(periodic) or box is not None
    t0 = time.perf_counter()
    got, diag = _core.cells_frames(os.fspath(path), traj, *rng, bool(water),
                                   (float(probe), float(tolerance), int(max_patches),
                                    bool(contacts), int(threads)), per, box_tokens(box))
    seconds = time.perf_counter() - t0
    w = parse(diag)
    emit(w, verbose)
    return [Cells(d, w, seconds, frame, model) for frame, model, d in got]

