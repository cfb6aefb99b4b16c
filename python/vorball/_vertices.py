"""The certified Voronoi vertices of spheres (the vertex pipeline)."""
from __future__ import annotations

import numbers
import os
import threading
import time
from typing import Any, Callable, Dict, List, NamedTuple, Optional, Union

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._errors import Diagnostic, emit, misuse, parse
from ._periodic import BoxInput, PeriodicResult, run_periodic
from ._channels import Channels, run_channels
from ._channels import _default as channel_default
from ._spheres import PathLike, SphereInput, Spheres, as_spheres


class Certificate(NamedTuple):
    """What a run proves. complete: every vertex of the diagram is among the
    certified ones (the direction cover's proof; False for the sampling
    proposer, which proves nothing about completeness); text: the line the
    command writes into its output header ('' when not complete)."""
    complete: bool
    text: str
    certified: int     # certified vertices (each proven exactly)
    rejected: int      # candidates (or cover roots) the certifier refused
    quadruples: int    # quadruples the cover proposed
    cover_cells: int
    cover_patches: int
    cover_host_cells: int


class Arcs(NamedTuple):
    """Arc closure of the certified list (vertices(..., arcs=True)): every
    Voronoi edge of the certified vertices traced exactly to its next
    vertex, as `vorball vertices --arcs` does. complete: every arc closed
    and no vertex added; the other fields are the counts of the command's
    '# arcs:' header line."""
    complete: bool
    vertices: int      # vertices traced: the proposer's and those added
    half_arcs: int     # arcs leaving a vertex (a finite edge counts from both ends)
    closed: int        # half arcs that end at a certified vertex
    infinite: int      # half arcs to infinity
    loops: int         # half arcs of a closed curve back to their vertex
    undecided: int     # half arcs not traced exactly (warning W766)
    added: int         # vertices found by tracing (certified and in the result)
    components: int    # connected components of the vertex-edge graph


class Topology(NamedTuple):
    """Faces and edges of the diagram (vertices(..., topology=True)), the
    file `vorball vertices --topology FILE` writes: exact from arc closure,
    or with proposer='sampling' and arcs=False from the sampling's evidence.
    faces         (k, 2) int64: sphere pairs i < j that share a face
    edges         (m, 2) int64: rows of the result's vertices an edge joins
                  (-1: the edge runs to infinity; both equal: a closed loop)
    edge_spheres  (m, 3) int64: the three spheres whose faces meet along it
    exact         True when from arc closure
    unresolved    what could not be decided (warning W765)
    sampled       edge lines the sampling's two-colour test saw"""
    faces: np.ndarray
    edges: np.ndarray
    edge_spheres: np.ndarray
    exact: bool
    unresolved: int
    sampled: int


def _arcs(d):
    return None if d is None else Arcs(d["complete"], d["vertices"], d["half_arcs"], d["closed"],
                                       d["infinite"], d["loops"], d["undecided"], d["added"],
                                       d["components"])


def _topology(d):
    if d is None:
        return None

    def rows(key, dtype, k):
        return np.frombuffer(d[key], dtype=dtype).astype(np.int64).reshape(-1, k)
    return Topology(rows("faces", np.uint32, 2), rows("edges", np.int64, 2),
                    rows("edge_spheres", np.uint32, 3), bool(d["exact"]), d["unresolved"],
                    d["sampled"])


def _csr(d):
    flat = np.frombuffer(d["ids"], dtype=np.uint32).astype(np.int64)
    start = np.frombuffer(d["start"], dtype=np.int64)
    return flat, start


def _vertex_arrays(d):
    """(ids_flat, offsets, ids, xyz, t) of the library's vertex arrays."""
    flat, start = _csr(d)
    ids = np.split(flat, start[1:-1]) if len(start) > 1 else []
    xyz = np.stack([np.frombuffer(d[k], dtype=np.float64) for k in "xyz"], axis=1) \
        if len(start) > 1 else np.empty((0, 3))
    return flat, start, ids, xyz, np.frombuffer(d["t"], dtype=np.float64)


class Result(tuple):
    """The certified vertices: unpacks as (ids, xyz, t).

    ids      list of int64 arrays, the sorted 0-based ids of all the spheres
             each vertex touches (4, or more at a degenerate vertex)
    xyz      (m, 3) float64: the exact vertex rounded to the nearest double
    t        (m,) float64: the tangent radius (negative where spheres overlap)
    ids_flat, offsets   the same ids as one array and m + 1 offsets
    certificate  a Certificate (complete, counts; its text holds the
             '# arcs:' line too when arcs were traced)
    arcs     an Arcs (arc closure's counts) when asked for, else None
    topology a Topology (faces and edges) when asked for, else None;
             topology_text() the --topology file
    stats    every counter `vorball vertices --stats` prints (with arcs,
             its arc_* lines too), as a dict of int, float (the library's
             value, not the printed digits) and str, from the library's
             one table of them (vb_vertices_stats, vb_arc_stats)
    times    seconds per stage (setup, certify, total, cull, ...)
    backend, device   what ran ('opencl' or 'ref', and the device name)
    warnings the warnings (vorball.Diagnostic) of reading the file or arrays
             given to this call, then of the run, each once: the lines
             the command prints; printed only when verbose
    spheres  the Spheres the vertices belong to
    Vertices are in the command's canonical order; to_text() gives the
    bytes `vorball vertices` writes.
    """

    ids: List[np.ndarray]
    xyz: np.ndarray
    t: np.ndarray
    ids_flat: np.ndarray
    offsets: np.ndarray
    certificate: Certificate
    arcs: Optional[Arcs]
    topology: Optional[Topology]
    stats: Dict[str, Union[int, float, str]]
    times: Dict[str, float]
    backend: str
    device: str
    max_distance: float
    warnings: List[Diagnostic]
    spheres: Optional[Spheres]

    def __new__(cls, d: Dict[str, Any], warnings: List[Diagnostic],
                spheres: Optional[Spheres]) -> Result:
        flat, start, ids, xyz, t = _vertex_arrays(d)
        self = super().__new__(cls, (ids, xyz, t))
        self.ids, self.xyz, self.t = ids, xyz, t
        self.ids_flat, self.offsets = flat, start
        self.certificate = Certificate(bool(d["complete"]), d["certificate"], d["certified"],
                                       d["rejected"], d["quadruples"], d["cover_cells"],
                                       d["cover_patches"], d["cover_host_cells"])
        self.arcs, self.topology = _arcs(d["arcs"]), _topology(d["topology"])
        self._topology_text = None if d["topology"] is None else d["topology"]["text"]
        self.stats = dict(d["stats"])
        self.times = dict(d["times"])
        self.backend, self.device = d["backend"], d["device"]
        self.max_distance = d["max_distance"]
        self.warnings = warnings
        self.spheres = spheres
        return self

    def __reduce__(self):
        # Pickled without its Spheres (a handle on library memory).
        state = {k: v for k, v in self.__dict__.items() if k != "spheres"}
        return (_restore, (tuple(self), state))

    def __repr__(self) -> str:
        return "<vorball.Result %d certified vertices%s, %s on %s>" % (
            len(self.t), ", complete" if self.certificate.complete else "", self.backend,
            self.device)

    def to_text(self, format: str = "tsv") -> str:
        """The vertex file `vorball vertices --output-format F` writes (tsv,
        json or voronota), byte for byte, certificate line included."""
        if format == "npz":
            raise misuse("npz is a binary archive: to_bytes('npz') or write(path, 'npz')")
        return vertex_text(self.ids_flat, self.offsets, self.xyz, self.t, format,
                           self.certificate.text)

    def to_bytes(self, format: str = "npz") -> bytes:
        """The vertex file as bytes: npz (`--output-format npz`, a NumPy
        archive that np.load reads without pickle), or a text format's UTF-8."""
        if format != "npz":
            return self.to_text(format).encode("utf-8")
        return vertex_text(self.ids_flat, self.offsets, self.xyz, self.t, format,
                           self.certificate.text)

    def topology_text(self) -> Optional[str]:
        """The file `vorball vertices --topology FILE` writes (faces and
        edges), or None without topology=True."""
        return self._topology_text

    def write(self, path: PathLike, format: str = "tsv") -> None:
        """Writes the vertex file in format (tsv, json, voronota, npz) to path."""
        with open(os.fspath(path), "wb") as f:
            f.write(self.to_bytes(format))

    def write_html(self, path: PathLike, title: Optional[str] = None) -> None:
        """Writes the results page of `vorball vertices --html` to path: the
        spheres and these vertices as markers, with the certificate line;
        titled title (default "vorball vertices " and the spheres' source,
        as the command titles it). Raises VorballError E133 past the page's
        size (2,000 spheres)."""
        if self.spheres is None:
            raise misuse("the result holds no spheres (unpickled): no page")
        if title is None:
            title = "vorball vertices %s" % self.spheres.source
        cols = [np.ascontiguousarray(self.xyz[:, k]) for k in range(3)]
        _, diag = _core.vertex_page(self.spheres._capsule,
                                    np.ascontiguousarray(self.ids_flat, dtype=np.uint32),
                                    np.ascontiguousarray(self.offsets, dtype=np.int64),
                                    cols[0], cols[1], cols[2], self.t, self.certificate.text,
                                    os.fspath(path), str(title))
        emit(parse(diag), False)


def _restore(fields, state):
    r = tuple.__new__(Result, fields)
    r.__dict__.update(state)
    r.spheres = None
    return r


def vertex_text(ids_flat: ArrayLike, offsets: ArrayLike, xyz: ArrayLike, t: ArrayLike,
                format: str = "tsv", comment: Optional[str] = None) -> Union[str, bytes]:
    """The library's vertex writer over CSR arrays (see Result.to_text)."""
    ids = np.ascontiguousarray(ids_flat, dtype=np.uint32)
    off = np.ascontiguousarray(offsets, dtype=np.int64)
    xyz = np.asarray(xyz, dtype=np.float64).reshape(-1, 3)
    cols = [np.ascontiguousarray(xyz[:, k]) for k in range(3)]
    return _core.vertex_text(ids, off, cols[0], cols[1], cols[2],
                             np.ascontiguousarray(t, dtype=np.float64), format, comment)


class Reference(tuple):
    """Every vertex of the diagram, exactly, by brute force (`vorball
    reference`): unpacks as (ids, xyz, t), with ids_flat and offsets as in
    Result, warnings (vorball.Diagnostic) and spheres. to_text(format)
    gives the vertex file (tsv, json or voronota) with the numbers that
    `vorball reference` writes. stats: the counts of `--stats`
    (quadruples, refuted by the filter, filter_calls, undecided,
    exact_evals) and seconds (this call's wall clock)."""

    def __new__(cls, d: Dict[str, Any], warnings: List[Diagnostic],
                spheres: Optional[Spheres]) -> Reference:
        flat, start, ids, xyz, t = _vertex_arrays(d)
        self = super().__new__(cls, (ids, xyz, t))
        self.ids, self.xyz, self.t = ids, xyz, t
        self.ids_flat, self.offsets = flat, start
        self.warnings, self.spheres = warnings, spheres
        self.stats = dict(d["stats"])
        return self

    def __repr__(self) -> str:
        return "<vorball.Reference %d exact vertices>" % len(self.t)

    def to_text(self, format: str = "tsv") -> str:
        """The vertex file of these vertices in format (tsv, json, voronota)."""
        n = len(self.spheres) if self.spheres is not None else 0
        return vertex_text(self.ids_flat, self.offsets, self.xyz, self.t, format,
                           "vorball.reference: %d spheres, %d vertices" % (n, len(self.t)))


def reference(xyz: SphereInput, r: Optional[ArrayLike] = None, *, force: bool = False,
              zero_radius: str = "auto", select: Optional[str] = None,
              verbose: bool = False) -> Reference:
    """Every Voronoi vertex of the spheres exactly, from all quadruples
    (`vorball reference`: the oracle for small inputs; its cost grows as
    n^4). xyz, r, zero_radius and select as for vorball.vertices. Above 500
    spheres it raises VorballError E130 unless force (`--force`). Returns a
    Reference that unpacks as (ids, xyz, t). Nothing is printed unless
    verbose."""
    s, made = as_spheres(xyz, r, min_count=4, zero_radius=zero_radius, select=select)
    t0 = time.perf_counter()
    d, diag = _core.reference_run(s._capsule, bool(force))
    d["stats"]["seconds"] = time.perf_counter() - t0
    w = made + parse(diag)
    emit(w, verbose)
    return Reference(d, w, s)


def devices(verbose: bool = False) -> str:
    """The OpenCL platforms and devices, one tab-separated line each, and
    last '#auto<TAB>' with the device that device='auto' takes: the table
    `vorball devices` prints."""
    text, diag = _core.devices()
    emit(parse(diag), verbose)
    return text


def _options(samples, tol, tiles, all_pairs, threads):
    for name, v, lo in (("samples", samples, 0), ("tiles", tiles, 0), ("threads", threads, 0)):
        if not isinstance(v, numbers.Integral) or isinstance(v, bool) or not lo <= v < 2**31:
            raise misuse("%s must be a non-negative integer, not %r" % (name, v))
    if tol is None:
        tol = 0.0
    elif not isinstance(tol, numbers.Real) or not tol > 0:
        raise misuse("tol must be a positive length, not %r" % (tol,))
    return int(samples), float(tol), int(tiles), bool(all_pairs), int(threads)


def _proposer(p):
    if p is not None and not isinstance(p, str):
        raise misuse("proposer must be a name (cover, sampling), not %r" % (p,))
    return p


def vertices(xyz: SphereInput, r: Optional[ArrayLike] = None, device: str = "auto",
             samples: int = 30, *, proposer: Optional[str] = None, tol: Optional[float] = None,
             tiles: int = 0, all_pairs: bool = False, threads: int = 0,
             arcs: bool = False, topology: bool = False, zero_radius: str = "auto",
             select: Optional[str] = None, periodic: bool = False, box: BoxInput = None,
             verbose: bool = False, progress: Optional[Callable[[str, int, int], Any]] = None
             ) -> Union[Result, PeriodicResult]:
    """The certified Voronoi vertices of spheres, as `vorball vertices`.

    xyz, r: arrays (see vorball.spheres for how each number becomes an
    exact decimal), or a Spheres (vorball.read, a frame), or a file path.
    device: auto (a GPU, on host threads below 20,000 spheres, where
    VORBALL_HOST_BELOW puts the crossover; else PoCL on the CPU), gpu, cpu or ref (the
    plain-C reference; same output); a device that cannot be used falls
    back to the reference with warning W760. samples: S x S rays per cube
    face for the sampling proposer; proposer: 'cover' (the default: proves
    that no vertex is missing) or 'sampling' (the seed paper's rays); tol,
    tiles, all_pairs, threads as the command's --tol, --tiles, --all-pairs,
    --threads (the output never depends on threads or device). arcs: trace
    every edge of the certified vertices exactly (`--arcs`: vertices found
    on the way are certified and added, result.arcs holds the counts);
    topology: the faces and edges (`--topology`; exact from arc closure,
    which it implies unless proposer='sampling' and arcs=False).
    progress: a callable called as progress(stage, done, total) while
    the library works (stage 'cover', 'certify', 'arcs', ...; done rises to
    total within a stage, total 0 when not known), at most about 1000
    times a stage, from a worker thread; an exception it raises is printed
    as unraisable (sys.unraisablehook) and stops the calls, never the run.
    select: only the atoms this expression selects (`--select`,
    Spheres.select; E118 for a bad or empty selection).
    periodic: the periodic diagram of the atoms repeated by the box
    (`--periodic`): the file's box (GRO's box line, PDB's CRYST1; a
    frame's own) unless box is given; box (implies periodic, `--box`):
    (a, b, c), (a, b, c, alpha, beta, gamma) in degrees, or a 3x3 matrix
    of the edge vectors as rows, in input units; numbers become exact
    decimals (a float its shortest round-trip decimal; a str verbatim).
    Returns a PeriodicResult (ids and image shifts of every vertex's
    members, once per vertex); E120 for no box or a flat or malformed
    one, E135 for a box too small; not with arcs or topology.
    Returns a Result that unpacks as (ids, xyz, t). Raises VorballError.
    Nothing is printed unless verbose.
    """
    opts = _options(samples, tol, tiles, all_pairs, threads)
    if not isinstance(device, str):
        raise misuse("device must be auto, gpu, cpu or ref, not %r" % (device,))
    if periodic or box is not None:
        if arcs or topology:
            raise misuse("periodic runs without arcs or topology (as the command's --periodic)")
        s, made = as_spheres(xyz, r, min_count=1, zero_radius=zero_radius, select=select)
        return run_periodic(s._capsule, box, (device, _proposer(proposer)) + opts + (progress,),
                            verbose, made)
    s, made = as_spheres(xyz, r, min_count=4, zero_radius=zero_radius, select=select)
    d, diag = _core.vertices_run(s._capsule, None, device, _proposer(proposer), *opts,
                                 bool(arcs), bool(topology), progress)
    w = made + parse(diag)
    emit(w, verbose)
    return Result(d, w, s)


class Engine:
    """A device opened once for many runs (the frames of a trajectory): the
    vertex pipeline's device and proposer, and the channel pipeline, each
    opened on first use by the one fallback rule. engine.vertices() and
    engine.channels() take the arguments of vorball.vertices and
    vorball.channels and give the same results. Safe to share between
    threads (one run at a time). A context manager; close() releases the
    device.
    """

    def __init__(self, device: str = "auto", proposer: Optional[str] = None,
                 jfa: Optional[str] = None, verbose: bool = False) -> None:
        jfa = channel_default("jfa") if jfa is None else jfa  # the channel table's default
        if not isinstance(device, str) or not isinstance(jfa, str):
            raise misuse("device and jfa are names")
        self.device, self.proposer, self.jfa = device, _proposer(proposer), jfa
        self.verbose = verbose
        self.warnings: List[Diagnostic] = []  # from opening the devices (W760, W804)
        self._vertices = None
        self._pipe = None
        self._carry = None
        self._lock = threading.Lock()
        self._frames_run = 0

    def _open(self, opener, *args):
        """A capsule from opener(*args), its warnings kept (call with the lock)."""
        cap, diag = opener(*args)
        w = parse(diag)
        emit(w, self.verbose)
        self.warnings.extend(w)
        return cap

    @property
    def setup_seconds(self) -> Optional[float]:
        """The seconds opening the vertex pipeline's device took (`vorball
        bench`'s device_setup), or None before the first vertices run."""
        with self._lock:
            if self._vertices is None:
                return None
            return _core.vertices_engine_seconds(self._vertices)

    def vertices(self, xyz: SphereInput, r: Optional[ArrayLike] = None, samples: int = 30, *,
                 tol: Optional[float] = None, tiles: int = 0, all_pairs: bool = False,
                 threads: int = 0, arcs: bool = False, topology: bool = False,
                 zero_radius: str = "auto", periodic: bool = False, box: BoxInput = None,
                 verbose: Optional[bool] = None,
                 progress: Optional[Callable[[str, int, int], Any]] = None
                 ) -> Union[Result, PeriodicResult]:
        """vorball.vertices on this engine's device and proposer; periodic
        and box as there (a PeriodicResult, the same bytes: the frames of a
        trajectory each in its own box, the device opened once)."""
        verbose = self.verbose if verbose is None else verbose
        opts = _options(samples, tol, tiles, all_pairs, threads)
        if periodic or box is not None:
            if arcs or topology:
                raise misuse("periodic runs without arcs or topology (as the command's "
                             "--periodic)")
            s, made = as_spheres(xyz, r, min_count=1, zero_radius=zero_radius)
            with self._lock:
                if self._vertices is None:
                    self._vertices = self._open(_core.vertices_engine_open, self.device,
                                                self.proposer)
                return run_periodic(s._capsule, box,
                                    (self.device, self.proposer) + opts + (progress,),
                                    verbose, made, self._vertices)
        s, made = as_spheres(xyz, r, min_count=4, zero_radius=zero_radius)
        with self._lock:
            if self._vertices is None:
                self._vertices = self._open(_core.vertices_engine_open, self.device,
                                            self.proposer)
            d, diag = _core.vertices_run(s._capsule, self._vertices, self.device, self.proposer,
                                         *opts, bool(arcs), bool(topology), progress)
        w = made + parse(diag)
        emit(w, verbose)
        return Result(d, w, s)

    def channels(self, xyz: SphereInput, r: Optional[ArrayLike] = None,
                 grid: Optional[int] = None, probe: Optional[float] = None,
                 **kw: Any) -> Channels:
        """vorball.channels on this engine's device (see there); later frames
        sweep the pore axis that the first frame found, as the command's
        frames do."""
        with self._lock:
            if self._pipe is None:
                self._pipe = self._open(_core.channels_open, self.device, self.jfa)
                self._carry = _core.channels_carry()
            first = self._frames_run == 0
            self._frames_run += 1
            return run_channels(self._pipe, first, xyz, r, grid, probe, carry=self._carry,
                                verbose=kw.pop("verbose", self.verbose), **kw)

    def close(self) -> None:
        with self._lock:
            self._vertices = None
            self._pipe = None

    def __enter__(self) -> Engine:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
