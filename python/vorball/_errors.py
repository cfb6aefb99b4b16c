"""Errors and diagnostics: one exception class carrying the catalogue's
E-number, and the warnings a call collected instead of printing them."""
from __future__ import annotations

import re
import sys
from typing import Dict, Iterable, List, NamedTuple, Optional, Tuple, Union

from . import _core

# Messages about spheres built from arrays name their source as this, with
# row i as line i + 1 (the XYZR text the arrays became); they are rewritten
# to name the row.
ARRAYS = "<arrays>"
_ROW = re.compile(re.escape(ARRAYS) + r":(\d+): ")


def rows(text: str) -> str:
    """Rewrites '<arrays>:N: ' (line N of the arrays' text) as '<arrays> row N-1: '."""
    return _ROW.sub(lambda m: "%s row %d: " % (ARRAYS, int(m.group(1)) - 1), text)


class Diagnostic(NamedTuple):
    """A warning (or info line) the library emitted during a call."""
    kind: str      # "W" for a warning, "I" for an informational line
    number: int    # the catalogue number (vorball.catalogue()), 0 for info lines
    message: str   # the text after "vorball: W<n>: "

    def __str__(self) -> str:
        if self.kind == "W":
            return "vorball: W%d: %s" % (self.number, self.message)
        return "vorball: " + self.message


_LINE = re.compile(r"^vorball: W(\d+): (.*)$")


def parse(text: Optional[str]) -> List[Diagnostic]:
    """The diagnostics of a call's captured text, one per line."""
    out = []
    for line in rows(text or "").splitlines():
        m = _LINE.match(line)
        if m:
            out.append(Diagnostic("W", int(m.group(1)), m.group(2)))
        elif line.startswith("vorball: "):
            out.append(Diagnostic("I", 0, line[len("vorball: "):]))
        elif line and out:  # a message over several lines
            out[-1] = out[-1]._replace(message=out[-1].message + "\n" + line)
    return out


def emit(diagnostics: Iterable[Diagnostic], verbose: bool) -> None:
    """Prints the diagnostics on sys.stderr when verbose, as the command does."""
    if verbose:
        for d in diagnostics:
            print(d, file=sys.stderr)


class VorballError(Exception):
    """Every failure of vorball: bad input, misuse, a device, memory.

    number       the diagnostic number of the catalogue (101 for E101 ...;
                 the README's table, vorball.catalogue())
    message      the library's message (file:line: ... for input errors;
                 spheres given as arrays are named '<arrays> row i')
    row          for spheres given as arrays, the row the message names
    status       the library's status code (vb.h)
    exit_status  the exit status of the `vorball` command for this error
    diagnostics  the warnings emitted before the failure
    """

    number: int
    message: str
    status: Optional[int]
    exit_status: Optional[int]
    diagnostics: List[Diagnostic]
    row: Optional[int]

    def __init__(self, number: int, message: str, status: Optional[int] = None,
                 exit_status: Optional[int] = None,
                 diagnostics: Union[str, Iterable[Diagnostic], None] = None) -> None:
        message = rows(message)
        super().__init__("E%d: %s" % (number, message))
        self.number = number
        self.message = message
        self.status = status
        self.exit_status = exit_status
        self.diagnostics = (parse(diagnostics) if isinstance(diagnostics, str)
                            else [Diagnostic(*d) for d in diagnostics or []])
        m = re.match(re.escape(ARRAYS) + r" row (\d+)[:,] ", message)
        self.row = int(m.group(1)) if m else None

    def __reduce__(self):
        return (type(self), (self.number, self.message, self.status, self.exit_status,
                             [tuple(d) for d in self.diagnostics]))


_core._set_error_class(VorballError)


def error(number: int, message: str) -> VorballError:
    """A VorballError of catalogue number `number` raised by the package
    itself, with the status code and exit status the library gives it."""
    status = number if number < 100 else 1 | ((number - 100) << 8)  # VB_EINPUT | detail << 8
    entry = catalogue().get(("E", number))
    return VorballError(number, message, status, entry.exit_status if entry else None)


def misuse(message: str) -> VorballError:
    """A VorballError for a wrong argument (E7: misuse of an option or of the API)."""
    return error(7, message)


class CatalogueEntry(NamedTuple):
    kind: str        # "E" or "W"
    number: int
    name: Optional[str]  # the C name after VB_E_ / VB_W_ (None when retired)
    exit_status: Optional[int]  # the command's exit status (0 for warnings; None when retired)
    meaning: str


def catalogue() -> Dict[Tuple[str, int], CatalogueEntry]:
    """Every diagnostic number vorball uses ({(kind, number): CatalogueEntry}),
    from the library's catalogue (core/vb_diag.h), retired numbers included."""
    return {(k, n): CatalogueEntry(k, n, name, ex, meaning)
            for k, n, name, ex, meaning in _core.diagnostics()}
