"""vorball: the Voronoi diagram of spheres, certified exactly, and the
channels of molecules, as NumPy arrays.

    import vorball
    s = vorball.read("1crn.pdb")                  # or arrays: vorball.vertices(xyz, r)
    ids, xyz, t = vorball.vertices(s)              # every vertex proven exactly
    ch = vorball.channels(s, grid=128)             # ch.table, ch.profile(0)
    c = vorball.cells(s, contacts=True)            # c.volume, c.sas_lo, c.area

The calls run the library of the `vorball` command (libvorball) in the
process: the same readers, the same pipelines, the same bytes
(Result.to_text() is what `vorball vertices` writes). Errors raise
VorballError with the catalogue's E-number; warnings are collected on the
results (.warnings), printed with verbose=True and otherwise issued as
VorballWarning (ignored unless a warnings filter shows them).
"""
from ._errors import CatalogueEntry, Diagnostic, VorballError, VorballWarning, catalogue
from ._spheres import Frames, Spheres, frames, read, spheres
from ._vertices import (Arcs, Certificate, Engine, Reference, Result, Topology, devices,
                        reference, vertex_text, vertices)
from ._verify import DUPLICATE, MISSING, NOT_VERTEX, WRONG_COORDS, Report, verify
from ._channels import Channels, channel_flags, channel_options, channels
from ._cells import Cells, cells, cells_frames
from ._jfa import Jfa, JfaRun, jfa
from ._periodic import BEYOND_REACH, NOT_CANONICAL, PeriodicReport, PeriodicResult, periodic_frames

__all__ = ["Arcs", "BEYOND_REACH", "catalogue", "CatalogueEntry", "Cells", "cells", "cells_frames",
           "Certificate", "channel_flags", "channel_options", "Channels", "channels", "devices",
           "Diagnostic", "DUPLICATE", "Engine", "Frames", "frames", "Jfa", "jfa", "JfaRun",
           "MISSING", "NOT_CANONICAL", "NOT_VERTEX", "periodic_frames", "PeriodicReport",
           "PeriodicResult", "read", "Reference", "reference", "Report", "Result", "Spheres",
           "spheres", "Topology", "verify", "vertex_text", "vertices", "VorballError",
           "VorballWarning", "WRONG_COORDS"]

try:
    from importlib.metadata import PackageNotFoundError, version as _version
    __version__ = _version("vorball")
except (ImportError, PackageNotFoundError):  # an in-place build
    __version__ = "unknown"
