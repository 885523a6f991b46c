"""The report, the classification and the metamorphosis: ``lacuna report``, ``lacuna classify``
and ``lacuna morph`` from Python.

The HTML report is the method ``report`` of :class:`~lacuna.Face`, :class:`~lacuna.Assembly`,
:class:`~lacuna.Automaton` and :class:`~lacuna.Volume` (:func:`_report` below does the work);
:func:`classify` compares inputs by their topological invariants and groups them into classes;
:func:`morph` builds and checks the frames between two parameter choices of faces or between
two automata of one shape, and writes the animated SVG.
"""

from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

from . import _lacuna
from . import Limits, PathLike, Record, UsageError, _html_table, _limits, _natural, _params, _path, _plot_cells


def _report(
    source: str,
    path: Optional[PathLike],
    level: int,
    params,
    raster: int,
    segments: int,
    max_cells: Optional[int],
    limits: Limits,
    choice: Optional[Dict[str, Any]] = None,
) -> Union[Path, str]:
    """The HTML page of ``lacuna report`` of ``source``: written to ``path`` (returned as a
    :class:`~pathlib.Path`), or returned as text when ``path`` is None; ``choice`` holds the
    keywords of faces' ``corners``, ``template`` and ``goals`` (``lacuna._face_choice``)."""
    html, _verified = _lacuna.report(
        source,
        _natural("level", level),
        _path(path),
        _params(params),
        _natural("raster", raster),
        _natural("segments", segments),
        max_cells,
        _limits(limits),
        **(choice or {}),
    )
    return html if path is None else Path(os.fspath(path))


def _source(x: Any) -> str:
    """What the command line would be given for ``x``: its ``source``, or ``x`` as a path."""
    s = getattr(x, "source", None)
    if isinstance(s, str):
        return s
    if isinstance(x, (str, os.PathLike)):
        return os.fspath(x)
    raise UsageError("E0504", f"{x!r} is not an input: give a Face, an Assembly, an Automaton, a Volume, notation, a path or a library name")


_INTEGER = re.compile(r"-?[0-9]+")
_RATIONAL = re.compile(r"-?[0-9]+/[0-9]+")


def _exact(v: Any) -> Any:
    """A count or an exact share as ``int`` or :class:`~fractions.Fraction` (other text stays)."""
    if isinstance(v, str):
        if _INTEGER.fullmatch(v):
            return int(v)
        if _RATIONAL.fullmatch(v):
            return Fraction(v)
    return v


def _shares(d: Mapping[str, Any]) -> Record:
    """Limit shares with each share a Fraction."""
    d = dict(d)
    if "shares" in d:
        d["shares"] = [dict(s, share=Fraction(s["share"])) for s in d["shares"]]
    return Record(d)


@dataclass(frozen=True)
class Comparison:
    """The comparison of two inputs (``lacuna classify A B --json``).

    Attributes:
        a, b: the inputs' names.
        kinds: ``(kind of a, kind of b)``: ``faces``, ``volume`` or ``automaton``.
        same_class: whether every invariant compared is equal.
        differs: the first invariant that differs (``group``, ``invariant``, ``level``, and the
            values ``a`` and ``b``, counts as ``int``), or None.
        levels: the levels compared, 0 to this.
        every_level: whether equality at these levels proves equality at every level.
        limit_valence: the valences the vertices of faces settle at (``a``, ``b``; None for others).
        limit_shares: the limit share of each valence (``a``, ``b``; shares as Fractions).
        notes: what was not compared, in words.
        text: the comparison as ``lacuna classify`` prints it.
    """

    a: str
    b: str
    kinds: Tuple[str, str]
    same_class: bool
    differs: Optional[Record]
    levels: int
    every_level: bool
    limit_valence: Record
    limit_shares: Record
    notes: List[str]
    text: str = field(repr=False)

    def _row(self) -> List[Any]:
        if self.differs is None:
            verdict = "same class"
        else:
            d = self.differs
            at = "" if d.level is None else f" at level {d.level}"
            verdict = f"differ: {d.invariant} ({d.group}){at}: {d.a} vs {d.b}"
        return [self.a, self.b, verdict, f"0 to {self.levels}" + (" (every level)" if self.every_level else "")]

    def _repr_html_(self) -> str:
        return _html_table(["A", "B", "verdict", "levels"], [self._row()])


def _comparison(d: Mapping[str, Any]) -> Comparison:
    differs = d.get("differs")
    if differs is not None:
        differs = Record(dict(differs, a=_exact(differs["a"]), b=_exact(differs["b"])))
    return Comparison(
        a=d["a"],
        b=d["b"],
        kinds=(d["kinds"]["a"], d["kinds"]["b"]),
        same_class=bool(d["same_class"]),
        differs=differs,
        levels=int(d["levels"]),
        every_level=bool(d["every_level"]),
        limit_valence=Record(d["limit_valence"]),
        limit_shares=Record({k: _shares(v) for k, v in d["limit_shares"].items()}),
        notes=list(d["notes"]),
        text=d["text"],
    )


class Classification:
    """The topological classes of the inputs of :func:`classify`.

    ``inputs`` are the inputs as given; ``classes`` groups them (each class a list of inputs, in
    the order given: two inputs share a class when a chain of comparisons says so);
    ``comparisons`` holds a :class:`Comparison` for every pair (``comparison(i, j)`` by
    position). ``same_class`` says whether all inputs are in one class. A notebook shows the
    comparisons as a table."""

    def __init__(self, inputs: List[Any], comparisons: Dict[Tuple[int, int], Comparison]):
        self.inputs = inputs
        self._comparisons = comparisons
        parent = list(range(len(inputs)))

        def find(i: int) -> int:
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        for (i, j), c in comparisons.items():
            if c.same_class:
                parent[find(j)] = find(i)
        groups: Dict[int, List[Any]] = {}
        for i, x in enumerate(inputs):
            groups.setdefault(find(i), []).append(x)
        self.classes: List[List[Any]] = list(groups.values())

    @property
    def comparisons(self) -> List[Comparison]:
        """Every pair's comparison, (0, 1), (0, 2), …, (1, 2), …"""
        return [self._comparisons[k] for k in sorted(self._comparisons)]

    def comparison(self, i: int, j: int) -> Comparison:
        """The comparison of input ``i`` (as A) with input ``j`` (as B), ``i != j``."""
        if i == j or not (0 <= i < len(self.inputs) and 0 <= j < len(self.inputs)):
            raise UsageError("E0504", f"comparison({i}, {j}): give two different positions from 0 to {len(self.inputs) - 1}")
        return self._comparisons[(i, j)] if i < j else self._comparisons[(j, i)]

    @property
    def same_class(self) -> bool:
        """Whether every input is in one class."""
        return len(self.classes) == 1

    def __len__(self) -> int:
        return len(self.classes)

    def __repr__(self) -> str:
        names = [[_name(x) for x in c] for c in self.classes]
        return f"Classification(classes={names})"

    def _repr_html_(self) -> str:
        return _html_table(["A", "B", "verdict", "levels"], [c._row() for c in self.comparisons])


def _name(x: Any) -> str:
    return getattr(x, "name", None) or os.fspath(x)


def classify(
    *inputs: Any,
    levels: int = 4,
    volume_levels: int = 2,
    max_cells: int = 200_000,
    multiplicity: str = "coincidences",
    limits: Limits = None,
) -> Classification:
    """The topological classes of two or more inputs (faces, assemblies, volumes, automata; the
    objects or what the command line reads), compared pair by pair as ``lacuna classify A B``
    does: cell counts and valences at levels 0 to ``levels`` (more when the recurrences of faces
    need more to decide every level), the limit valences and their shares. A volume's level-k
    complexes are built for k up to ``volume_levels`` (at most ``max_cells`` cells);
    an automaton's multiplicity is seed 002's (pieces that are one exact map, decided at every
    level when its distinct maps satisfy the open-set condition); ``multiplicity="contacts"``
    also counts the pieces meeting at the images of fixed corners, in a note, never compared."""
    if len(inputs) < 2:
        raise UsageError("E0504", f"classify needs two inputs or more, got {len(inputs)}")
    sources = [_source(x) for x in inputs]
    lim = _limits(limits)
    opts = (
        _natural("levels", levels),
        _natural("volume_levels", volume_levels),
        _natural("max_cells", max_cells),
        str(multiplicity),
    )
    comparisons: Dict[Tuple[int, int], Comparison] = {}
    for i in range(len(sources)):
        for j in range(i + 1, len(sources)):
            d = json.loads(_lacuna.classify(sources[i], sources[j], *opts, lim))
            comparisons[(i, j)] = _comparison(d)
    return Classification(list(inputs), comparisons)


@dataclass
class MorphFrame:
    """One frame of a morph: its cells (``polygons``, each an (n, 2) NumPy array; ``types`` the
    face type or automaton state of each; ``closed`` whether each is a filled polygon rather
    than an open polyline or a point), its position ``t`` (a Fraction from 0 to 1) and its
    verdict (``verified``, ``failures``; for faces the ``holes`` and ``components`` observed)."""

    index: int
    t: Fraction
    verified: bool
    failures: List[str]
    holes: Optional[int]
    components: Optional[int]
    polygons: List[Any] = field(repr=False)
    types: Any = field(repr=False)
    closed: Any = field(repr=False)

    def __len__(self) -> int:
        return len(self.polygons)

    def plot(self, ax=None, cmap: str = "tab10", edgecolor: str = "black", linewidth: float = 0.3):
        """Draws the cells on a matplotlib axis (polygons filled by type, open cells as lines);
        returns the axis."""
        return _plot_cells(ax, self.polygons, self.types, self.closed, cmap, edgecolor, linewidth)


@dataclass
class Morph:
    """The metamorphosis of :func:`morph` (``lacuna morph --json``): ``frames`` (each a
    :class:`MorphFrame` with its cells), how many of the ``parameters`` (operators, for automata)
    change, for two automata with control points ``moving_points`` (moving, of all), the verdict
    (``verified``; ``first_failure``, the index of the first frame that fails) and the files
    written. A notebook shows the frames' verdicts as a table."""

    name: str
    level: int
    changing: int
    parameters: int
    moving_points: Optional[Tuple[int, int]]
    frames: List[MorphFrame]
    verified: bool
    first_failure: Optional[int]
    written: List[Path]

    def __len__(self) -> int:
        return len(self.frames)

    def __repr__(self) -> str:
        return (
            f"Morph({self.name!r}, frames={len(self.frames)}, level={self.level}, "
            f"verified={self.verified}, written={[p.name for p in self.written]})"
        )

    def _repr_html_(self) -> str:
        rows = [
            [f.index, f.t, "verified" if f.verified else "FAILED: " + "; ".join(f.failures), len(f.polygons)]
            for f in self.frames
        ]
        return _html_table(["frame", "t", "verdict", "cells"], rows)


def _choice(x: Any) -> Tuple[Optional[str], List[Tuple[str, str]]]:
    """A parameter choice of faces: (template path, exact values); ``None`` or ``"default"`` is
    the default fit, a mapping the exact values by name, a path a template file."""
    if x is None or (isinstance(x, str) and x.strip() == "default"):
        return None, []
    if isinstance(x, Mapping):
        return None, _params(x)
    if isinstance(x, (str, os.PathLike)):
        return os.fspath(x), []
    raise UsageError("E0504", f"{x!r} is not a parameter choice: give None (the default fit), {{name: exact value}} or a template file")


def morph(
    a: Any,
    b: Any,
    *,
    on: Any = None,
    frames: int = 9,
    level: int = 2,
    size: int = 512,
    seconds: float = 0.5,
    svg: Optional[PathLike] = None,
    png: Optional[str] = None,
    max_cells: int = 200_000,
    limits: Limits = None,
) -> Morph:
    """The metamorphosis from ``a`` to ``b`` in ``frames`` frames (both ends included), every
    frame built and checked at ``level`` as ``lacuna morph`` does.

    With ``on`` (faces: a Face, an Assembly or what the command line reads), ``a`` and ``b`` are
    parameter choices of those faces: None or ``"default"`` (the default fit), ``{name: exact
    value}``, or a template file; each frame's holes and components are counted on a raster of
    ``size`` pixels against the exact counts (at most ``max_cells`` cells a frame). Without
    ``on``, ``a`` and ``b`` are two automata of one shape (Automaton objects or sources), moved
    operator by operator. The animated SVG (``size`` pixels wide, ``seconds`` a frame) is
    written to ``svg`` when given, and one PNG per frame (``size`` pixels wide, as ``lacuna morph
    --png``) when ``png`` is a pattern: its ``{}`` becomes the frame number, three digits from
    ``000`` (``"frame-{}.png"``). Neither overwrites an input; ``written`` lists the files."""
    import numpy as np

    if on is None:
        ta, va, tb, vb = _source(a), [], _source(b), []
    else:
        (ta, va), (tb, vb) = _choice(a), _choice(b)
    report, cells, written = _lacuna.morph(
        ta,
        tb,
        va,
        vb,
        None if on is None else _source(on),
        _natural("frames", frames),
        _natural("level", level),
        _natural("size", size),
        float(seconds),
        _path(svg),
        png if png is None else os.fspath(png),
        _natural("max_cells", max_cells),
        _limits(limits),
    )
    d = json.loads(report)
    out: List[MorphFrame] = []
    for f, (types, offsets, xy, closed) in zip(d["frames"], cells):
        pts = np.asarray(xy, dtype=float).reshape(-1, 2)
        out.append(
            MorphFrame(
                index=int(f["index"]),
                t=Fraction(f["t"]),
                verified=bool(f["verified"]),
                failures=list(f["failures"]),
                holes=f.get("holes"),
                components=f.get("components"),
                polygons=[pts[offsets[i] : offsets[i + 1]] for i in range(len(types))],
                types=np.asarray(types, dtype=int),
                closed=np.asarray(closed, dtype=bool),
            )
        )
    moving = d.get("moving_points")
    return Morph(
        name=d["name"],
        level=int(d["level"]),
        changing=int(d["changing"]),
        parameters=int(d["parameters"]),
        moving_points=None if moving is None else (int(moving[0]), int(moving[1])),
        frames=out,
        verified=bool(d["verified"]),
        first_failure=d.get("first_failure"),
        written=[Path(w) for w in written],
    )
