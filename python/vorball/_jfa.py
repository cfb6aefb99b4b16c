"""Discrete Voronoi diagrams on [n]^d grids (`vorball jfa`): the JFA
variants and Facet-JFA, timed and checked against the exact diagram."""
from __future__ import annotations

import json as _json
import os
from typing import Any, Dict, List, Optional, Sequence

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._errors import Diagnostic, emit, misuse, parse
from ._spheres import SphereInput, as_spheres


class JfaRun:
    """One variant's run: variant (its name), time_ms and time_ms_min (mean
    and fastest of the repeats), gpu_ms, fill_ms, prep_transfer_ms, prep_ms,
    counts (dict: steps, pixels_processed, threads, m, boundary, collisions
    and the exact variants' tile counts), metrics (with check: wrong,
    differ, wrong_rate, max_err, mean_err, boundary_*; else None) and
    labels: the seed index of each pixel, (n, n) indexed [y, x] in 2D,
    (n, n, n) indexed [z, y, x] in 3D (uint32, read-only)."""

    variant: str
    time_ms: float
    time_ms_min: float
    gpu_ms: float
    fill_ms: float
    prep_transfer_ms: float
    prep_ms: float
    counts: Dict[str, int]
    metrics: Optional[Dict[str, Any]]
    labels: np.ndarray

    def __init__(self, d: Dict[str, Any], dim: int, n: int) -> None:
        for k in ("variant", "time_ms", "time_ms_min", "gpu_ms", "fill_ms", "prep_transfer_ms",
                  "prep_ms", "counts", "metrics"):
            setattr(self, k, d[k])
        self.labels = np.frombuffer(d["labels"], dtype=np.uint32).reshape((n,) * dim)

    def __repr__(self) -> str:
        return "<vorball.JfaRun %s: %.3f ms>" % (self.variant, self.time_ms)


class Jfa:
    """The figures of a `vorball jfa` run.

    runs        a JfaRun per variant, in the order asked
    labels      the last run's labels (what --png pictures)
    device, dim, n, seeds (count), source, repeat, exact_ms (with check,
    else None); text and json: what the command prints (the table, or
    with --json its document), byte for byte but the times; warnings.
    picture(slices) is --png's image as an array.
    """

    runs: List[JfaRun]
    device: str
    dim: int
    n: int
    seeds: int
    source: str
    repeat: int
    exact_ms: Optional[float]
    text: str
    json: str
    warnings: List[Diagnostic]

    def __init__(self, d: Dict[str, Any], warnings: List[Diagnostic]) -> None:
        for k in ("device", "dim", "n", "seeds", "source", "repeat", "exact_ms", "text", "json"):
            setattr(self, k, d[k])
        self.runs = [JfaRun(r, self.dim, self.n) for r in d["runs"]]
        self.warnings = warnings

    @property
    def labels(self) -> np.ndarray:
        return self.runs[-1].labels

    def picture(self, slices: Optional[Sequence[int]] = None,
                run: int = -1) -> np.ndarray:
        """The image `vorball jfa --png` writes, as an (n, w, 3) uint8 array
        (row 0 at the top): each region a colour from its label, boundary
        pixels black; in 3D the z-slices side by side (`--slice`: default
        n/2; each below n, at most 16: else VorballError E7)."""
        labels = self.runs[run].labels
        (rgb, w), diag = _core.jfa_picture(labels.tobytes(), self.dim, self.n,
                                           None if slices is None else list(slices))
        emit(parse(diag), False)
        return np.frombuffer(rgb, dtype=np.uint8).reshape(self.n, w, 3)

    def to_json(self) -> Any:
        """The JSON document as Python objects."""
        return _json.loads(self.json)

    def __repr__(self) -> str:
        return "<vorball.Jfa %d^%d, %d seeds, %d run(s) on %s>" % (
            self.n, self.dim, self.seeds, len(self.runs), self.device)


def jfa(seeds: Any = None, *, protein: Optional[SphereInput] = None, dim: Optional[int] = None,
        size: Optional[int] = None, k: Optional[int] = None, dist: Optional[str] = None,
        rng: Optional[int] = None, margin: Optional[float] = None,
        variant: Optional[str] = None, m: Optional[int] = None,
        fuse_cells: Optional[int] = None, device: str = "auto", check: bool = False,
        repeat: Optional[int] = None, verbose: bool = False) -> Jfa:
    """The discrete Voronoi diagram of seeds on an [n]^d grid, as `vorball
    jfa` (the same library calls: its seeds, runs, checks and figures).

    seeds: a seed file (a path: 'x y' or 'x y z' per line, pixels), or an
    array (k, dim) of pixel coordinates, each in [-0.5, n - 0.5); None:
    generated (k, dist: uniform|clustered|shell, rng), or with protein (a
    path, a Spheres or arrays) the atom centres fitted into an [n]^3 grid
    with margin (Angstrom). dim (-d), size (-n, a power of two), variant
    (-V: 'jfa+1', 'facet,exact', 'all', ...), m, fuse_cells, repeat,
    device (auto|gpu|cpu|ref) and check (--check) as the command's options;
    None: the library's default. Each is set by name on the library's
    jfa handle (vb_jfa.h, its ranges): a bad value raises VorballError
    E7 with the command's words. Returns a Jfa; warnings W780, W781, W782, W751 as the
    command's, in .warnings (printed with verbose).
    """
    numbers = {"dim": dim, "n": size, "k": k, "m": m, "fuse_cells": fuse_cells,
               "repeat": repeat, "rng": rng, "margin": margin}
    for name, v in (("dist", dist), ("variant", variant)):
        if v is not None and not isinstance(v, str):
            raise misuse("%s must be a name, not %r" % (name, v))
    if not isinstance(device, str):
        raise misuse("device must be auto, gpu, cpu or ref, not %r" % (device,))
    path = points = cap = name = None
    made: List[Diagnostic] = []
    if protein is not None:
        if seeds is not None:
            raise misuse("give either seeds or protein")
        s, made = as_spheres(protein, None, min_count=1, exact=False, revalidated=False)
        cap = s._capsule
        name = os.fspath(protein) if isinstance(protein, (str, os.PathLike)) else s.source
        numbers["dim"] = 3 if dim is None else dim
    elif isinstance(seeds, (str, os.PathLike)):
        path = os.fspath(seeds)
    elif seeds is not None:
        p = np.asarray(seeds)
        if p.ndim != 2 or p.shape[1] not in (2, 3) or p.dtype.kind not in "iuf":
            raise misuse("seeds must be a path or a (k, 2) or (k, 3) array of numbers")
        numbers["dim"] = p.shape[1] if dim is None else dim
        if numbers["dim"] != p.shape[1]:
            raise misuse("seeds have %d columns, dim is %r" % (p.shape[1], dim))
        points = np.ascontiguousarray(p, dtype=np.float64)
    d, diag = _core.jfa_run(numbers, dist, variant, device, bool(check), path, points, cap, name)
    w = made + parse(diag)
    emit(w, verbose)
    return Jfa(d, w)
