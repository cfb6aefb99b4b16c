"""Errors and diagnostics: one exception class carrying the catalogue's
E-number, one warning class carrying the W-number, and the warnings a call
collected instead of printing them. The library hands its diagnostics over
as records (kind, number, file, line, message: its log callback), never as
text to parse back."""
from __future__ import annotations

import re
import sys
import warnings
from typing import Dict, Iterable, List, NamedTuple, Optional, Tuple

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


def _located(file: Optional[str], line: int, message: str) -> str:
    """The message with its location, as the command prints it; spheres
    given as arrays are named by row."""
    if file == ARRAYS and line > 0:
        return rows("%s row %d: %s" % (ARRAYS, line - 1, message))
    if file and line > 0:
        return rows("%s:%d: %s" % (file, line, message))
    return rows("%s: %s" % (file, message) if file else message)


def parse(records: Optional[Iterable[tuple]]) -> List[Diagnostic]:
    """The diagnostics of a call: its records (kind, number, file, line,
    message) from the library's log callback, or Diagnostic tuples."""
    out = []
    for r in records or []:
        if len(r) == 5:
            kind, number, file, line, message = r
            out.append(Diagnostic(kind, number, _located(file, line, message)))
        else:
            out.append(Diagnostic(*r))
    return out


class VorballWarning(UserWarning):
    """A warning of the library, issued through the warnings module when a
    call is not verbose. number: the catalogue's W-number (vorball.catalogue());
    diagnostic: the vorball.Diagnostic. Ignored by default (the package
    appends an 'ignore' filter, which any filter of the caller overrides:
    warnings.simplefilter("always", vorball.VorballWarning) shows them,
    "error" raises them)."""

    number: int
    diagnostic: Diagnostic

    def __init__(self, diagnostic: Diagnostic) -> None:
        super().__init__(str(diagnostic))
        self.number = diagnostic.number
        self.diagnostic = diagnostic


warnings.filterwarnings("ignore", category=VorballWarning, append=True)


def emit(diagnostics: Iterable[Diagnostic], verbose: Optional[bool],
         stacklevel: int = 3) -> None:
    """Prints the diagnostics on sys.stderr when verbose, as the command
    does; otherwise issues each warning as a VorballWarning (stacklevel 3:
    the caller of the package's function that called emit). verbose None:
    neither (a call inside the package, whose caller emits them)."""
    if verbose is None:
        return
    for d in diagnostics:
        if verbose:
            print(d, file=sys.stderr)
        elif d.kind == "W":
            warnings.warn(VorballWarning(d), stacklevel=stacklevel)


class VorballError(Exception):
    """Every failure of vorball: bad input, misuse, a device, memory.

    number       the diagnostic number of the catalogue (101 for E101 ...;
                 the README's table, vorball.catalogue())
    message      the library's message (file:line: ... for input errors;
                 spheres given as arrays are named '<arrays> row i')
    row          for spheres given as arrays, the row the message names
    file, line   where the library's error record points (None, 0: nowhere)
    status       the library's status code (vb.h); also as code
    exit_status  the exit status of the `vorball` command for this error
    diagnostics  the warnings emitted before the failure
    """

    number: int
    message: str
    status: Optional[int]
    exit_status: Optional[int]
    diagnostics: List[Diagnostic]
    row: Optional[int]
    file: Optional[str]
    line: int

    def __init__(self, number: int, message: str, status: Optional[int] = None,
                 exit_status: Optional[int] = None,
                 diagnostics: Optional[Iterable[tuple]] = None,
                 file: Optional[str] = None, line: int = 0, row: Optional[int] = None) -> None:
        # From the library: the error record's message, file and line apart.
        message = _located(file, line, message)
        super().__init__("E%d: %s" % (number, message))
        self.number = number
        self.message = message
        self.status = status
        self.exit_status = exit_status
        self.diagnostics = parse(diagnostics)
        self.file, self.line = file, line
        self.row = row if row is not None else (
            line - 1 if file == ARRAYS and line > 0 else None)

    @property
    def code(self) -> Optional[int]:
        """The library's status code (status)."""
        return self.status

    def __reduce__(self):
        return (type(self), (self.number, self.message, self.status, self.exit_status,
                             [tuple(d) for d in self.diagnostics]),
                {"row": self.row, "file": self.file, "line": self.line})


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
