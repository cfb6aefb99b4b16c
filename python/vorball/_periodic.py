"""Periodic boxes (issue 34): the box argument as `--box` takes it, the
periodic vertices of a set (vorball.vertices(..., periodic=True)) and of
every frame of a trajectory, each in its own box (vorball.periodic_frames),
and a periodic vertex file judged (vorball.verify(..., periodic=True)).
The library builds the images, runs the pipeline and writes the text."""
from __future__ import annotations

import numbers
import os
import tempfile
from typing import Any, List, Optional, Sequence, Union

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._errors import Diagnostic, emit, misuse, parse
from ._spheres import PathLike, frame_range

BoxInput = Union[Sequence[Any], np.ndarray, None]


def _token(v):
    """One number of a box as the decimal the command would read: str
    verbatim, integers exactly, floats as their shortest round-trip
    decimal (0.1 stays '0.1')."""
    if isinstance(v, str):
        return v
    if isinstance(v, (bool, np.bool_)):
        raise misuse("a box holds numbers, not %r" % (v,))
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        return np.format_float_positional(float(v), unique=True, trim="-")
    raise misuse("a box holds numbers, not %r" % (v,))


def box_tokens(box: BoxInput) -> Optional[List[str]]:
    """The tokens of `--box` for box: None (the file's box), (a, b, c),
    (a, b, c, alpha, beta, gamma) in degrees, or a 3x3 matrix whose rows
    are the edge vectors a, b, c. A wrong count or a flat box is the
    library's to refuse (E120)."""
    if box is None:
        return None
    if isinstance(box, str):
        raise misuse("box is a sequence of 3, 6 or 9 numbers or a 3x3 matrix, not %r" % (box,))
    flat = np.asarray(box, dtype=object).reshape(-1)
    return [_token(v) for v in flat]


class PeriodicResult(tuple):
    """The vertices of a periodic diagram: unpacks as (ids, shifts, xyz, t).

    Each vertex is written once, as its canonical translate (README,
    'Periodic boxes'): member k is atom ids[k] moved by
    shifts[k] = (dx, dy, dz) times the box edges a, b, c, the notation
    `i@(dx,dy,dz)` of the command's files.
    ids      list of int64 arrays, the members' atom ids of each vertex
    shifts   list of (k, 3) int64 arrays, the members' image shifts
    ids_flat, shifts_flat, offsets   the same as flat arrays and m + 1 offsets
    xyz, t   (m, 3) and (m,) float64: the canonical translate's point, radius
    box      (3, 3) float64: the edge vectors as rows (nearest doubles)
    certificate  what the run proves (the file's header lines)
    atoms, spheres  the box's atoms; atoms and images the run used
    rho, reach      the proven bound of every vertex's t; the images' reach
    translates, beyond_rho  run vertices dropped as translates or as t > rho
    frame, model    for a trajectory's frame (periodic_frames), else None
    warnings        diagnostics of the call
    to_text('tsv' or 'json') gives the bytes `vorball vertices --periodic`
    writes (less its provenance lines)."""

    def __new__(cls, d, warnings: List[Diagnostic], frame: Optional[int] = None,
                model: Optional[int] = None) -> PeriodicResult:
        flat = np.frombuffer(d["ids"], dtype=np.uint32).astype(np.int64)
        sh = np.frombuffer(d["shifts"], dtype=np.int16).astype(np.int64).reshape(-1, 3)
        start = np.frombuffer(d["start"], dtype=np.int64)
        cut = start[1:-1] if len(start) > 1 else []
        ids = np.split(flat, cut) if len(start) > 1 else []
        shifts = np.split(sh, cut) if len(start) > 1 else []
        xyz = np.stack([np.frombuffer(d[k], dtype=np.float64) for k in "xyz"], axis=1)
        t = np.frombuffer(d["t"], dtype=np.float64)
        self = super().__new__(cls, (ids, shifts, xyz, t))
        self.ids, self.shifts, self.xyz, self.t = ids, shifts, xyz, t
        self.ids_flat, self.shifts_flat, self.offsets = flat, sh, start
        self.box = np.frombuffer(d["box"], dtype=np.float64).reshape(3, 3)
        self.certificate = d["certificate"]
        self.atoms, self.spheres = d["atoms"], d["spheres"]
        self.rho, self.reach = d["rho"], d["reach"]
        self.translates, self.beyond_rho = d["translates"], d["beyond_rho"]
        self.frame, self.model = frame, model
        self.warnings = warnings
        self._text = {"tsv": d["tsv"], "json": d["json"]}
        return self

    def to_text(self, format: str = "tsv") -> str:
        """The periodic vertex file (tsv or json) as the command writes it."""
        if format not in self._text:
            raise misuse("a periodic vertex file is tsv or json, not %r" % (format,))
        return self._text[format]

    def write(self, path: PathLike, format: str = "tsv") -> None:
        """Writes to_text(format) to path."""
        text = self.to_text(format)
        with open(os.fspath(path), "w", encoding="utf-8", newline="") as f:
            f.write(text)

    def __repr__(self) -> str:
        return "<vorball.PeriodicResult %d vertices of %d atoms%s>" % (
            len(self.t), self.atoms, "" if self.frame is None else ", frame %d" % self.frame)


def run_periodic(capsule, box: BoxInput, opts, verbose, made, engine=None) -> PeriodicResult:
    """vorball.vertices(..., periodic=True) on a set's capsule (on an
    Engine's capsule when given: Engine.vertices(..., periodic=True))."""
    d, diag = _core.periodic_vertices(capsule, engine, box_tokens(box), opts)
    w = made + parse(diag)
    emit(w, verbose)
    return PeriodicResult(d, w)


def periodic_frames(path: PathLike, trajectory: Optional[PathLike] = None,
                    box: BoxInput = None, start: int = 0, stop: Optional[int] = None,
                    step: int = 1, *, water: bool = False, device: str = "auto",
                    samples: int = 30,
                    tol: Optional[float] = None, tiles: int = 0, all_pairs: bool = False,
                    threads: int = 0, verbose: bool = False, progress: Any = None
                    ) -> List[PeriodicResult]:
    """The periodic vertices of every selected frame, as `vorball vertices
    --periodic [--traj TRAJECTORY] [--frames A:B:S]`: each frame in the box
    it carries (GRO's box line, an XTC/TRR/DCD frame's box, PDB's CRYST1)
    or in `box` for all; water: keep water molecules (`--water`). A
    binary frame's floats become their shortest decimals in Angstrom
    (README). Returns a list of PeriodicResult with
    .frame and .model set. Raises VorballError (E120 for a frame without
    a box and no box given)."""
    from ._vertices import _options
    rng = frame_range(start, stop, step)
    if not isinstance(device, str):
        raise misuse("device must be auto, gpu, cpu or ref, not %r" % (device,))
    opts = (device, None) + _options(samples, tol, tiles, all_pairs, threads) + (progress,)
    traj = None if trajectory is None else os.fspath(trajectory)
    got, diag = _core.periodic_frames(os.fspath(path), traj, box_tokens(box), *rng, bool(water),
                                      opts)
    w = parse(diag)
    emit(w, verbose)
    return [PeriodicResult(d, w, frame, model) for frame, model, d in got]


NOT_CANONICAL, BEYOND_REACH = 1, 2  # PeriodicReport.flags (VB_PERIODIC_* of vb_periodic.h)


class PeriodicReport:
    """A periodic vertex file judged exactly, as `vorball verify --periodic`.

    ok        every line certified
    counts    dict: lines, certified, not_canonical, beyond_reach,
              not_vertex, wrong_coordinates, missing_members, duplicate
              (the keys of the command's --json)
    line      (m,) int64: each vertex line's line in the file
    flags     (m,) uint8: NOT_CANONICAL (not its vertex's canonical
              translate), BEYOND_REACH (beyond the images' proven reach)
    problems  (m,) int32: the exact verifier's bits (vorball.NOT_VERTEX,
              WRONG_COORDS, MISSING, DUPLICATE; 0: certified or not judged)
    """

    def __init__(self, d: Any, warnings: List[Diagnostic]) -> None:
        self.counts = {k: d[k] for k in ("lines", "certified", "not_canonical", "beyond_reach",
                                          "not_vertex", "wrong_coordinates", "missing_members",
                                          "duplicate")}
        self.ok = self.counts["certified"] == self.counts["lines"]
        self.line = np.frombuffer(d["line"], dtype=np.int64)
        self.flags = np.frombuffer(d["flags"], dtype=np.uint8)
        self.problems = np.frombuffer(d["problems"], dtype=np.int32)
        self.warnings = warnings

    def __repr__(self) -> str:
        return "<vorball.PeriodicReport %d of %d lines certified>" % (
            self.counts["certified"], self.counts["lines"])


def verify_periodic(capsule, vertices: Any, box: BoxInput, tol: float, verbose: bool,
                    made: List[Diagnostic]) -> PeriodicReport:
    """vorball.verify(..., periodic=True): vertices a periodic vertex file's
    path or a PeriodicResult (its tsv, written to a temporary file that the
    library reads)."""
    tokens = box_tokens(box)
    if isinstance(vertices, PeriodicResult):
        with tempfile.TemporaryDirectory(prefix="vorball-") as tmp:
            path = os.path.join(tmp, "periodic.tsv")
            vertices.write(path)
            d, diag = _core.periodic_verify(capsule, path, tokens, float(tol))
    elif isinstance(vertices, (str, os.PathLike)):
        d, diag = _core.periodic_verify(capsule, os.fspath(vertices), tokens, float(tol))
    else:
        raise misuse("periodic verify judges a periodic vertex file or a PeriodicResult, not %r"
                     % (type(vertices).__name__,))
    w = made + parse(diag)
    emit(w, verbose)
    return PeriodicReport(d, w)
