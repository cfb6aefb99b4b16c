"""Exact judgement of vertices against spheres (`vorball verify`)."""
from __future__ import annotations

import json as _json
import numbers
import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._errors import Diagnostic, emit, error, misuse, parse
from ._periodic import BoxInput, PeriodicReport, verify_periodic
from ._spheres import PathLike, SphereInput, as_spheres
from ._vertices import Arcs, Result, _arcs

# Vertices as verify takes them: a Result, (ids, xyz, t) in memory, or a
# vertex file.
VertexInput = Union[Result, Tuple[Sequence[ArrayLike], ArrayLike, ArrayLike], PathLike]

# Problem bits of each line (enum vb_verify_problem).
NOT_VERTEX, WRONG_COORDS, MISSING, DUPLICATE = 1, 2, 4, 8
_NAMES = ((NOT_VERTEX, "not a vertex"), (WRONG_COORDS, "wrong coordinates"),
          (MISSING, "missing members"), (DUPLICATE, "duplicate"))


class Report:
    """The judgement of every vertex (line) by the exact certifier.

    ok         every line certified, (with complete) nothing missed and
               (with arcs) every arc closed with no vertex added
    counts     dict: lines, certified, not_vertex, wrong, missing,
               duplicate, missed, groups
    problems   (m,) int: the bits NOT_VERTEX, WRONG_COORDS, MISSING,
               DUPLICATE of each line (0: certified)
    line       (m,) the source line (for vertices in memory: row + 1)
    dist, dt   distance of each line's point to the exact vertex, |t - t_exact|
    exact      (m, 4) the exact vertex (x y z t) rounded, where known
    intruder   (m,) the sphere cutting the tangent sphere of a line that is
               not a vertex (-1 when none)
    missed     with complete: (ids, xyz, t) of the vertices no line names
    arcs       with arcs: an Arcs (arc closure's counts; added: the vertices
               it found that no line names), else None
    arcs_missing  with arcs: (ids, xyz, t) of those vertices, else None
    text, json the report `vorball verify` writes (text, and --json; with
               arcs those of `--arcs`)
    """

    ok: bool
    counts: Dict[str, int]
    format: str
    tol: float
    text: str
    json: str
    problems: np.ndarray
    line: np.ndarray
    dist: np.ndarray
    dt: np.ndarray
    exact: np.ndarray
    intruder: np.ndarray
    missed: Tuple[List[np.ndarray], np.ndarray, np.ndarray]
    arcs: Optional[Arcs]
    arcs_missing: Optional[Tuple[List[np.ndarray], np.ndarray, np.ndarray]]
    warnings: List[Diagnostic]

    def __init__(self, d: Dict[str, Any], warnings: List[Diagnostic]) -> None:
        self.warnings = warnings
        self.ok = bool(d["ok"])
        self.counts = dict(d["counts"])
        self.format, self.tol = d["format"], d["tol"]
        self.text, self.json = d["text"], d["json"]
        self.problems = np.frombuffer(d["problems"], dtype=np.int32)
        self.line = np.frombuffer(d["line"], dtype=np.int64)
        self.dist = np.frombuffer(d["dist"], dtype=np.float64)
        self.dt = np.frombuffer(d["dt"], dtype=np.float64)
        self.exact = np.frombuffer(d["exact"], dtype=np.float64).reshape(-1, 4)
        intr = np.frombuffer(d["intruder"], dtype=np.uint32).astype(np.int64)
        intr[intr == 2**32 - 1] = -1
        self.intruder = intr
        self.missed = _rows(d["missed"])
        self.arcs = _arcs(d["arcs"])
        self.arcs_missing = _rows(d["arcs"]["missing"]) if d["arcs"] else None

    def classes(self, k: int) -> List[str]:
        """The names of the problems of line k ([] when certified)."""
        return [name for bit, name in _NAMES if self.problems[k] & bit]

    def to_json(self) -> Any:
        """The --json report as Python objects."""
        return _json.loads(self.json)

    def __repr__(self) -> str:
        c = self.counts
        return "<vorball.Report %s: %d of %d lines certified, %d missed>" % (
            "ok" if self.ok else "PROBLEMS", c["certified"], c["lines"], c["missed"])


def _rows(m):
    """(ids, xyz, t) of vertices handed over as CSR bytes."""
    flat = np.frombuffer(m["ids"], dtype=np.uint32).astype(np.int64)
    start = np.frombuffer(m["start"], dtype=np.int64)
    ids = np.split(flat, start[1:-1]) if len(start) > 1 else []
    xyz = np.stack([np.frombuffer(m[k], dtype=np.float64) for k in "xyz"], axis=1) \
        if len(start) > 1 else np.empty((0, 3))
    return ids, xyz, np.frombuffer(m["t"], dtype=np.float64)


def _csr(vertices):
    """(ids uint32, offsets int64, x, y, z, t) of (ids, xyz, t)."""
    if isinstance(vertices, Result):
        ids, xyz, t = vertices.ids_flat, vertices.xyz, vertices.t
        off = vertices.offsets
    else:
        try:
            ids_list, xyz, t = vertices
        except (TypeError, ValueError):
            raise misuse("vertices must be a Result, (ids, xyz, t) or a vertex file path") from None
        if isinstance(ids_list, np.ndarray) and ids_list.ndim == 2:
            ids_list = list(ids_list)
        rows = [np.asarray(v) for v in ids_list]
        for k, v in enumerate(rows):
            if v.ndim != 1 or v.dtype.kind not in "iu":
                raise misuse("vertex %d: ids must be a 1-D integer array" % k)
            if v.size and (v.min() < 0 or v.max() >= 2**32 - 1):
                raise misuse("vertex %d: sphere id out of range" % k)
            if np.unique(v).size != v.size:
                raise error(101, "vertices row %d: a sphere is named twice" % k)
        off = np.zeros(len(rows) + 1, dtype=np.int64)
        off[1:] = np.cumsum([v.size for v in rows])
        ids = np.concatenate(rows) if rows else np.zeros(0, np.int64)
    xyz = np.asarray(xyz, dtype=np.float64)
    t = np.asarray(t, dtype=np.float64)
    m = len(off) - 1
    if xyz.shape != (m, 3) or t.shape != (m,):
        raise misuse("vertices: %d id lists need xyz of shape (%d, 3) and t of (%d,)" % (m, m, m))
    return (np.ascontiguousarray(ids, dtype=np.uint32), np.ascontiguousarray(off, dtype=np.int64),
            np.ascontiguousarray(xyz[:, 0]), np.ascontiguousarray(xyz[:, 1]),
            np.ascontiguousarray(xyz[:, 2]), np.ascontiguousarray(t))


def _is_vertices(v):
    return isinstance(v, (Result, str, os.PathLike)) or (isinstance(v, tuple) and len(v) == 3)


def verify(xyz: SphereInput, r: Union[ArrayLike, VertexInput, None] = None,
           vertices: Optional[VertexInput] = None, *, tol: float = 1e-6, complete: bool = False,
           arcs: bool = False, threads: int = 0, format: str = "tsv", zero_radius: str = "auto",
           periodic: bool = False, box: BoxInput = None, verbose: bool = False,
           progress: Optional[Callable[[str, int, int], Any]] = None
           ) -> Union[Report, PeriodicReport]:
    """Judges vertices exactly against the spheres, as `vorball verify`.

    xyz, r: the spheres (arrays, a Spheres or a file path; r may be left
    out: verify(spheres, vertices)). vertices: a Result, (ids, xyz, t) in
    memory (ids a list of int arrays or an (m, k) array), or the path of a
    vertex file (tsv, json or Voronota's, detected by content). format
    says how vertices in memory are grouped: 'voronota' judges quadruple
    lines of one vertex together. tol: distance tolerance (> 0); complete:
    also list the vertices no line names (exact reference: small inputs);
    arcs: trace every edge of the certified lines exactly (`--arcs`, any
    size; report.arcs, report.arcs_missing); threads: its host threads
    (0: all CPUs; the report does not depend on it). progress: a callable called as progress(stage, done, total) while
    the library works (stage 'arcs'; done rises to
    total within a stage, total 0 when not known), at most about 1000
    times a stage, from a worker thread; an exception it raises is printed
    as unraisable (sys.unraisablehook) and stops the calls, never the run.
    periodic, box: vertices is a periodic vertex file (or a
    PeriodicResult) judged in the box (`verify --periodic`; box as
    vorball.vertices takes it, else the file's): each line its vertex's
    canonical translate, within the images' reach, certified exactly;
    returns a PeriodicReport (without complete or arcs; E120 for no box or a
    bad one).
    Returns a Report; raises VorballError (E105 for no vertices).
    """
    if periodic or box is not None:
        if complete or arcs:
            raise misuse("periodic verify judges each line: without complete or arcs")
        if not isinstance(tol, numbers.Real) or not tol > 0:
            raise misuse("tol must be > 0, not %r" % (tol,))
        if vertices is None:
            r, vertices = None, r
        s, made = as_spheres(xyz, r, min_count=1, zero_radius=zero_radius)
        return verify_periodic(s._capsule, vertices, box, tol, verbose, made)
    if vertices is None and r is not None and _is_vertices(r):
        r, vertices = None, r
    if vertices is None:
        raise misuse("verify needs vertices: a Result, (ids, xyz, t) or a vertex file path")
    if not isinstance(tol, numbers.Real) or not tol > 0:
        raise misuse("tol must be > 0, not %r" % (tol,))
    if not isinstance(threads, numbers.Integral) or isinstance(threads, bool) or \
            not 0 <= threads <= 64:
        raise misuse("threads must be an integer in 0..64, not %r" % (threads,))
    s, made = as_spheres(xyz, r, min_count=4, zero_radius=zero_radius)
    if isinstance(vertices, (str, os.PathLike)):
        v = os.fspath(vertices)
        name = v
    else:
        v = _csr(vertices)
        name = "<vertices>"
    d, diag = _core.verify_run(s._capsule, v, format, name, float(tol), bool(complete), s.source,
                               bool(arcs), int(threads), progress)
    w = made + parse(diag)
    emit(w, verbose)
    return Report(d, w)
