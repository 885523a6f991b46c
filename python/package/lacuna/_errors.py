"""lacuna's errors as Python exceptions.

Every error of the library has a stable code (``E0103``, …; the table is ``docs/ERRORS.md``), a
one-line message and, when it points into a source text, a span. The native module raises them
through :func:`from_native`, which picks the subclass from the code.
"""

from __future__ import annotations

from typing import NamedTuple, Optional


class Span(NamedTuple):
    """A place in a source text: 1-based line and column (in characters), and a length."""

    line: int
    col: int
    len: int


class LacunaError(Exception):
    """An error of lacuna: bad input, an exceeded limit, a failed write, …

    Attributes:
        code: the stable code, e.g. ``"E0103"``.
        message: the one-line message.
        span: where in the source text (:class:`Span`), or ``None``.
        rendered: the full diagnostic as the command line prints it (the source line and a caret).
    """

    def __init__(self, code: str, message: str, span: Optional[Span] = None, rendered: str = ""):
        super().__init__(f"[{code}] {message}")
        self.code = code
        self.message = message
        self.span = span
        self.rendered = rendered or f"error[{code}]: {message}\n"


class InputError(LacunaError, ValueError):
    """A text that cannot be read: face notation, an assembly, AutoFrac2D, automaton, template or
    volume or rule file, a parameter value, a goal (codes E01xx, E02xx, E03xx, E07xx, E09xx,
    E1007, E102x, E1030, E12xx, E13xx)."""


class FileError(LacunaError, OSError):
    """A file that cannot be read (E0601), is not UTF-8 text (E0602) or cannot be written (E1005)."""


class LimitError(LacunaError):
    """A configurable limit exceeded before the work started (E0501, E1003): never a verdict; raise
    the limit (``limits={"max_level": …}``) knowingly."""


class RunawayError(LacunaError):
    """The work needs a closed closure and the recursion did not close (E0502); ``closure()`` shows
    the witness chain."""


class UsageError(LacunaError, ValueError):
    """Arguments that do not fit the input or each other (E0504), a value outside the range a
    keyword accepts (E0503), or a PNG pattern of :func:`~lacuna.morph` without ``{}`` (E1401)."""


class AnalysisError(LacunaError):
    """An exact analysis that could not finish (E0801), or a face whose rule chooses no spoke
    (E0401)."""


class GeometryError(LacunaError):
    """Instantiation, measures and solids: no solution to draw, a parameter that is not free, goals
    that cannot be met, a solid that does not realise the exact topology (E10xx)."""


def error_class(code: str) -> type:
    """The exception class of an error code."""
    if code in ("E0501", "E1003"):
        return LimitError
    if code == "E0502":
        return RunawayError
    if code in ("E0503", "E0504", "E1401"):
        return UsageError
    if code in ("E0601", "E0602", "E1005"):
        return FileError
    if code in ("E0401", "E0801"):
        return AnalysisError
    if code in ("E1007", "E1030") or code.startswith("E102") or code[:3] in ("E01", "E02", "E03", "E07", "E09", "E12", "E13"):
        return InputError
    if code.startswith("E1"):
        return GeometryError
    return LacunaError


def from_native(code: str, message: str, span, rendered: str) -> LacunaError:
    """The exception for an error of the native module (called from Rust)."""
    s = Span(*span) if span is not None else None
    return error_class(code)(code, message, s, rendered)
