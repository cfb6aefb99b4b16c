"""Sphere sets: read from files by the library's readers, built from NumPy
arrays (exactly: see `spheres`), and the frames of trajectories."""
from __future__ import annotations

import decimal
import numbers
import os
from typing import Any, Iterable, Iterator, List, Optional, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._errors import ARRAYS, Diagnostic, emit, misuse, parse

# A file path as the calls take it.
PathLike = Union[str, os.PathLike]

_ZERO = {"auto": _core.ZERO_RADIUS_AUTO, "error": _core.ZERO_RADIUS_ERROR,
         "point": _core.ZERO_RADIUS_POINT, "drop": _core.ZERO_RADIUS_DROP}


def _zero_radius(word):
    try:
        return _ZERO[word]
    except (KeyError, TypeError):
        raise misuse("zero_radius must be auto, error, point or drop, not %r" % (word,)) from None


class Spheres:
    """A sphere set as the library holds it.

    xyz (n, 3) and r (n,) are the doubles the pipelines use; `decimals` the
    exact decimals the certifier uses (None for a frame of a binary
    trajectory, which has doubles only); `atoms` the atom records of
    PDB/PQR/mmCIF input (a structured array: serial, name, resname, chain,
    resseq, icode, altloc, element, hetatm; None for XYZR and arrays);
    `line` the source line of each sphere; `contained` which spheres lie
    inside another (their cells are empty). Frames of a trajectory also
    have `index` (from 0) and `model` (the MODEL serial, or index + 1).
    `warnings` holds what the reader reported (water dropped, unknown
    elements, ...). Arrays are read-only views.
    """

    n: int
    source: str
    exact: bool
    index: int
    model: int
    warnings: List[Diagnostic]
    xyz: np.ndarray
    r: np.ndarray
    line: np.ndarray
    contained: np.ndarray

    def __init__(self, capsule: Any, diagnostics: Optional[Iterable[tuple]] = None,
                 index: int = 0, model: int = 1) -> None:
        self._capsule = capsule
        info = _core.spheres_info(capsule)
        self.n = info["n"]
        self.source = info["source"]
        self.exact = info["exact"]
        self.index = index
        self.model = model
        self.warnings = parse(diagnostics)

        self.xyz = np.stack([np.frombuffer(info[k], dtype=np.float64) for k in "xyz"], axis=1)
        self.xyz.setflags(write=False)
        self.r = np.frombuffer(info["r"], dtype=np.float64)
        self.line = np.frombuffer(info["line"], dtype=np.int64)
        self.contained = (np.frombuffer(info["contained"], dtype=np.uint8).astype(bool)
                          if info["contained"] is not None else np.zeros(self.n, bool))
        self.contained.setflags(write=False)
        self._has_atoms = info["atoms"]
        self._atoms = None

    def __len__(self) -> int:
        return self.n

    def select(self, expr: str) -> "Spheres":
        """The spheres that expr selects, in their order, as a new Spheres
        (exact decimals kept): the grammar of `--select` (README, Input:
        chain, segid, resname, resid a:b, name, element, protein, water,
        and/or/not, parentheses). Raises VorballError E118 for a malformed
        expression (its position in the message) or an empty selection."""
        if not isinstance(expr, str):
            raise misuse("select must be an expression (a str), not %r" % (expr,))
        cap, diag = _core.spheres_select(self._capsule, expr)
        s = Spheres(cap, diag, index=self.index, model=self.model)
        return s

    def atoms_text(self) -> str:
        """The sphere table the commands' `--atoms FILE` writes: what each
        0-based id stands for (chain, residue, number, atom name, element,
        source line, the exact x y z r used), TSV."""
        text, diag = _core.spheres_atoms_text(self._capsule)
        emit(parse(diag), False)
        return text

    def __repr__(self) -> str:
        return "<vorball.Spheres %d from %r%s>" % (
            self.n, self.source, "" if self.exact else " (doubles only)")

    @property
    def atoms(self) -> Optional[np.ndarray]:
        """The atom records (structured array), or None."""
        if self._has_atoms and self._atoms is None:
            raw, itemsize, off = _core.spheres_atoms(self._capsule)
            fields = [("serial", "=i4"), ("resseq", "=i4"), ("name", "S8"), ("resname", "S8"),
                      ("chain", "S8"), ("element", "S4"), ("icode", "S1"), ("altloc", "S1"),
                      ("hetatm", "u1")]
            dt = np.dtype({"names": [f for f, _ in fields], "formats": [t for _, t in fields],
                           "offsets": [off[f] for f, _ in fields], "itemsize": itemsize})
            a = np.frombuffer(raw, dtype=dt)
            out = np.empty(self.n, dtype=[("serial", "i4"), ("name", "U8"), ("resname", "U8"),
                                          ("chain", "U8"), ("resseq", "i4"), ("icode", "U1"),
                                          ("altloc", "U1"), ("element", "U4"), ("hetatm", "?")])
            for f in out.dtype.names:
                v = a[f]
                out[f] = np.char.decode(v, "latin-1") if v.dtype.kind == "S" else v
            out.setflags(write=False)
            self._atoms = out
        return self._atoms

    @property
    def decimals(self) -> Optional[np.ndarray]:
        """The exact input numbers: an (n, 4) object array of decimal.Decimal
        (x, y, z, r), or None for a set of doubles only."""
        d = _core.spheres_decimals(self._capsule)
        if d is None:
            return None
        mant = np.frombuffer(d[0], dtype=np.int64)
        exp = np.frombuffer(d[1], dtype=np.int32)
        out = np.empty(mant.size, dtype=object)
        for k, (m, e) in enumerate(zip(mant.tolist(), exp.tolist())):
            out[k] = decimal.Decimal(m).scaleb(e, decimal.Context(prec=40))
        return out.reshape(self.n, 4)


# What the calls accept as spheres: a Spheres, a file path, or arrays.
SphereInput = Union[Spheres, PathLike, ArrayLike]


def _number_arg(name, v):
    # The ranges are the library's (vb_read_options_check), whose 0 is
    # "not given": None asks for that, an explicit 0 is refused as the
    # command refuses it.
    if v is None:
        return 0
    if not isinstance(v, numbers.Integral) or isinstance(v, bool):
        raise misuse("%s must be a %s number >= 1, not %r" % (name, name, v))
    return int(v) or -1


def _read_args(format, model, assembly, water, hydrogens, strict_elements, radii, zero_radius):
    if not isinstance(format, str):
        raise misuse("format must be a name (auto, xyzr, pdb, pqr, cif, ...), not %r" % (format,))
    radii = "" if radii is None else os.fspath(radii)
    return (format, _number_arg("model", model), _number_arg("assembly", assembly),
            int(bool(water)), int(not hydrogens), int(bool(strict_elements)),
            _zero_radius(zero_radius), radii)


def read(path: PathLike, format: str = "auto", model: Optional[int] = None, water: bool = False,
         hydrogens: bool = True, strict_elements: bool = False, radii: Optional[PathLike] = None,
         zero_radius: str = "auto", verbose: Optional[bool] = False,
         assembly: Optional[int] = None) -> Spheres:
    """Reads the spheres of a file as every `vorball` command does.

    path is any format the command reads (detected by content, or named by
    `format`: xyzr, pdb, pqr, cif|mmcif, and what later versions add).
    model picks a model of a multi-model file (default: the first);
    assembly (mmCIF, `--assembly N`) builds biological assembly N, its
    copies moved by the operators exactly; water
    keeps water; hydrogens=False drops H/D; strict_elements makes an
    unknown element an error (E108) instead of radius 1.70; radii names a
    radii file ('ELEMENT RADIUS' lines); zero_radius is auto (points in
    PQR, else an error), error, point or drop. The set is validated
    (duplicates, magnitudes, contained spheres flagged) as the commands
    validate it. Returns a Spheres; raises VorballError (E1xx with
    file:line). Warnings are in .warnings, printed only when verbose.
    """
    args = _read_args(format, model, assembly, water, hydrogens, strict_elements, radii,
                      zero_radius)
    mdl = args[1]
    cap, diag = _core.spheres_read(os.fspath(path), *args, 1)
    s = Spheres(cap, diag, model=mdl or 1)
    emit(s.warnings, verbose)
    return s


def frame_range(start: int, stop: Optional[int], step: int) -> Tuple[int, int, int]:
    """(start, stop or -1, step) for the library's frame range (`--frames
    A:B:S`) of the calls over frames; VorballError E7 for values that
    are not one."""
    for name, v, lo in (("start", start, 0), ("step", step, 1)):
        if not isinstance(v, numbers.Integral) or isinstance(v, bool) or v < lo:
            raise misuse("%s must be an integer >= %d, not %r" % (name, lo, v))
    if stop is not None and (not isinstance(stop, numbers.Integral) or isinstance(stop, bool)
                             or stop < 0):
        raise misuse("stop must be None or an integer >= 0, not %r" % (stop,))
    return int(start), -1 if stop is None else int(stop), int(step)


class Frames:
    """The frames of a molecule, one in memory at a time: the models of a
    multi-model PDB/PQR/mmCIF/XYZR file, or with `trajectory` the frames of
    that trajectory (a DCD today; what vb_frame_source reads) over `path`
    as its topology. Iterate it (each frame a Spheres with .index and
    .model); start/stop/step select frames as `--frames A:B:S` does. Every
    frame is checked as `vorball channels` checks it. A context manager;
    close() releases the file.
    """

    def __init__(self, path: PathLike, trajectory: Optional[PathLike] = None, start: int = 0,
                 stop: Optional[int] = None, step: int = 1, format: str = "auto",
                 model: Optional[int] = None, water: bool = False, hydrogens: bool = True,
                 strict_elements: bool = False, radii: Optional[PathLike] = None,
                 zero_radius: str = "auto", verbose: bool = False,
                 assembly: Optional[int] = None) -> None:
        for name, v in (("start", start), ("step", step)):
            if not isinstance(v, numbers.Integral) or v < (1 if name == "step" else 0):
                raise misuse("%s must be an integer >= %d, not %r" % (name, name == "step", v))
        if stop is not None and (not isinstance(stop, numbers.Integral) or stop <= start):
            raise misuse("stop must be an integer > start, not %r" % (stop,))
        self.start, self.stop, self.step = int(start), stop, int(step)
        self.verbose = verbose
        args = _read_args(format, model, assembly, water, hydrogens, strict_elements, radii,
                          zero_radius)
        traj = "" if trajectory is None else os.fspath(trajectory)
        self._capsule, diag = _core.frames_open(os.fspath(path), traj, *args)
        self.warnings = parse(diag)
        emit(self.warnings, verbose)
        self._index = 0

    def __iter__(self) -> Iterator[Spheres]:
        return self

    def __next__(self) -> Spheres:
        while self._capsule is not None:
            if self.stop is not None and self._index >= self.stop:
                break
            got, diag = _core.frames_next(self._capsule)
            w = parse(diag)
            emit(w, self.verbose)
            if got is None:
                self.warnings.extend(w)
                break
            index = self._index
            self._index += 1
            if index >= self.start and (index - self.start) % self.step == 0:
                return Spheres(got[0], w, index=index, model=got[1])
        self.close()
        raise StopIteration

    def close(self) -> None:
        if self._capsule is not None:
            _core.frames_close(self._capsule)
            self._capsule = None

    def __enter__(self) -> Frames:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def frames(path: PathLike, trajectory: Optional[PathLike] = None, **kw: Any) -> Frames:
    """The frames of `path` (see Frames): `for f in vorball.frames(top, dcd): ...`."""
    return Frames(path, trajectory, **kw)


# ---- arrays -----------------------------------------------------------------

def _object_token(v):
    if isinstance(v, str):
        return v
    if isinstance(v, bytes):
        return v.decode("ascii", "replace")
    if isinstance(v, bool) or isinstance(v, np.bool_):
        raise misuse("booleans are not coordinates")
    if isinstance(v, (decimal.Decimal, numbers.Integral)):
        return str(v)
    if isinstance(v, np.floating) and v.dtype.itemsize == 4:
        return str(v)  # numpy's shortest decimal of the float32
    if isinstance(v, (float, np.floating)) and np.dtype(type(v)).itemsize == 8:
        return repr(float(v))
    raise misuse("cannot read a %s as an exact number (use float64, float32, int, str or "
                 "decimal.Decimal)" % type(v).__name__)


def _column(a, what):
    """(kind, data) of one column for _core.spheres_from_columns."""
    kind, size = a.dtype.kind, a.dtype.itemsize
    if kind == "f" and size == 8:
        return ("d", np.ascontiguousarray(a, dtype="=f8"))
    if kind == "f" and size == 4:
        return ("f", np.ascontiguousarray(a, dtype="=f4"))
    if kind in "iu":
        if kind == "u" and size == 8 and a.size and int(a.max()) > 2**63 - 1:
            raise misuse("%s: unsigned values beyond 2**63 are not coordinates" % what)
        return ("q", np.ascontiguousarray(a, dtype="=i8"))
    if kind in "US":
        return ("s", [v.decode("ascii", "replace") if isinstance(v, bytes) else str(v)
                      for v in a.tolist()])
    if kind == "O":
        return ("s", [_object_token(v) for v in a.tolist()])
    if kind == "f":
        raise misuse("%s: float%d is refused: convert to float64 or float32 first (the decimal "
                     "of each value must be decided by you, not here)" % (what, 8 * size))
    raise misuse("%s: dtype %s is not a number vorball reads (float64, float32, integers, str, "
                 "decimal.Decimal)" % (what, a.dtype))


def _unmasked(a, what):
    if isinstance(a, np.ma.MaskedArray):
        if np.ma.is_masked(a):
            raise misuse("%s has masked values" % what)
        return np.asarray(a.data)
    return np.asarray(a)


def spheres(xyz: Union[Spheres, ArrayLike], r: Optional[ArrayLike] = None,
            zero_radius: str = "auto", min_count: int = 1,
            verbose: Optional[bool] = False) -> Spheres:
    """Spheres from arrays, with exact decimals as the certifier needs them.

    xyz is (n, 3) (or (n, 4) x y z r when r is None); r is (n,) or one
    number. Any order and layout (C or Fortran, strided views, byte
    order). Each element becomes the exact decimal the `vorball` command
    would read from a text file holding it as follows:
      float64  Python's repr of it: the shortest decimal that reads back as
               the same double (0.1 is the decimal 0.1, not the binary
               fraction nearest it); the input is then exactly the file
               written with repr(x) of every number;
      float32  the shortest decimal that reads back as the same float32
               (numpy's str of np.float32): coordinates that came from a
               PDB file through float32 (MDAnalysis) are the file's
               decimals again; the pipelines then use the double nearest
               that decimal, as the command reading it does, not the
               float32 value itself;
      integers exactly;
      str, decimal.Decimal (object or str arrays) verbatim: the way to give
               any decimal of up to 18 significant digits exactly.
    float16, longdouble, bool, complex and other dtypes are refused (E7).
    The set is validated as the commands validate a file (E1xx; messages
    name '<arrays> row i'); min_count is the fewest spheres accepted.
    """
    if isinstance(xyz, Spheres):
        return xyz
    a = _unmasked(xyz, "xyz")
    if a.ndim != 2 or a.shape[1] not in (3, 4) or (a.shape[1] == 4 and r is not None):
        raise misuse("xyz must have shape (n, 3)%s, not %s" % (
            "" if r is not None else " or (n, 4) with r None", a.shape))
    if r is None and a.shape[1] == 3:
        raise misuse("radii missing: give r, or xyz of shape (n, 4)")
    n = a.shape[0]
    if r is None:
        rr = a[:, 3]
    else:
        rr = _unmasked(r, "r")
        if rr.ndim == 0:
            rr = np.broadcast_to(rr, (n,))
        if rr.shape != (n,):
            raise misuse("r must have shape (%d,) or be one number, not %s" % (n, rr.shape))
    cols = tuple(_column(c, name) for c, name in ((a[:, 0], "x"), (a[:, 1], "y"), (a[:, 2], "z"),
                                                 (rr, "r")))
    cap, diag = _core.spheres_from_columns(ARRAYS, cols, int(min_count), _zero_radius(zero_radius))
    s = Spheres(cap, diag)
    emit(s.warnings, verbose)
    return s


# The warnings of validation (vb_spheres_validate): a run that validates
# its set again in its own context (vertices, verify) emits them again.
VALIDATION = frozenset({701, 702})


def as_spheres(xyz: SphereInput, r: Optional[ArrayLike] = None, min_count: int = 1,
               zero_radius: str = "auto", exact: bool = True,
               revalidated: bool = True, select: Optional[str] = None
               ) -> Tuple[Spheres, List[Diagnostic]]:
    """A Spheres from what the public calls accept: a Spheres, a path (read),
    or arrays (spheres()). With exact, a set of doubles only (a binary
    trajectory's frame) is rebuilt from its float64 arrays (repr rule).
    Also returns the warnings of making the set here (none for a Spheres
    given as it is), without those of validation when the run repeats
    them (revalidated): what the command prints before its run, once.
    select: keep the spheres this expression selects (Spheres.select)."""
    if select is not None:
        # Selected before a trajectory frame is rebuilt from its doubles,
        # which drops its atom records.
        made = []
        if not isinstance(xyz, Spheres):
            xyz, made = as_spheres(xyz, r, min_count, zero_radius, False, revalidated)
            r = None
        t = xyz.select(select)
        s, more = as_spheres(t, r, min_count, zero_radius, exact, revalidated)
        return s, made + [w for w in t.warnings
                          if not (revalidated and w.number in VALIDATION)] + more
    if isinstance(xyz, Spheres):
        if r is not None:
            raise misuse("r is given with a Spheres that has its radii")
        if not (exact and not xyz.exact):
            return xyz, []
        s = spheres(xyz.xyz, xyz.r, zero_radius, min_count, verbose=None)
        s.index, s.model = xyz.index, xyz.model
    elif isinstance(xyz, (str, os.PathLike)):
        if r is not None:
            raise misuse("r is given with a file that has its radii")
        s = read(xyz, zero_radius=zero_radius, verbose=None)
    else:
        s = spheres(xyz, r, zero_radius, min_count, verbose=None)
    # verbose=None: collected, not emitted; the caller emits them with its own.
    return s, [w for w in s.warnings if not (revalidated and w.number in VALIDATION)]
