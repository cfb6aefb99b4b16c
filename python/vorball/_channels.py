"""Channels and cavities of a molecule (the discrete Voronoi pipeline of
the Facet-JFA paper, Sec. 4, with components, centrelines, bottlenecks and
lining atoms), one frame at a time."""
from __future__ import annotations

import csv
import io
import json as _json
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._errors import Diagnostic, emit, misuse, parse
from ._spheres import SphereInput, Spheres, as_spheres

# The columns of the table that the bound structures give at full
# precision; every other column of the library's CSV is added as the
# library writes it (so new columns appear without a change here).
_TABLE = [("frame", "i8"), ("model", "i8"), ("channel", "i8"), ("kind", "U7"), ("through", "?"),
          ("length_A", "f8"), ("bottleneck_A", "f8"), ("bottleneck_x", "f8"),
          ("bottleneck_y", "f8"), ("bottleneck_z", "f8"), ("start_x", "f8"), ("start_y", "f8"),
          ("start_z", "f8"), ("end_x", "f8"), ("end_y", "f8"), ("end_z", "f8"), ("voxels", "i8"),
          ("volume_A3", "f8"), ("mouths", "i8"), ("points", "i8"), ("lining_atoms", "i8")]
_KNOWN = {name for name, _ in _TABLE}
_KIND = {0: "channel", 1: "cavity", 2: "pore"}  # enum vbc_kind, as the CSV writes it
_POINT = np.dtype([("s", "f8"), ("x", "f8"), ("y", "f8"), ("z", "f8"), ("r", "f8"), ("atom", "i4")])


def _typed(values):
    """A column of CSV strings as int64, float64 or str, by content."""
    for conv, dt in ((int, "i8"), (float, "f8")):
        try:
            return np.array([conv(v) for v in values], dtype=dt)
        except ValueError:
            pass
    return np.array(values, dtype=str)


class Channels:
    """The channels (and, when asked, cavities) of one frame.

    table        structured array, one row per channel, longest first, with
                 the columns of the command's CSV (frame, model, channel,
                 kind, through, length_A, bottleneck_A, bottleneck_x/y/z,
                 start_*, end_*, voxels, volume_A3, mouths, points,
                 lining_atoms, lining_residues, and any the library adds);
                 numbers at full precision
    centrelines  list of structured arrays, one per row: s (arc length
                 from the first point, Å), x, y, z, r (clearance: distance
                 to the nearest atom surface, Å), atom (the atom bounding r)
    lining       list of int arrays: the atoms lining each channel
    grid         dict: nx, ny, nz, h (voxel edge, Å), origin
    components, pruned, channel_voxels   counts before pruning
    csv, json    what `vorball channels` writes for this frame (the CSV
                 with its header; the JSON document)
    profile_csv  what its --profile writes for this frame: per point of
                 every row the axial and arc coordinates, position, radius,
                 nearest and bounding atoms
    pore         the frame's pore, or None: axis (unit vector), start (Å),
                 step (Å between planes), F (HOLE's geometric factor, 1/Å),
                 g_macro_pS (its conductance estimate, 1 M KCl), open_lo /
                 open_hi (the openings: each end left the molecule),
                 buried (Å walled along the axis), why (how the axis was
                 found)
    flags        with flags=True: the (nz, ny, nx) uint8 volume of VBC_F_*
                 bits (vorball.channel_flags())
    ms           per-stage milliseconds (prepare, upload, jfa, masks, analysis,
                 cells, refine, sweep, verdict, lining, pore, total: the keys
                 of the command's JSON "ms" but read)
    device, warnings, spheres
    """

    table: np.ndarray
    centrelines: List[np.ndarray]
    lining: List[np.ndarray]
    grid: Dict[str, Any]
    components: int
    pruned: int
    channel_voxels: int
    csv: str
    json: str
    profile_csv: str
    pore: Optional[Dict[str, Any]]
    flags: Optional[np.ndarray]
    device: str
    ms: Dict[str, float]
    warnings: List[Diagnostic]
    spheres: Spheres
    frame: int
    model: int

    def __init__(self, d: Dict[str, Any], warnings: List[Diagnostic], spheres: Spheres,
                 frame: int, model: int) -> None:
        self.spheres, self.warnings = spheres, warnings
        self.frame, self.model = frame, model
        self.csv, self.json = d["csv"], d["json"]
        self.profile_csv, self.pore = d["profile"], d["pore"]
        self.device, self.ms = d["device"], dict(d["ms"])
        self.components, self.pruned = d["components"], d["pruned"]
        self.channel_voxels = d["channel_voxels"]
        g = d["grid"]
        self.grid = {"nx": g["nx"], "ny": g["ny"], "nz": g["nz"], "h": g["h"],
                     "origin": tuple(g["origin"])}
        pts = np.frombuffer(d["points"], dtype=np.float64).reshape(-1, 4)
        atoms = np.frombuffer(d["point_atoms"], dtype=np.int32)
        lining = np.frombuffer(d["lining"], dtype=np.int32)
        rows = list(csv.DictReader(io.StringIO(self.csv)))
        header = next(csv.reader(io.StringIO(self.csv)), [])
        chans = d["channels"]
        self.centrelines, self.lining = [], []
        table = []
        for t, (kind, through, voxels, mouths, length, bottleneck, at, p0, npts, l0, nl) in \
                enumerate(chans):
            c = np.zeros(npts, dtype=_POINT)
            p = pts[p0:p0 + npts]
            c["x"], c["y"], c["z"], c["r"] = p[:, 0], p[:, 1], p[:, 2], p[:, 3]
            c["atom"] = atoms[p0:p0 + npts]
            if npts > 1:
                c["s"][1:] = np.cumsum(np.linalg.norm(np.diff(p[:, :3], axis=0), axis=1))
            c.setflags(write=False)
            self.centrelines.append(c)
            self.lining.append(lining[l0:l0 + nl].astype(np.int64))
            b, first, last = p[at], p[0], p[-1]
            h = g["h"]
            table.append((frame, model, t + 1, _KIND[kind], bool(through),
                          length, bottleneck, b[0], b[1], b[2], first[0], first[1], first[2],
                          last[0], last[1], last[2], voxels, voxels * (h * h * h), mouths, npts, nl))
        extra = [name for name in header if name not in _KNOWN]
        cols = {name: _typed([row[name] for row in rows]) for name in extra}
        dtype = _TABLE + [(name, cols[name].dtype.str if cols[name].size else "U1")
                          for name in extra]
        out = np.zeros(len(table), dtype=dtype)
        for k, row in enumerate(table):
            for (name, _), v in zip(_TABLE, row):
                out[name][k] = v
        for name in extra:
            if len(table):
                out[name] = cols[name]
        out.setflags(write=False)
        self.table = out
        if "flags" in d:
            self.flags = np.frombuffer(d["flags"], dtype=np.uint8).reshape(g["nz"], g["ny"], g["nx"])
        else:
            self.flags = None

    def __len__(self) -> int:
        return len(self.table)

    def __repr__(self) -> str:
        return "<vorball.Channels frame %d: %d channel(s) on %s>" % (self.frame, len(self),
                                                                       self.device)

    def profile(self, k: int = 0) -> Tuple[np.ndarray, np.ndarray]:
        """The pore profile of row k: (s, r), the clearance radius r along
        the centreline at arc length s (Å) from its first point."""
        c = self.centrelines[k]
        return c["s"], c["r"]

    def to_json(self) -> Any:
        """The JSON document as Python objects."""
        return _json.loads(self.json)


def channel_flags() -> Dict[str, int]:
    """The bits of Channels.flags: {'atomic': 1, 'molecular': 2, ...}."""
    return _core.channel_flag_bits()


# The analysis's options, declared once in the library
# (core/discrete/channel_options.c): {keyword: (type, min, max, default,
# choices, help)}. The library checks every value and fills the defaults.
OPTIONS: Dict[str, Tuple[str, float, float, Optional[str], Optional[str], str]] = \
    _core.channel_options()


def _default(name: str) -> str:
    return OPTIONS[name][3]


def _options_doc() -> str:
    lines = []
    for name, (typ, lo, hi, default, choices, text) in sorted(OPTIONS.items()):
        rng = " (%g..%g)" % (lo, hi) if typ in ("real", "count", "pow2") else ""
        dflt = "; default %s" % default if default is not None else ""
        lines.append("    %s: %s%s%s" % (name, text, rng, dflt))
    return "\n".join(lines)


def _keywords(grid, probe, options):
    """The keyword dict for the library (None: its default)."""
    kw = dict(options)
    for name in kw:
        if name not in OPTIONS or name in ("device", "jfa"):
            raise misuse("unknown channels option %r (vorball.channel_options: %s)"
                         % (name, ", ".join(sorted(OPTIONS))))
    kw["grid"], kw["probe"] = grid, probe
    return kw


def channel_options() -> Dict[str, Tuple[str, float, float, Optional[str], Optional[str], str]]:
    """The options of vorball.channels as the library declares them:
    {keyword: (type, min, max, default, choices, help)}, the same table that
    `vorball channels` parses and prints with --help."""
    return dict(OPTIONS)


def run_channels(pipe: Any, first: bool, xyz: SphereInput, r: Optional[ArrayLike],
                 grid: Optional[int] = None, probe: Optional[float] = None, *, carry: Any = None,
                 flags: bool = False, zero_radius: str = "auto", verbose: bool = False,
                 progress: Optional[Callable[[str, int, int], Any]] = None,
                 select: Optional[str] = None, **options: Any) -> Channels:
    """One frame through an opened channel pipe (vorball.channels, Engine.channels)."""
    kw = _keywords(grid, probe, options)
    s, made = as_spheres(xyz, r, min_count=1, zero_radius=zero_radius, exact=False,
                         revalidated=False, select=select)
    d, diag = _core.channels_run(pipe, s._capsule, kw, carry, int(s.model), int(s.index),
                                 bool(flags), bool(first), progress)
    w = made + parse(diag)
    emit(w, verbose)
    return Channels(d, w, s, s.index, s.model)


def channels(xyz: SphereInput, r: Optional[ArrayLike] = None, grid: Optional[int] = None,
             probe: Optional[float] = None, *, device: Optional[str] = None,
             jfa: Optional[str] = None, flags: bool = False, zero_radius: str = "auto",
             verbose: bool = False, progress: Optional[Callable[[str, int, int], Any]] = None,
             select: Optional[str] = None, **options: Any) -> Channels:
    """Channels, cavities and the pore of one set of spheres, as `vorball
    channels` (the same call: the same table, pore included).

    xyz, r: arrays, a Spheres (a frame of vorball.frames: its index and
    model go into the table), or a file path (its first model). grid,
    probe, device, jfa and the options below are the command's, by the same
    names (--min-length is min_length, --no-pore no_pore=True, --axis
    axis=(x, y, z), --ignore ignore="DUM,POPC"); None or absent: the
    library's default. device: auto, gpu, cpu or ref (W804 when it falls
    back). flags=True keeps the mask volume. For the frames of a
    trajectory, open the device once: `with vorball.Engine() as e: for f in
    vorball.frames(...): e.channels(f)` (later frames sweep the first
    frame's pore axis, as the command does). progress: a callable,
    progress('frames', 1, 1) once the frame is analysed (the library's
    progress callback, as for vorball.vertices). select: only the atoms
    this expression selects (`--select`; E118 when bad or empty). Returns
    Channels; raises VorballError.

    Options (vorball.channel_options()):
%s
    """
    device = _default("device") if device is None else device
    jfa = _default("jfa") if jfa is None else jfa
    if not isinstance(device, str) or not isinstance(jfa, str):
        raise misuse("device and jfa are names")
    kw = _keywords(grid, probe, options)
    pipe, diag = _core.channels_open(device, jfa)
    w = parse(diag)
    emit(w, verbose)
    c = run_channels(pipe, True, xyz, r, flags=flags, zero_radius=zero_radius, verbose=verbose,
                     progress=progress, select=select, **kw)
    c.warnings[:0] = w
    return c


channels.__doc__ = (channels.__doc__ or "") % _options_doc()


class ChannelFrames:
    """Every frame of a source through the library's run over frames
    (vorball.channels_frames): what `vorball channels` writes for a
    trajectory.

    text          the table of every frame as the command writes it: CSV
                  (with its header) or, with json=True, the JSON document
                  (without the command line's provenance)
    stats_csv     the per-frame statistics rows (stats=True), else None
    centrelines_pdb   the centrelines of every frame, one MODEL each, with
                  the first frame's CONECT records (centerlines=), else None
    profile_csv   the radius profile of every row of every frame
                  (profile=True), else None
    selected      frames selected; analysed: frames run here
    series        structured array (frame, rmin, s): the pore's smallest
                  radius per frame and where along the axis
    stages        with png=True: the first frame's eight-panel picture as a
                  (h, w, 3) uint8 array (what --png encodes), else None
    ms_per_run, masks_ms_per_run   mean milliseconds of a frame's run and
                  of its device stages (the command's closing line)
    device, warnings
    """

    def __init__(self, d: Dict[str, Any], warnings: List[Diagnostic]) -> None:
        self.text = d["table"]
        self.stats_csv, self.centrelines_pdb = d["stats"], d["centrelines"]
        self.profile_csv = d["profile"]
        self.selected, self.analysed, self.device = d["selected"], d["analysed"], d["device"]
        runs = max(1, d["analysed"] * d["repeat"])
        self.ms_per_run, self.masks_ms_per_run = d["ms_total"] / runs, d["ms_masks"] / runs
        self.series = np.array(d["series"], dtype=[("frame", "i8"), ("rmin", "f8"), ("s", "f8")])
        if d["stages"] is None:
            self.stages = None
        else:
            w, h, rgb = d["stages"]
            self.stages = np.frombuffer(rgb, dtype=np.uint8).reshape(h, w, 3)
        self.warnings = warnings

    def __repr__(self) -> str:
        return "<vorball.ChannelFrames: %d frame(s) on %s>" % (self.selected, self.device)


# The command's options that are files or the run's own (no Python keyword
# in the library's table): Python name -> its spelling.
_FILES = {"pymol": "--pymol", "volume": "--volume", "volume_mask": "--volume-mask",
          "html": "--html", "occupancy": "--occupancy", "png_normal": "--png-normal",
          "repeat": "--repeat"}


def channels_frames(path: Any, trajectory: Any = None, *, start: int = 0,
                    stop: Optional[int] = None, step: int = 1, grid: Optional[int] = None,
                    probe: Optional[float] = None, device: Optional[str] = None,
                    jfa: Optional[str] = None, json: bool = False, stats: bool = False,
                    centerlines: Any = None, profile: bool = False, fixed_grid: bool = False,
                    png: bool = False, read: Optional[Dict[str, Any]] = None,
                    verbose: bool = False,
                    progress: Optional[Callable[[str, int, int], Any]] = None,
                    **options: Any) -> ChannelFrames:
    """Channels of every frame of `path` (with `trajectory`: of that DCD, XTC
    or TRR over `path` as its topology), as `vorball channels` runs them:
    the library's run over frames (frames in flight, the pore axis of the
    first frame swept on the later ones), the same table, statistics,
    centrelines and profile (as text) and the same files: pymol=PATH
    (needs centerlines=PATH), volume=PATH ('%d' for one per frame),
    volume_mask=, html=PATH, occupancy=PATH (needs fixed_grid=True),
    repeat=N. start/stop/step select frames as --frames A:B:S; read= the
    keywords of vorball.frames (model, water, hydrogens, radii, ...);
    grid, probe, device, jfa and **options as vorball.channels. The
    centrelines file is written when the run succeeded. Returns
    ChannelFrames; raises VorballError.
    """
    import os
    from ._spheres import Frames
    device = _default("device") if device is None else device
    jfa = _default("jfa") if jfa is None else jfa
    if not isinstance(device, str) or not isinstance(jfa, str):
        raise misuse("device and jfa are names")
    files = {name: options.pop(name) for name in list(options) if name in _FILES}
    kw = _keywords(grid, probe, options)
    outs: Dict[str, Any] = {}
    for name, v in files.items():
        if v is not None:
            outs[_FILES[name]] = os.fspath(v) if name != "repeat" else str(v)
    for flag, on in (("--json", json), ("--stats", stats), ("--fixed-grid", fixed_grid)):
        if on:
            outs[flag] = True
    if centerlines is not None:
        outs["--centerlines"] = os.fspath(centerlines)
    if png:
        outs["--png"] = "stages.png"  # the picture comes back as pixels
    if not options.get("no_pore"):
        outs["--plot"] = "series.png"  # the pore series comes back (the plot is the command's)
    with Frames(path, trajectory, verbose=verbose, **(read or {})) as src:
        outs["--frames"] = "%d:%s:%d" % (start, "" if stop is None else stop, step)
        if trajectory is not None:
            outs["--traj"] = os.fspath(trajectory)
        d, diag = _core.channels_frames(src._capsule, os.fspath(path), kw, outs, device, jfa,
                                        bool(stats), centerlines is not None, bool(profile),
                                        progress)
        w = src.warnings + parse(diag)
    emit(w[len(src.warnings):], verbose)
    if centerlines is not None:
        with open(centerlines, "w", encoding="utf-8") as f:
            f.write(d["centrelines"])
    return ChannelFrames(d, w)
