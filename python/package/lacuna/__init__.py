"""lacuna from Python: the exact verifier and solver of BC-IFS fractal topology.

>>> import lacuna
>>> f0 = lacuna.Face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1")
>>> len(f0.closure().types)
1
>>> f0.counts(2)[2].faces
36
>>> f0.ratio().value
Fraction(1, 3)

Exact results are Python objects: integers as ``int`` (of any size), rationals as
``fractions.Fraction``, algebraic numbers as exact strings with a SymPy conversion
(:meth:`Ratio.sympy`). Floats appear only in geometry (polygons, measures). Errors are
:class:`LacunaError` exceptions (or a subclass) carrying ``code``, ``message`` and ``span``.

Inputs are what the command line reads: face notation (:class:`Face`), assembly and AutoFrac2D
files (:class:`Assembly`), automaton files (:class:`Automaton`), volume notation and volume files
(:class:`Volume`, one volume or several glued face to face), and the names of the library
(:func:`library`, :func:`load`).

Every input writes the HTML report of ``lacuna report`` (``report(path)``); :func:`classify`
groups inputs into topological classes and :func:`morph` builds and checks the frames between two
parameter choices (``lacuna classify``, ``lacuna morph``).
"""

from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _lacuna
from ._errors import (
    AnalysisError,
    FileError,
    GeometryError,
    InputError,
    LacunaError,
    LimitError,
    RunawayError,
    Span,
    UsageError,
)

__version__ = _lacuna.__version__

__all__ = [
    "Face",
    "Assembly",
    "Automaton",
    "Rule",
    "Counts",
    "Volume",
    "Structure",
    "Closure",
    "FaceType",
    "LevelCount",
    "Ratio",
    "LimitPoint",
    "Solution",
    "FieldVerdict",
    "Certificate",
    "CheckReport",
    "Rendering",
    "Shapes",
    "VolumeClosure",
    "VolumeType",
    "VolumeLevelCount",
    "VolumeCounts",
    "SolidLevel",
    "SolidTopology",
    "VolumeRendering",
    "Record",
    "Exploration",
    "explore",
    "classify",
    "Classification",
    "Comparison",
    "morph",
    "Morph",
    "MorphFrame",
    "census",
    "check_mesh",
    "operators",
    "design",
    "Design",
    "library",
    "load",
    "check",
    "LacunaError",
    "InputError",
    "FileError",
    "LimitError",
    "RunawayError",
    "UsageError",
    "AnalysisError",
    "GeometryError",
    "Span",
]

PathLike = Union[str, "os.PathLike[str]"]
Limits = Optional[Mapping[str, int]]
Params = Optional[Mapping[str, Union[str, int, Fraction]]]
#: The corners of a single face: ``"X Y, X Y, …"`` as ``--corners`` reads it, or (x, y) pairs.
Corners = Union[str, Sequence[Sequence[Union[str, int, Fraction]]], None]
#: One goal (``"nonnegative"``, ``"nonnegative=M"``, ``"min-lacuna=S"``) or several.
Goals = Union[str, Sequence[str], None]


# ---------------------------------------------------------------------------------------------
# Exact values


def _q(text: Optional[str]) -> Optional[Fraction]:
    """An exact rational written by lacuna (``5/2``, ``-1``) as a Fraction."""
    return None if text is None else Fraction(text)


def _matrix(text: str) -> List[List[Fraction]]:
    """A matrix written ``[a b; c d]`` as rows of Fractions."""
    body = text.strip()
    if body.startswith("[") and body.endswith("]"):
        body = body[1:-1]
    if not body.strip():
        return []
    return [[Fraction(x) for x in row.split()] for row in body.split(";")]


def _params(params: Params) -> List[Tuple[str, str]]:
    """Parameter values as exact text for the native module."""
    if not params:
        return []
    out = []
    for k, v in params.items():
        if isinstance(v, float):
            raise UsageError(
                "E0504",
                f"parameter {k} = {v!r}: give an exact value (a Fraction, an int or a string such as '1/7')",
            )
        out.append((str(k), str(v)))
    return out


def _face_choice(corners: Corners, template: Optional[PathLike], goal: Goals) -> Dict[str, Any]:
    """The parameter choice of faces beyond ``params`` as the native module's keywords: the
    corners of a single face as the command line's ``--corners`` text (``"0 0, 1 0, 0 1"``, or
    (x, y) pairs of exact values), a template file (``--template``) and the goals (``--goal``,
    one or several)."""
    if corners is not None and not isinstance(corners, str):
        pairs = []
        for pt in corners:
            if any(isinstance(c, float) for c in pt):
                raise UsageError("E0504", f"corner {tuple(pt)!r}: give exact values (a Fraction, an int or a string such as '1/7')")
            pairs.append(" ".join(str(c) for c in pt))
        corners = ", ".join(pairs)
    goals = [] if goal is None else [goal] if isinstance(goal, str) else [str(g) for g in goal]
    return {"corners": corners, "template": _path(template), "goals": goals}


def _natural(name: str, value) -> int:
    """A level, a number of digits or a size as the native module takes it: an int ≥ 0, else a
    :class:`UsageError` (E0503) — never Python's ``OverflowError`` from the conversion."""
    if isinstance(value, bool) or not isinstance(value, int):
        try:
            value = int(value)
        except (TypeError, ValueError):
            raise UsageError("E0503", f"{name} = {value!r}: give a whole number ≥ 0") from None
    if value < 0 or value >= 2**63:
        raise UsageError("E0503", f"{name} = {value}: give a whole number from 0 to 2^63 − 1")
    return value


def _limits(limits: Limits) -> Optional[Dict[str, int]]:
    return None if limits is None else {str(k): int(v) for k, v in limits.items()}


class Record:
    """A report of lacuna as attributes (nested objects are Records too, lists stay lists).

    ``record.data`` is the plain JSON-like data, the same as the command line's ``--json`` output.
    """

    def __init__(self, data: Mapping[str, Any]):
        object.__setattr__(self, "data", dict(data))

    def __getattr__(self, name: str) -> Any:
        try:
            return _wrap(self.data[name])
        except KeyError:
            raise AttributeError(name) from None

    def __getitem__(self, name: str) -> Any:
        return _wrap(self.data[name])

    def __contains__(self, name: str) -> bool:
        return name in self.data

    def keys(self):
        """The field names."""
        return self.data.keys()

    def __dir__(self):
        return list(self.data.keys()) + ["data", "keys"]

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={_short(v)}" for k, v in self.data.items())
        return f"Record({inner})"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Record) and other.data == self.data

    def _repr_html_(self) -> str:
        """A notebook shows a report (a verdict of ``verify``, a measure, …) as a table of its
        fields, long values shortened."""
        return _html_table(["field", "value"], [[k, _short(v)] for k, v in self.data.items()])


def _png_bytes(render, level: int, size: int) -> bytes:
    """The PNG bytes of ``render(level, png=PATH, size=size)`` through a temporary file."""
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "picture.png"
        render(level, png=out, size=size)
        return out.read_bytes()


def _decode_png(data: bytes):
    """The pixels of a PNG lacuna wrote as an (h, w, 4) uint8 NumPy array (RGBA)."""
    import numpy as np

    h, w, rgba = _lacuna.decode_png(data)
    return np.frombuffer(bytes(rgba), dtype=np.uint8).reshape(h, w, 4)


class _Picture:
    """A rendering that can draw itself: ``_repr_png_`` for notebooks (``display`` pixels wide)
    and ``image``, the picture as an RGBA NumPy array."""

    #: The width in pixels of the picture a notebook shows.
    display = 480

    def png(self, size: int = 1024) -> bytes:
        """The PNG of this level, ``size`` pixels wide, as ``render(..., png=...)`` writes it."""
        return _png_bytes(self._render, self._level, _natural("size", size))

    def _repr_png_(self) -> bytes:
        return self.png(self.display)

    @property
    def image(self):
        """The picture (1024 pixels wide) as an (h, w, 4) uint8 RGBA NumPy array."""
        return _decode_png(self.png(1024))


def _html_table(head: List[str], rows: List[List[Any]]) -> str:
    """A small HTML table (cells escaped)."""
    import html

    th = "".join(f"<th>{html.escape(str(h))}</th>" for h in head)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>" for row in rows
    )
    return f"<table><tr>{th}</tr>{body}</table>"


def _short(v: Any) -> str:
    r = repr(v)
    return r if len(r) < 60 else r[:57] + "..."


def _wrap(v: Any) -> Any:
    if isinstance(v, dict):
        return Record(v)
    if isinstance(v, list):
        return [_wrap(x) for x in v]
    return v


# ---------------------------------------------------------------------------------------------
# Results


@dataclass(frozen=True)
class FaceType:
    """One face type of a closure.

    Attributes:
        id: ``"T0"``, ``"T1"``, … (start types first).
        face: its canonical notation.
        children: the type of each sub-face, in order.
        subfaces: the notation of each sub-face.
        contribution: the lacunas it contributes per subdivision (halves: a lacuna on a shared
            edge counts half on each side).
        complex: the exact level-1 complex (vertices, edges, faces, holes, valences), when given.
    """

    id: str
    face: str
    children: Tuple[str, ...]
    subfaces: Tuple[str, ...]
    contribution: Fraction
    complex: Optional[Record] = None


@dataclass(frozen=True)
class Closure:
    """The closure of the start faces under subdivision.

    Attributes:
        closed: True when the recursion closes; False for a runaway (see ``runaway``).
        types: the face types.
        start: the type of each start face.
        classes: strongly connected classes with their periods (when closed).
        bound: the stated bound that proves the closure finite (a Record), when closed.
        runaway: the witness chain and the limit hit, when it did not close.
        data: the whole report as ``lacuna closure --json`` prints it.
    """

    closed: bool
    types: Tuple[FaceType, ...]
    start: Tuple[str, ...]
    classes: Optional[Record]
    bound: Optional[Record]
    runaway: Optional[Record]
    data: Dict[str, Any] = field(repr=False, compare=False)

    @property
    def edges(self) -> List[Tuple[str, str, Dict[str, int]]]:
        """The type graph as a networkx-compatible edge list: ``(T_i, T_j, {"count": k})`` when
        k sub-faces of T_i are of type T_j (``networkx.DiGraph(closure.edges)``)."""
        out = []
        for t in self.types:
            seen: Dict[str, int] = {}
            for c in t.children:
                seen[c] = seen.get(c, 0) + 1
            out.extend((t.id, c, {"count": k}) for c, k in seen.items())
        return out

    def graph(self):
        """The type graph as a ``networkx.DiGraph`` (nodes carry ``face`` and ``contribution``;
        edges ``count``). Needs networkx."""
        import networkx as nx

        g = nx.DiGraph()
        for t in self.types:
            g.add_node(t.id, face=t.face, contribution=t.contribution)
        g.add_edges_from(self.edges)
        return g

    def _repr_html_(self) -> str:
        """A table of the face types in a notebook: notation, sub-faces by type, contribution."""
        if not self.closed:
            return f"<p>The closure does not close: {self.runaway!r}</p>"
        rows = []
        for t in self.types:
            seen: Dict[str, int] = {}
            for c in t.children:
                seen[c] = seen.get(c, 0) + 1
            kids = " + ".join(f"{k}×{c}" if k > 1 else c for c, k in seen.items())
            rows.append([t.id, t.face, kids, t.contribution])
        n = len(self.types)
        head = f"<p>closed: {n} face type{'' if n == 1 else 's'}, start {', '.join(self.start)}</p>"
        return head + _html_table(["type", "face", "sub-faces", "contribution"], rows)

    def matrix(self) -> List[List[int]]:
        """The substitution matrix: ``M[i][j]`` sub-faces of type j in type i."""
        index = {t.id: i for i, t in enumerate(self.types)}
        m = [[0] * len(self.types) for _ in self.types]
        for i, t in enumerate(self.types):
            for c in t.children:
                m[i][index[c]] += 1
        return m


@dataclass(frozen=True)
class LevelCount:
    """Exact counts at one level: ``faces`` = N^C_i (an int), ``lacunas`` = N^L_i (a Fraction:
    lacunas on shared edges count half) and ``ratio`` = R_i (a Fraction)."""

    level: int
    faces: int
    lacunas: Fraction
    ratio: Fraction


class Counts(list):
    """The :class:`LevelCount` of every level from 0, in order (a list); a notebook shows them
    as a table."""

    def _repr_html_(self) -> str:
        return _html_table(
            ["level", "N^C", "N^L", "R"],
            [[c.level, c.faces, c.lacunas, c.ratio] for c in self],
        )


@dataclass(frozen=True)
class LimitPoint:
    """``lim R_{Pn+r}`` for the residue r (exact text and certified decimals)."""

    residue: int
    exact: str
    decimal: str


@dataclass(frozen=True)
class Ratio:
    """The limit ratio R of lacunas against sub-faces, exact.

    Attributes:
        exists: whether R_i converges.
        exact: the limit as exact text: ``1/3``, ``(-3 + sqrt(17))/4`` when ρ is quadratic, or a
            polynomial in ρ with ρ the root of its minimal polynomial in an interval; None when
            the limit does not exist (see ``limit_points``).
        decimal: certified decimals (truncated), when it exists.
        coordinates: the limit on the power basis 1, ρ, …, ρ^(d−1) of Q(ρ), as Fractions.
        perron_root, perron_decimal, perron_min_poly: ρ, its decimals, its minimal polynomial
            in x.
        period: P, the lcm of the dominant periods.
        limit_points: the limits of R_{Pn+r}, one per residue r.
        reasons: how the decision was reached.
    """

    exists: bool
    exact: Optional[str]
    decimal: Optional[str]
    coordinates: Optional[Tuple[Fraction, ...]]
    perron_root: str
    perron_decimal: str
    perron_min_poly: str
    period: int
    limit_points: Tuple[LimitPoint, ...]
    reasons: Tuple[str, ...]
    data: Dict[str, Any] = field(repr=False, compare=False)

    @property
    def degree(self) -> int:
        """The degree of ρ over Q (1: R is rational; 2: quadratic)."""
        powers = [int(e) for e in re.findall(r"x\^(\d+)", self.perron_min_poly)]
        return max(powers, default=1 if "x" in self.perron_min_poly else 0)

    @property
    def rational(self) -> bool:
        """Whether R exists and is rational."""
        return self.exists and self.coordinates is not None and all(c == 0 for c in self.coordinates[1:])

    @property
    def value(self) -> Optional[Fraction]:
        """R as a Fraction when it is rational, else None."""
        return self.coordinates[0] if self.rational else None

    @property
    def quadratic(self) -> bool:
        """Whether R exists and its exact text is a SymPy expression in a square root."""
        return self.exists and self.degree <= 2

    def sympy(self):
        """R as an exact SymPy number: ``sympify(exact)`` when rational or quadratic, else the
        polynomial in ρ on ``coordinates`` with ρ the largest real root of its minimal polynomial
        (a ``CRootOf``). Needs SymPy; None when the limit does not exist."""
        import sympy

        if not self.exists:
            return None
        if self.quadratic:
            return sympy.sympify(self.exact)
        rho = self.rho()
        return sum(sympy.Rational(c.numerator, c.denominator) * rho**i for i, c in enumerate(self.coordinates))

    def rho(self):
        """ρ as an exact SymPy number (the largest real root of its minimal polynomial)."""
        import sympy

        x = sympy.Symbol("x")
        return sympy.Poly(sympy.sympify(self.perron_min_poly.replace("^", "**")), x).real_roots()[-1]


@dataclass(frozen=True)
class Solution:
    """The exact solution of the BC-IFS constraint system.

    Attributes:
        consistent: whether a solution exists.
        unknowns, equations: the size of the system.
        rank: its rank (None when inconsistent).
        dof: the degrees of freedom; ``dof_by_state`` and ``dof_by_operator`` split them.
        parameters: the free parameters, named after the entry each controls (``T0.T1[2][4]``).
        particular: one solution: each unknown operator's matrix, rows of Fractions.
        basis: for each parameter, the entries it moves and by how much (Fractions).
        conflicts: when inconsistent, the constraints with the multipliers that sum them to
            ``0 = conflict_constant``.
        degenerate: forced collapses found by the degeneracy check.
    """

    consistent: bool
    unknowns: int
    equations: int
    rank: Optional[int]
    dof: int
    dof_by_state: Dict[str, int]
    dof_by_operator: Dict[str, int]
    parameters: Tuple[str, ...]
    particular: Dict[str, List[List[Fraction]]]
    basis: Tuple[Dict[str, Fraction], ...]
    conflicts: Tuple[Tuple[str, Fraction], ...]
    conflict_constant: Optional[Fraction]
    degenerate: Tuple[str, ...]
    degeneracy_checked: bool
    data: Dict[str, Any] = field(repr=False, compare=False)

    @property
    def ok(self) -> bool:
        """Consistent and without forced collapse."""
        return self.consistent and not self.degenerate


@dataclass(frozen=True)
class FieldVerdict:
    """The verdict on an automaton whose entries lie in a real number field (every operator given):
    whether every constraint holds exactly in the field, and which fail."""

    field: str
    consistent: bool
    failed: Tuple[str, ...]
    data: Dict[str, Any] = field(repr=False, compare=False)

    @property
    def ok(self) -> bool:
        """Whether every constraint holds."""
        return self.consistent


@dataclass(frozen=True)
class CheckReport:
    """What the independent checker says of a certificate.

    Attributes:
        all_proved: every step the claim needs is proved (the command line's exit 0).
        partial: every step present is proved but some the claim needs are missing (exit 3).
        claim: the claim, in words.
        steps: each step's outcome, verdict and message (Records).
        missing: the steps the claim needs that the certificate lacks.
    """

    all_proved: bool
    partial: bool
    claim: Tuple[str, ...]
    steps: Tuple[Record, ...]
    missing: Tuple[str, ...]
    data: Dict[str, Any] = field(repr=False, compare=False)


class Certificate:
    """A certificate of every verdict on faces (closure, solution space, limit ratio): the JSON
    file ``lacuna verify --certificate`` writes. The checker re-verifies it alone."""

    def __init__(self, text: str):
        self.text = text

    @property
    def data(self) -> Dict[str, Any]:
        """The certificate as JSON data."""
        return json.loads(self.text)

    def write(self, path: PathLike) -> Path:
        """Writes the certificate to a file."""
        p = Path(path)
        p.write_text(self.text, encoding="utf-8")
        return p

    def check(self) -> CheckReport:
        """Runs the independent checker on this certificate."""
        return _check_report(*_lacuna.check_text(self.text))

    def __repr__(self) -> str:
        d = self.data
        return f"Certificate(input={d.get('input')!r}, steps={len(d.get('steps', []))})"


@dataclass
class Rendering(_Picture):
    """The cells of a level of faces: one float polygon per cell (an (n, 2) NumPy array, counter-
    clockwise), its face type, and the files written. A notebook shows its picture; ``image`` is
    the picture as an RGBA array."""

    polygons: List[Any]
    types: Any
    written: List[Path]
    _render: Any = field(default=None, repr=False, compare=False)
    _level: int = field(default=0, repr=False, compare=False)

    def __repr__(self) -> str:
        return f"Rendering(level={self._level}, cells={len(self.polygons)}, written={[p.name for p in self.written]})"

    def __len__(self) -> int:
        return len(self.polygons)

    def plot(self, ax=None, cmap: str = "tab10", edgecolor: str = "black", linewidth: float = 0.3):
        """Draws the cells on a matplotlib axis (filled by type); returns the axis."""
        return _plot_cells(ax, self.polygons, self.types, None, cmap, edgecolor, linewidth)


def _plot_cells(ax, polygons, types, closed, cmap: str, edgecolor: str, linewidth: float):
    """Draws cells on a matplotlib axis (a new one when ``ax`` is None): the closed ones (all when
    ``closed`` is None) as polygons filled by type, the open ones as lines of their type's colour
    three times as wide; returns the axis. Used by :meth:`Rendering.plot` and the frames of
    :func:`morph`."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection

    if ax is None:
        _, ax = plt.subplots()
    colours = plt.get_cmap(cmap)
    closed = [True] * len(polygons) if closed is None else closed
    filled = [(p, t) for p, t, c in zip(polygons, types, closed) if c]
    open_ = [(p, t) for p, t, c in zip(polygons, types, closed) if not c]
    if filled:
        ax.add_collection(
            PolyCollection(
                [p for p, _ in filled],
                facecolors=[colours(int(t) % colours.N) for _, t in filled],
                edgecolors=edgecolor,
                linewidths=linewidth,
            )
        )
    if open_:
        ax.add_collection(
            LineCollection(
                [p for p, _ in open_],
                colors=[colours(int(t) % colours.N) for _, t in open_],
                linewidths=linewidth * 3,
            )
        )
    ax.autoscale_view()
    ax.set_aspect("equal")
    return ax


@dataclass
class Shapes(_Picture):
    """The pieces of an automaton's attractor at a level: each an (n, space) NumPy array of points
    (space 2 or 3), its state's name and kind (``point``, ``polyline``, ``polygon``). A notebook
    shows its picture; ``image`` is the picture as an RGBA array."""

    points: List[Any]
    states: List[str]
    kinds: List[str]
    space: int
    consistent: bool
    written: List[Path]
    _render: Any = field(default=None, repr=False, compare=False)
    _level: int = field(default=0, repr=False, compare=False)

    def __repr__(self) -> str:
        return f"Shapes(level={self._level}, pieces={len(self.points)}, space={self.space}, written={[p.name for p in self.written]})"

    def __len__(self) -> int:
        return len(self.points)

    def plot(self, ax=None, cmap: str = "tab10", linewidth: float = 0.5):
        """Draws the pieces on a matplotlib axis (x, y); returns the axis."""
        import matplotlib.pyplot as plt
        from matplotlib.collections import LineCollection, PolyCollection

        if ax is None:
            _, ax = plt.subplots()
        colours = plt.get_cmap(cmap)
        names = sorted(set(self.states))
        colour = {n: colours(i % colours.N) for i, n in enumerate(names)}
        polys = [(p[:, :2], colour[s]) for p, s, k in zip(self.points, self.states, self.kinds) if k == "polygon"]
        lines = [(p[:, :2], colour[s]) for p, s, k in zip(self.points, self.states, self.kinds) if k == "polyline"]
        dots = [(p[:, :2], colour[s]) for p, s, k in zip(self.points, self.states, self.kinds) if k == "point"]
        if polys:
            ax.add_collection(
                PolyCollection([p for p, _ in polys], facecolors=[c for _, c in polys], edgecolors="black", linewidths=linewidth)
            )
        if lines:
            ax.add_collection(LineCollection([p for p, _ in lines], colors=[c for _, c in lines], linewidths=linewidth * 2))
        for p, c in dots:
            ax.plot(p[:, 0], p[:, 1], ".", color=c, markersize=2)
        ax.autoscale_view()
        ax.set_aspect("equal")
        return ax


def _check_report(text: str, all_proved: bool, partial: bool) -> CheckReport:
    d = json.loads(text)
    return CheckReport(
        all_proved=all_proved,
        partial=partial,
        claim=tuple(d.get("claim", [])),
        steps=tuple(Record(s) for s in d.get("steps", [])),
        missing=tuple(d.get("missing", [])),
        data=d,
    )


def _closure(d: Dict[str, Any]) -> Closure:
    types = tuple(
        FaceType(
            id=t["id"],
            face=t["face"],
            children=tuple(t.get("children", [])),
            subfaces=tuple(t.get("subfaces", [])),
            contribution=Fraction(t["contribution"]),
            complex=Record(t["complex"]) if t.get("complex") else None,
        )
        for t in d.get("types", [])
    )
    closed = bool(d.get("closed"))
    return Closure(
        closed=closed,
        types=types,
        start=tuple(d.get("start", [])),
        classes=Record(d["classes"]) if d.get("classes") else None,
        bound=Record(d["bound"]) if d.get("bound") else None,
        runaway=None if closed else Record(d.get("runaway") or {}),
        data=d,
    )


def _ratio(d: Dict[str, Any]) -> Ratio:
    coords = d.get("coordinates")
    return Ratio(
        exists=bool(d["exists"]),
        exact=d.get("exact"),
        decimal=d.get("decimal"),
        coordinates=None if coords is None else tuple(Fraction(c) for c in coords),
        perron_root=d["perron_root"],
        perron_decimal=d["perron_decimal"],
        perron_min_poly=d["perron_min_poly"],
        period=int(d["period"]),
        limit_points=tuple(LimitPoint(int(p["residue"]), p["exact"], p["decimal"]) for p in d.get("limit_points", [])),
        reasons=tuple(d.get("reasons", [])),
        data=d,
    )


def _solution(d: Dict[str, Any]) -> Union[Solution, FieldVerdict]:
    if "field" in d and "unknowns" not in d:
        return FieldVerdict(field=d["field"], consistent=bool(d["consistent"]), failed=tuple(d.get("failed", [])), data=d)
    return Solution(
        consistent=bool(d["consistent"]),
        unknowns=int(d["unknowns"]),
        equations=int(d["equations"]),
        rank=d.get("rank"),
        dof=int(d["dof"]),
        dof_by_state=dict(d.get("dof_by_state", {})),
        dof_by_operator=dict(d.get("dof_by_operator", {})),
        parameters=tuple(d.get("parameters", [])),
        particular={k: _matrix(v) for k, v in d.get("particular", {}).items()},
        basis=tuple({k: Fraction(v) for k, v in b.items()} for b in d.get("basis", [])),
        conflicts=tuple((c["constraint"], Fraction(c["multiplier"])) for c in (d.get("conflict") or [])),
        conflict_constant=_q(d.get("conflict_constant")),
        degenerate=tuple(d.get("degenerate", [])),
        degeneracy_checked=bool(d.get("degeneracy_checked")),
        data=d,
    )


# ---------------------------------------------------------------------------------------------
# Subdivision operators (`lacuna operators`)

Points = Union[str, Sequence[Sequence[Union[int, float, Fraction, str]]]]


def _rows(points: Points) -> str:
    """Control points as the command line's ``x y; x y; …`` (a string is passed as it is)."""
    if isinstance(points, str):
        return points
    return "; ".join(" ".join(str(x) for x in row) for row in points)


def _operators(
    source: Optional[str],
    matrices: Sequence[str] = (),
    op: Optional[str] = None,
    points: Optional[Points] = None,
    at: Sequence[Union[str, int, Fraction]] = (),
    level: int = 8,
    curvature: Optional[str] = None,
    limits: Limits = None,
) -> Record:
    """The report of ``lacuna operators [SOURCE] … --json`` as a :class:`Record`."""
    text = _lacuna.operators(
        source,
        [str(m) for m in matrices],
        op,
        None if points is None else _rows(points),
        [str(t) for t in at],
        _natural("level", level),
        curvature,
        _limits(limits),
    )
    return Record(json.loads(text))


def operators(*matrices: Union[str, Sequence[Sequence[Union[int, Fraction, str]]]], limits: Limits = None) -> Record:
    """The eigen analysis of matrices given by hand (``lacuna operators --matrix M … --json``):
    each a string ``"[a b; c d]"`` or rows of exact numbers. ``.matrices`` holds one report per
    matrix (eigenvalues, fixed point, contraction, tangent and pseudo-curvature class)."""
    texts = [m if isinstance(m, str) else "[" + _rows(m) + "]" for m in matrices]
    return _operators(None, texts, limits=limits)


class _Operators:
    """The ``operators`` method shared by faces, assemblies and automata (``source`` is what the
    command line would be given)."""

    source: str

    def operators(
        self,
        op: Optional[str] = None,
        points: Optional[Points] = None,
        limits: Limits = None,
        *,
        at: Sequence[Union[str, int, Fraction]] = (),
        level: int = 8,
        curvature: Optional[str] = None,
    ) -> Record:
        """The eigen analysis of the subdivision operators (THEORY §8), as ``lacuna operators
        --json`` reports it: ``.automaton`` (every operator's eigenvalues, fixed point,
        contraction, tangent and pseudo-curvature class, the end and joining points of curves),
        ``.curves`` with ``points`` (the control points of a curve's state, ``"x y; x y"`` or
        rows): the DCFs and pseudo-curvature ranges (also at the dyadic parameters ``at``), and
        ``.curvature`` the estimate at the fixed point of the operator ``curvature``. ``op``
        analyses only that operator. Faces and assemblies are instantiated with the default
        parameters first."""
        return _operators(self.source, (), op, points, at, level, curvature, limits)


@dataclass(frozen=True)
class Design:
    """An operator built from its eigenvalues and eigenvectors (``lacuna design``).

    Attributes:
        matrix: T = V·D·V⁻¹, exact, as rows of Fractions.
        analysis: its eigen analysis (a Record, as ``lacuna operators`` reports a matrix).
        check: with an automaton, the result of plugging T in as one of its operators (a Record:
            barycentric, every constraint involving it, the re-solved system), else None.
        data: the object ``lacuna design --json`` prints.
    """

    matrix: List[List[Fraction]]
    analysis: Record
    check: Optional[Record]
    data: Dict[str, Any] = field(repr=False)

    @property
    def ok(self) -> bool:
        """The design satisfies every constraint of the automaton (True without a check; the
        command line's exit code 1 otherwise)."""
        return self.check is None or _design_ok(self.data["check"])


def _design_ok(check: Dict[str, Any]) -> bool:
    """The verdict of a design check (``DesignCheck::ok``): barycentric when it must be, every
    constraint holds and the re-solved system is consistent."""
    return check.get("barycentric") is not False and all(c["holds"] for c in check["constraints"]) and bool(check["consistent"])


def design(
    eigenvalues: Union[str, Sequence[Union[int, Fraction, str]]],
    eigenvectors: Union[str, Sequence[Sequence[Union[int, Fraction, str]]]],
    *,
    check: Union[None, str, "Automaton"] = None,
    op: Optional[str] = None,
) -> Design:
    """Inverse design (``lacuna design --json``): the exact operator T = V·D·V⁻¹ with the
    eigenvalues ``eigenvalues`` (``"1 1/2 1/4"`` or exact numbers) and the eigenvectors
    ``eigenvectors`` (one per row, in the same order: ``"[1 0 0; -1 1 0; 1 -2 1]"`` or rows), with
    its eigen analysis; with ``check`` (an automaton) and ``op`` (one of its operators), whether T
    can replace that operator."""
    values = eigenvalues if isinstance(eigenvalues, str) else " ".join(str(v) for v in eigenvalues)
    vectors = eigenvectors if isinstance(eigenvectors, str) else "[" + _rows(eigenvectors) + "]"
    if (check is None) != (op is None):
        raise UsageError("E0504", "check and op go together: give the automaton and the operator to replace")
    source = check.source if isinstance(check, Automaton) else (None if check is None else os.fspath(check))
    d = json.loads(_lacuna.design(values, vectors, source, op))
    return Design(
        matrix=_matrix(d["matrix"]),
        analysis=Record(d["analysis"]),
        check=None if d.get("check") is None else Record(d["check"]),
        data=d,
    )


# ---------------------------------------------------------------------------------------------
# Inputs


class Structure(_Operators):
    """What the faces' methods share: a face, an assembly of faces (with shared edges) or a face
    structure of the library. ``source`` is what the command line would be given (notation, a
    path or a library name)."""

    source: str
    name: str

    def __init__(self, source: str):
        kind, name = _lacuna.kind(source)
        if kind != "faces":
            raise UsageError("E0504", f"`{source}` is a {kind}, not faces: use lacuna.load()")
        self.source = source
        self.name = name

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r})"

    def closure(self, *, limits: Limits = None) -> Closure:
        """Every face type the recursion produces, with sub-faces, contributions, classes and the
        stated bound; a runaway is a result (``closed`` False), not an error."""
        return _closure(json.loads(_lacuna.closure(self.source, _limits(limits))))

    def counts(self, levels: int, *, limits: Limits = None) -> "Counts":
        """Exact counts for levels 0..levels: N^C_i (int), N^L_i and R_i (Fractions), as a list
        (:class:`Counts`) that a notebook shows as a table."""
        d = json.loads(_lacuna.counts(self.source, _natural("levels", levels), _limits(limits)))
        return Counts(
            LevelCount(int(r["level"]), int(r["faces"]), Fraction(r["lacunas"]), Fraction(r["ratio"]))
            for r in d["levels"]
        )

    def ratio(self, digits: int = 30, *, limits: Limits = None) -> Ratio:
        """The exact limit ratio R by eigen analysis, with ``digits`` certified decimals."""
        return _ratio(json.loads(_lacuna.ratio(self.source, _natural("digits", digits), _limits(limits))))

    def solve(self, degree: int = 2, cantor_gap: Union[str, int, Fraction] = 1, *, limits: Limits = None) -> Solution:
        """The exact BC-IFS constraint system of the closure with Bézier degree ``degree`` and
        Cantor gap/piece ``cantor_gap``: rank, degrees of freedom, particular solution and basis,
        or the conflicting constraints."""
        d = json.loads(_lacuna.solve(self.source, int(degree), str(cantor_gap), _limits(limits)))
        return _solution(d)  # type: ignore[return-value]

    def verify(self, levels: int = 5, *, limits: Limits = None) -> Record:
        """The whole verification (closure, bound, identities, classes, counts, R, solver) as
        ``lacuna verify --json`` reports it; ``.verified`` is the verdict."""
        return Record(json.loads(_lacuna.verify(self.source, _natural("levels", levels), _limits(limits))))

    def certificate(self, path: Optional[PathLike] = None, *, limits: Limits = None) -> Certificate:
        """The certificate of every verdict; written to ``path`` when given."""
        c = Certificate(_lacuna.certificate(self.source, _limits(limits)))
        if path is not None:
            c.write(path)
        return c

    #: The level and width in pixels of the picture a notebook shows (``_repr_png_``).
    display = (3, 480)

    def _repr_png_(self) -> bytes:
        """The picture a notebook shows: level ``display[0]``, ``display[1]`` pixels wide, cells
        coloured by type with the legend (``render(..., png=...)``)."""
        level, size = self.display
        return _png_bytes(self.render, level, size)

    def render(
        self,
        level: int,
        *,
        svg: Optional[PathLike] = None,
        png: Optional[PathLike] = None,
        stl: Optional[PathLike] = None,
        stl_ascii: bool = False,
        size: int = 1024,
        legend: bool = True,
        transparent: bool = False,
        width: Optional[float] = None,
        thickness: Optional[float] = None,
        params: Params = None,
        corners: Corners = None,
        template: Optional[PathLike] = None,
        goal: Goals = None,
        segments: int = 4,
        max_cells: Optional[int] = None,
        limits: Limits = None,
    ) -> Rendering:
        """Instantiates the verified model (default parameters, or ``params`` {name: exact value})
        and returns the polygons of level ``level`` as NumPy arrays; writes an SVG, a PNG (``size``
        pixels wide) and a printable STL (``width``/``thickness`` in mm; checked against the exact
        topology before writing) when their paths are given. As ``lacuna render``'s
        ``--corners``, ``--template`` and ``--goal``: ``corners`` places a single face (``"X Y,
        X Y, …"`` or (x, y) pairs, exact, counter-clockwise), ``template`` is a template file
        projected exactly instead of the default fit, ``goal`` one inequality goal or several
        (``"nonnegative"``, ``"nonnegative=M"``, ``"min-lacuna=S"``) met through an LP."""
        import numpy as np

        p = _params(params)
        lim = _limits(limits)
        chosen = _face_choice(corners, template, goal)
        types, offsets, xy = _lacuna.polygons(self.source, int(level), p, int(segments), max_cells, lim, **chosen)
        pts = np.asarray(xy, dtype=float).reshape(-1, 2)
        polygons = [pts[offsets[i] : offsets[i + 1]] for i in range(len(types))]
        written: List[Path] = []
        if svg is not None or png is not None or stl is not None:
            written = [
                Path(w)
                for w in _lacuna.render(
                    self.source,
                    int(level),
                    p,
                    _path(svg),
                    _path(png),
                    _path(stl),
                    bool(stl_ascii),
                    int(size),
                    bool(legend),
                    bool(transparent),
                    width,
                    thickness,
                    int(segments),
                    max_cells,
                    lim,
                    **chosen,
                )
            ]
        picture = lambda lv, png, size: self.render(  # noqa: E731
            lv,
            png=png,
            size=size,
            params=params,
            corners=corners,
            template=template,
            goal=goal,
            segments=segments,
            max_cells=max_cells,
            limits=limits,
        )
        return Rendering(
            polygons=polygons, types=np.asarray(types, dtype=int), written=written, _render=picture, _level=int(level)
        )

    def export(
        self,
        path: Optional[PathLike] = None,
        format: str = "aut",
        *,
        degree: int = 2,
        cantor_gap: Union[str, int, Fraction] = 1,
        limits: Limits = None,
    ) -> str:
        """The automaton generated from the closure (Bézier degree ``degree``, Cantor gap/piece
        ``cantor_gap``) in lacuna's automaton format (``format="aut"``, which :meth:`solve` reads
        back with the same rank and degrees of freedom) or as the MODITERE Python model of
        AutoFrac2D (``format="moditere"``), as ``lacuna export SOURCE --format FORMAT`` writes
        it; also written to ``path`` when given (never over the input)."""
        return _lacuna.export(self.source, str(format), _path(path), _natural("degree", degree), str(cantor_gap), _limits(limits))

    def measure(
        self,
        level: int,
        *,
        params: Params = None,
        corners: Corners = None,
        template: Optional[PathLike] = None,
        goal: Goals = None,
        raster: int = 2048,
        max_raster: int = 8192,
        width: Optional[float] = None,
        resolution: Optional[float] = None,
        segments: int = 4,
        max_cells: Optional[int] = None,
        limits: Limits = None,
    ) -> Record:
        """Area, perimeter, F_A, F_P, box-counting dimension, density, holes and components per
        level against the exact counts (``.verified``), and the printability at the level, as
        ``lacuna measure --json`` reports them; the parameters chosen by ``params``, ``corners``,
        ``template`` and ``goal`` as in :meth:`render`."""
        return Record(
            json.loads(
                _lacuna.measure(
                    self.source,
                    int(level),
                    _params(params),
                    int(raster),
                    int(max_raster),
                    30,
                    width,
                    resolution,
                    int(segments),
                    max_cells,
                    _limits(limits),
                    **_face_choice(corners, template, goal),
                )
            )
        )


    def report(
        self,
        path: Optional[PathLike] = None,
        level: int = 3,
        *,
        params: Params = None,
        corners: Corners = None,
        template: Optional[PathLike] = None,
        goal: Goals = None,
        raster: int = 2048,
        segments: int = 4,
        max_cells: Optional[int] = None,
        limits: Limits = None,
    ) -> Union[Path, str]:
        """The self-contained HTML report ``lacuna report`` writes: the verdict line, the
        verification (levels 0 to ``level``, at least 5), pictures of levels 0 to ``level`` and
        the measures (``raster`` pixels for box counting, ``segments`` per Bézier edge; at most
        ``max_cells`` cells, 200 000 by default), the parameters chosen by ``params``,
        ``corners``, ``template`` and ``goal`` as in :meth:`render`. Written to ``path`` (never
        over the input or the template), which is returned; with ``path`` None the HTML text is
        returned instead. A closure that does not close is a page that says so."""
        from ._commands import _report

        return _report(self.source, path, level, params, raster, segments, max_cells, limits, _face_choice(corners, template, goal))


def _path(p: Optional[PathLike]) -> Optional[str]:
    return None if p is None else os.fspath(p)


class Face(Structure):
    """One face in lacuna's notation: ``Face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1")`` (boundary |
    Ea El Ec | algorithm [| delay]). Raises :class:`InputError` with the span of a bad token.

    ``notation`` is the canonical form (the least rotation of the boundary)."""

    def __init__(self, notation: str):
        self.notation = _lacuna.canonical(notation)
        super().__init__(notation)

    @classmethod
    def _named(cls, source: str, notation: str) -> "Face":
        """The one face of a file or a library entry (``source``, which keeps its name and any
        coordinates the file gives), of canonical notation ``notation``."""
        f = cls.__new__(cls)
        f.notation = notation
        Structure.__init__(f, source)
        return f

    @classmethod
    def from_notation(cls, notation: str) -> "Face":
        """The face written in lacuna's notation (the same as ``Face(notation)``)."""
        return cls(notation)

    def __repr__(self) -> str:
        return f"Face({self.notation!r})"


class Assembly(Structure):
    """Faces with shared edges: an assembly file in lacuna's format, an AutoFrac2D input file, or a
    library entry of faces."""

    @classmethod
    def from_file(cls, path: PathLike) -> "Assembly":
        """Reads an assembly or AutoFrac2D file."""
        p = os.fspath(path)
        if not os.path.isfile(p):
            _lacuna.read_text(p)  # raises FileError (E0601) with lacuna's message
        return cls(p)


class Automaton(_Operators):
    """A hand-written automaton (lacuna's automaton format): states, operators, constraints, and
    optionally a field, points and primitives to draw its attractor."""

    def __init__(self, source: str):
        kind, name = _lacuna.kind(source)
        if kind != "automaton":
            raise UsageError("E0504", f"`{source}` is {kind}, not an automaton")
        self.source = source
        self.name = name

    @classmethod
    def from_file(cls, path: PathLike) -> "Automaton":
        """Reads an automaton file."""
        p = os.fspath(path)
        if not os.path.isfile(p):
            _lacuna.read_text(p)
        return cls(p)

    def __repr__(self) -> str:
        return f"Automaton({self.name!r})"

    #: The level and width in pixels of the picture a notebook shows (``_repr_png_``).
    display = (8, 480)

    def _repr_png_(self) -> bytes:
        """The picture a notebook shows: the attractor at level ``display[0]``, ``display[1]``
        pixels wide, coloured by state with the legend."""
        level, size = self.display
        return _png_bytes(self.render, level, size)

    def solve(self, *, limits: Limits = None) -> Union[Solution, FieldVerdict]:
        """The exact solution of its constraint system (a :class:`FieldVerdict` when its entries lie
        in a number field and every operator is given)."""
        return _solution(json.loads(_lacuna.solve(self.source, 2, "1", _limits(limits))))

    def certificate(self, path: Optional[PathLike] = None, *, limits: Limits = None) -> Certificate:
        """The certificate of what ``lacuna verify`` proves about it (constraints, contraction of
        every walk, similarity dimension and, where convex sets decide it, the open-set
        condition); written to ``path`` when given."""
        c = Certificate(_lacuna.automaton_certificate(self.source, _limits(limits)))
        if path is not None:
            c.write(path)
        return c

    def render(
        self,
        level: int,
        *,
        svg: Optional[PathLike] = None,
        png: Optional[PathLike] = None,
        size: int = 1024,
        params: Params = None,
        max_cells: Optional[int] = None,
        limits: Limits = None,
        state: Optional[str] = None,
    ) -> Shapes:
        """The attractor at ``level`` (operators resolved with ``params``, every cycle checked to
        contract): its pieces as NumPy arrays; writes an SVG and a PNG when their paths are given.
        ``state`` draws the attractor of that state instead of the start state's, from its frame
        (``lacuna render --state``): the start's points carried by the first operator reaching it."""
        import numpy as np

        p = _params(params)
        lim = _limits(limits)
        text, _names, consistent = _lacuna.automaton_shapes(self.source, int(level), p, max_cells, lim, state)
        d = json.loads(text)
        shapes = d.get("shapes", [])
        space = int(d.get("space", 2))
        written: List[Path] = []
        if svg is not None or png is not None:
            written = [
                Path(w)
                for w in _lacuna.render(
                    self.source, int(level), p, _path(svg), _path(png), None, False, int(size), True, False,
                    None, None, 4, max_cells, lim, None, None, [], state,
                )
            ]
        picture = lambda lv, png, size: self.render(lv, png=png, size=size, params=params, max_cells=max_cells, limits=limits, state=state)  # noqa: E731
        return Shapes(
            points=[np.asarray(s["points"], dtype=float).reshape(-1, space) for s in shapes],
            states=[s["state"] for s in shapes],
            kinds=[s["kind"] for s in shapes],
            space=space,
            consistent=bool(consistent),
            written=written,
            _render=picture,
            _level=int(level),
        )

    def export(
        self,
        path: Optional[PathLike] = None,
        format: str = "aut",
        *,
        degree: int = 2,
        cantor_gap: Union[str, int, Fraction] = 1,
        limits: Limits = None,
    ) -> str:
        """The automaton in lacuna's automaton format (``format="aut"``; it has no MODITERE model), as
        ``lacuna export SOURCE --format FORMAT`` writes it; also written to ``path`` when given
        (never over the input)."""
        return _lacuna.export(self.source, str(format), _path(path), _natural("degree", degree), str(cantor_gap), _limits(limits))

    def measure(self, level: int, *, digits: int = 30, params: Params = None, max_cells: Optional[int] = None, limits: Limits = None, state: Optional[str] = None) -> Record:
        """Lengths and areas per level, a box-counting estimate and the exact similarity dimension
        with ``digits`` certified digits, as ``lacuna measure --json`` reports them; ``state``
        measures that state's attractor instead of the start state's (``measure --state``)."""
        return Record(
            json.loads(
                _lacuna.measure(
                    self.source, int(level), _params(params), 2048, 8192, int(digits), None, None, 4,
                    max_cells, _limits(limits), None, None, [], state,
                )
            )
        )


    def report(
        self,
        path: Optional[PathLike] = None,
        level: int = 3,
        *,
        params: Params = None,
        max_cells: Optional[int] = None,
        limits: Limits = None,
    ) -> Union[Path, str]:
        """The self-contained HTML report ``lacuna report`` writes: the verdict on its constraints
        (operators resolved with ``params``), pictures of levels 0 to ``level`` (at most
        ``max_cells`` pieces, 100 000 by default), the measures and similarity dimension, the
        operators' eigen analysis, the curvature of its curves and its source. Written to
        ``path`` (never over the input), which is returned; with ``path`` None the HTML text is
        returned instead."""
        from ._commands import _report

        return _report(self.source, path, level, params, 2048, 4, max_cells, limits)


# ---------------------------------------------------------------------------------------------
# The library


def library() -> Dict[str, str]:
    """The named structures shipped with lacuna: {name: the first line of its description}."""
    return {n: t.splitlines()[0].lstrip("#").strip() if t else "" for n, t in _lacuna.library()}


def library_text(name: str) -> str:
    """The text of a library entry (its file as shipped)."""
    for n, t in _lacuna.library():
        if n == name:
            return t
    raise FileError("E0601", f"cannot read `{name}`: no such library entry")


class Rule(Automaton):
    """A production rule (Kaandorp's initiator and generators, lacuna's rule format) compiled to
    an automaton: a rule file or a library entry written as a rule (``koch``,
    ``heighway-dragon``, …). ``text`` is the rule text; everything else is the
    :class:`Automaton`'s. Raises :class:`UsageError` for a hand-written automaton."""

    def __init__(self, source: str):
        super().__init__(source)
        text = _lacuna.rule_text(source)
        if text is None:
            raise UsageError("E0504", f"`{source}` is a hand-written automaton, not a rule")
        self.text = text


def load(source: PathLike) -> Union[Face, Assembly, Automaton, "Volume"]:
    """What ``source`` names, as the command line reads it: face notation, or a file or a library
    name of one face without shared edges (a :class:`Face`; ``load("F0")``), a file or a library
    name of several faces (an :class:`Assembly`), of an automaton (an :class:`Automaton`; a
    :class:`Rule` when it is compiled from a rule), or
    volume notation, a volume file or a library name of volumes (a :class:`Volume`, one volume or
    several glued face to face)."""
    s = os.fspath(source)
    kind, _ = _lacuna.kind(s)
    if kind == "automaton":
        return Rule(s) if _lacuna.rule_text(s) is not None else Automaton(s)
    if kind == "volume":
        return Volume(s)
    if "|" in s:
        return Face(s)
    faces, shared = _lacuna.start_faces(s)
    if len(faces) == 1 and shared == 0:
        return Face._named(s, faces[0])
    return Assembly(s)


def check(path: PathLike) -> CheckReport:
    """Runs the independent checker on a certificate file (``lacuna check``)."""
    text = _lacuna.read_text(os.fspath(path))
    return _check_report(*_lacuna.check_text(text))


# Volumes live in their own module; it uses the helpers above, so it is imported last.
from ._volume import (  # noqa: E402
    SolidLevel,
    SolidTopology,
    Volume,
    VolumeClosure,
    VolumeCounts,
    VolumeLevelCount,
    VolumeRendering,
    VolumeType,
)

# Families and the mesh checker, likewise.
from ._family import Exploration, census, check_mesh, explore  # noqa: E402

# The report, the classification and the metamorphosis, likewise.
from ._commands import Classification, Comparison, Morph, MorphFrame, classify, morph  # noqa: E402
