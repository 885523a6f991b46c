"""Volumes and volume assemblies from Python (THEORY §10): :class:`Volume` and its results.

A volume is given as the command line reads it: volume notation
(``Volume("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1")``: solid and edge type | E | A | G | rule
[| delay]), a volume file (``volume NAME { … }`` blocks, volumes glued face to face) or a library
name (``cube-B2``, ``tetrahedron-B2``, ``two-cubes``, …). Exact results are Python objects, as for
faces: cells as ``int``, lacunas and ratios as ``fractions.Fraction`` (lacunas are multiples of
1/4: a cavity counts 1, a hole or gap in a face is shared by the two cells on it), R as a
:class:`Ratio`.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple, Union

from . import (
    Certificate,
    Limits,
    PathLike,
    Ratio,
    Record,
    Solution,
    _html_table,
    _lacuna,
    _limits,
    _natural,
    _path,
    _png_bytes,
    _ratio,
    _solution,
)
from ._errors import UsageError


def _int(text: Optional[Union[str, int]]) -> Optional[int]:
    """An exact integer written by lacuna (a string of any size, or a JSON number) as an int."""
    return None if text is None else int(text)


def _max_cells(value: Optional[int]) -> Optional[int]:
    return None if value is None else _natural("max_cells", value)


@dataclass(frozen=True)
class VolumeType:
    """One volume type of a closure.

    Attributes:
        id: ``"V0"``, ``"V1"``, … (start types first).
        faces, corners, edges: the cells of its boundary surface (a sphere).
        surface: its faces by notation, ``"6×(B2 B2 B2 B2)"``.
        delay: its delay.
        contribution: the lacunas it contributes per subdivision (multiples of 1/4).
        children: the type of each sub-volume, in order.
    """

    id: str
    faces: int
    corners: int
    edges: int
    surface: str
    delay: int
    contribution: Fraction
    children: Tuple[str, ...]


def _kids(children: Tuple[str, ...]) -> str:
    """Sub-volumes by type: ``16×V1 + 3×V2``."""
    seen: Dict[str, int] = {}
    for c in children:
        seen[c] = seen.get(c, 0) + 1
    return " + ".join(f"{k}×{c}" for c, k in seen.items())


@dataclass(frozen=True)
class VolumeClosure:
    """The closure of the start volumes under subdivision.

    Attributes:
        closed: True when the recursion closes; False for a runaway (see ``runaway``). No bound
            is proved for volumes: the closure is checked against the limits ``max_types`` and
            ``max_boundary``.
        types: the volume types.
        start: the type of each start volume.
        runaway: the witness chain and the reason, when it did not close.
        data: the whole report as ``lacuna closure --json`` prints it.
    """

    closed: bool
    types: Tuple[VolumeType, ...]
    start: Tuple[str, ...]
    runaway: Optional[Record]
    data: Dict[str, Any] = field(repr=False, compare=False)

    def __repr__(self) -> str:
        if not self.closed:
            return "VolumeClosure(closed=False)"
        return f"VolumeClosure(closed=True, types={len(self.types)}, start={list(self.start)})"

    @property
    def edges(self) -> List[Tuple[str, str, Dict[str, int]]]:
        """The type graph as a networkx-compatible edge list: ``(V_i, V_j, {"count": k})`` when
        k sub-volumes of V_i are of type V_j."""
        out = []
        for t in self.types:
            seen: Dict[str, int] = {}
            for c in t.children:
                seen[c] = seen.get(c, 0) + 1
            out.extend((t.id, c, {"count": k}) for c, k in seen.items())
        return out

    def matrix(self) -> List[List[int]]:
        """The substitution matrix: ``M[i][j]`` sub-volumes of type j in type i."""
        index = {t.id: i for i, t in enumerate(self.types)}
        m = [[0] * len(self.types) for _ in self.types]
        for i, t in enumerate(self.types):
            for c in t.children:
                m[i][index[c]] += 1
        return m

    def _repr_html_(self) -> str:
        """A table of the volume types in a notebook: surface, sub-volumes by type, contribution."""
        if not self.closed:
            return f"<p>The closure does not close: {self.runaway!r}</p>"
        rows = [
            [t.id, f"{t.faces} faces, {t.corners} corners, {t.edges} edges", t.surface, t.delay, _kids(t.children), t.contribution]
            for t in self.types
        ]
        n = len(self.types)
        head = f"<p>closed: {n} volume type{'' if n == 1 else 's'}, start {', '.join(self.start)}</p>"
        return head + _html_table(["type", "boundary", "faces", "delay", "sub-volumes", "contribution"], rows)


@dataclass(frozen=True)
class VolumeLevelCount:
    """Exact counts at one level: ``cells`` = N^C_i (an int), ``lacunas`` = N^L_i (a Fraction, a
    multiple of 1/4) and ``ratio`` = R_i = N^L_i / (N^L_i + N^C_i) (a Fraction)."""

    level: int
    cells: int
    lacunas: Fraction
    ratio: Fraction


class VolumeCounts(list):
    """The counts of levels 0..n (a list of :class:`VolumeLevelCount`), shown as a table in a
    notebook."""

    def _repr_html_(self) -> str:
        rows = [[c.level, c.cells, c.lacunas, c.ratio, f"{float(c.ratio):.6f}"] for c in self]
        return _html_table(["level", "cells N^C", "lacunas N^L", "R_i", "R_i ≈"], rows)


@dataclass(frozen=True)
class SolidLevel:
    """The exact topology of the level-n solid (the union of the level-n sub-volumes).

    Attributes:
        volumes, faces, edges, corners: its cells.
        euler: χ = corners − edges + faces − volumes.
        components: connected components b0, where derived (else None).
        voids: enclosed cavities b2, where derived.
        tunnels: b1 = b0 + b2 − χ, where b0 and b2 are derived.
    """

    level: int
    volumes: int
    faces: int
    edges: int
    corners: int
    euler: int
    components: Optional[int]
    voids: Optional[int]
    tunnels: Optional[int]


def _solid_level(d: Dict[str, Any]) -> SolidLevel:
    return SolidLevel(
        level=int(d["level"]),
        volumes=int(d["volumes"]),
        faces=int(d["faces"]),
        edges=int(d["edges"]),
        corners=int(d["corners"]),
        euler=int(d["euler"]),
        components=_int(d.get("components")),
        voids=_int(d.get("voids")),
        tunnels=_int(d.get("tunnels")),
    )


class SolidTopology(list):
    """The level-n solid of levels 0..n (a list of :class:`SolidLevel`), shown as a table in a
    notebook (– where not derived)."""

    def _repr_html_(self) -> str:
        dash = lambda v: "–" if v is None else v  # noqa: E731
        rows = [
            [s.level, s.volumes, s.faces, s.edges, s.corners, s.euler, dash(s.components), dash(s.voids), dash(s.tunnels)]
            for s in self
        ]
        return _html_table(["level", "volumes", "faces", "edges", "corners", "χ", "components", "voids", "tunnels"], rows)


@dataclass
class VolumeRendering:
    """The level-n solid of a volume as built: one closed triangle mesh per connected component,
    in millimetres (``vertices[k]`` an (n, 3) float array, ``triangles[k]`` an (m, 3) int array of
    vertex indices, counter-clockwise seen from outside), checked against the exact topology.

    Attributes:
        level: the level.
        solid: its exact topology (:class:`SolidLevel`).
        embedded: no two triangles cross (the mesh files are written only then).
        crossing: where two triangles cross, when they do.
        written: the files written.
        notes: what the command line says on its way (the mesh check, sizes, orientation).
        printability: the printability of the mesh written (a Record, as ``render --json`` has
            it), when a mesh file was asked for.
        viewer: with ``render(..., viewer=True)`` (or :meth:`Volume.view`), the HTML fragment of
            the report's rotating WebGL view (a canvas and its script, no server); a notebook
            shows it inline.
    """

    level: int
    solid: SolidLevel
    vertices: List[Any]
    triangles: List[Any]
    embedded: bool
    crossing: Optional[str]
    written: List[Path]
    notes: str
    printability: Optional[Record]
    viewer: Optional[str] = None

    def __len__(self) -> int:
        return len(self.vertices)

    def _repr_html_(self) -> Optional[str]:
        """The WebGL view when it was asked for (drag to rotate); else none, and a notebook shows
        the ``repr``."""
        return self.viewer

    def __repr__(self) -> str:
        n = sum(len(t) for t in self.triangles)
        files = [p.name for p in self.written]
        return f"VolumeRendering(level={self.level}, parts={len(self.vertices)}, triangles={n}, embedded={self.embedded}, written={files})"

    def plot(self, ax=None, colour: str = "#6c9bd2", edgecolor: str = "black", linewidth: float = 0.1):
        """Draws the mesh on a matplotlib 3D axis; returns the axis. Needs matplotlib."""
        import matplotlib.pyplot as plt
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        if ax is None:
            ax = plt.figure().add_subplot(projection="3d")
        for v, t in zip(self.vertices, self.triangles):
            ax.add_collection3d(Poly3DCollection(v[t], facecolors=colour, edgecolors=edgecolor, linewidths=linewidth))
        if self.vertices:
            import numpy as np

            pts = np.concatenate(self.vertices)
            lo, hi = pts.min(axis=0), pts.max(axis=0)
            ax.set_xlim(lo[0], hi[0])
            ax.set_ylim(lo[1], hi[1])
            ax.set_zlim(lo[2], hi[2])
            ax.set_box_aspect(tuple(max(h - l, 1e-9) for l, h in zip(lo, hi)))
        return ax


class Volume:
    """A volume or volumes glued face to face: volume notation
    (``Volume("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1")``), a volume file or a library name
    (``cube-B2``, ``two-cubes``). Raises :class:`InputError` with the code and span of a bad
    token, as the command line does."""

    source: str
    name: str

    def __init__(self, source: PathLike):
        s = os.fspath(source)
        kind, name = _lacuna.kind(s)
        if kind != "volume":
            what = "faces" if kind == "faces" else f"an {kind}"
            raise UsageError("E0504", f"`{s}` is {what}, not a volume: use lacuna.load()")
        self.source = s
        self.name = name

    @classmethod
    def from_file(cls, path: PathLike) -> "Volume":
        """Reads a volume file."""
        p = os.fspath(path)
        if not os.path.isfile(p):
            _lacuna.read_text(p)  # raises FileError (E0601) with lacuna's message
        return cls(p)

    def __repr__(self) -> str:
        return f"Volume({self.name!r})"

    def closure(self, *, limits: Limits = None) -> VolumeClosure:
        """Every volume type the recursion produces, with its surface, delay, contribution and
        sub-volumes; a runaway is a result (``closed`` False), not an error."""
        d = json.loads(_lacuna.volume_closure(self.source, _limits(limits)))
        closed = bool(d.get("closed"))
        types = tuple(
            VolumeType(
                id=f"V{i}",
                faces=int(t["faces"]),
                corners=int(t["corners"]),
                edges=int(t["edges"]),
                surface=t["surface"],
                delay=int(t["delay"]),
                contribution=Fraction(t["contribution"]),
                children=tuple(f"V{c}" for c in t.get("children", [])),
            )
            for i, t in enumerate(d.get("types", []))
        )
        return VolumeClosure(
            closed=closed,
            types=types,
            start=tuple(f"V{s}" for s in d.get("start", [])),
            runaway=None if closed else Record(d.get("runaway") or {}),
            data=d,
        )

    def _counts(self, levels: int, limits: Limits) -> Dict[str, Any]:
        return json.loads(_lacuna.volume_counts_json(self.source, _natural("levels", levels), _limits(limits)))

    def counts(self, levels: int, *, limits: Limits = None) -> VolumeCounts:
        """Exact counts for levels 0..levels: N^C_i (int), N^L_i and R_i (Fractions)."""
        d = self._counts(levels, limits)
        return VolumeCounts(
            VolumeLevelCount(int(r["level"]), int(r["cells"]), Fraction(r["lacunas"]), Fraction(r["ratio"]))
            for r in d["levels"]
        )

    def solid(self, levels: int, *, limits: Limits = None) -> SolidTopology:
        """The exact topology of the level-n solid for n = 0..levels: volumes, faces, edges,
        corners, χ, components, voids and tunnels (None where lacuna does not derive them)."""
        d = self._counts(levels, limits)
        return SolidTopology(_solid_level(s) for s in d["solid"])

    def ratio(self, digits: int = 30, *, limits: Limits = None) -> Ratio:
        """The exact limit ratio R of lacunas against sub-volumes, by eigen analysis of the volume
        types' matrix, with ``digits`` certified decimals."""
        return _ratio(json.loads(_lacuna.volume_ratio(self.source, _natural("digits", digits), _limits(limits))))

    def solve(self, degree: int = 2, cantor_gap: Union[str, int, Fraction] = 1, *, limits: Limits = None) -> Solution:
        """The exact constraint system of the volume states (THEORY §10; faces shared between
        volumes read from both sides) with Bézier degree ``degree`` and Cantor gap/piece
        ``cantor_gap``: unknowns, equations, rank, degrees of freedom, or the conflicting
        constraints."""
        d = json.loads(_lacuna.volume_solve(self.source, _natural("degree", degree), str(cantor_gap), _limits(limits)))
        return _solution(d)  # type: ignore[return-value]

    def verify(self, levels: int = 5, *, limits: Limits = None) -> Record:
        """The whole verification as ``lacuna verify --json`` reports it for a volume: the closure,
        every sub-volume's boundary a sphere (``failures``), counts, the level-n solid, R and the
        constraints (``solver``; ``constraints_undecided`` when a limit stopped the solve);
        ``.verified`` is the verdict."""
        return Record(json.loads(_lacuna.volume_verify(self.source, _natural("levels", levels), _limits(limits))))

    def certificate(self, path: Optional[PathLike] = None, *, levels: int = 5, limits: Limits = None) -> Certificate:
        """The certificate of the closure, the counts, R and the level-n solid's cells and ranks
        over F2 for levels 0..``levels`` (the file ``lacuna verify NAME --certificate`` writes);
        written to ``path`` when given. :func:`check` and :meth:`Certificate.check` re-verify it."""
        c = Certificate(_lacuna.volume_certificate(self.source, _natural("levels", levels), _limits(limits)))
        if path is not None:
            c.write(path)
        return c

    #: The level and width in pixels of the picture a notebook shows (``_repr_png_``).
    display = (1, 480)

    def _repr_png_(self) -> bytes:
        """The picture a notebook shows: the shaded level-``display[0]`` solid, ``display[1]``
        pixels wide (``render(..., png=...)``)."""
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
        threemf: Optional[PathLike] = None,
        threemf_colours: bool = False,
        threemf_parts: bool = False,
        obj: Optional[PathLike] = None,
        claims: Optional[PathLike] = None,
        size: int = 1024,
        transparent: bool = False,
        width: float = 100.0,
        resolution: float = 0.4,
        strict: bool = False,
        bed: Tuple[float, float, float] = (200.0, 200.0, 200.0),
        orient: str = "keep",
        layers: int = 20,
        max_cells: Optional[int] = None,
        viewer: bool = False,
        limits: Limits = None,
    ) -> VolumeRendering:
        """Builds the level-``level`` solid on its default placement (or the corners its file
        gives), checks it against the exact topology, and returns its mesh; writes what is asked
        as ``lacuna render`` does: a shaded PNG (``size`` pixels), an SVG projection, and — only
        when no two triangles cross (else :class:`GeometryError` E1041) — STL (``stl_ascii``), 3MF
        (``threemf_colours``: a material per volume type; ``threemf_parts``: one part per type),
        OBJ, and the claims for :func:`check_mesh`-style re-checking (``claims``). ``width`` in mm
        scales the solid; ``resolution``, ``layers``, ``strict``, ``bed`` and ``orient``
        (``"keep"`` or ``"auto"``) are the command line's print options. A folding solid drawn only
        as pictures gives a warning (``embedded`` False)."""
        import warnings

        import numpy as np

        if threemf_colours and threemf_parts:
            raise UsageError("E0504", "threemf_colours and threemf_parts exclude each other: give one")
        targets = {
            "svg": _path(svg),
            "png": _path(png),
            "stl": _path(stl),
            "stl_ascii": bool(stl_ascii),
            "threemf": _path(threemf),
            "threemf_style": "colours" if threemf_colours else "parts" if threemf_parts else "plain",
            "obj": _path(obj),
            "claims": _path(claims),
            "size": _natural("size", size),
            "transparent": bool(transparent),
            "orient": str(orient),
            "viewer": bool(viewer),
        }
        d = json.loads(
            _lacuna.volume_render(
                self.source,
                _natural("level", level),
                targets,
                float(width),
                float(resolution),
                bool(strict),
                tuple(float(x) for x in bed),
                _natural("layers", layers),
                _max_cells(max_cells),
                _limits(limits),
            )
        )
        if not d["embedded"]:
            warnings.warn(f"{self.name} level {level}: {d['crossing']}", stacklevel=2)
        return VolumeRendering(
            level=int(d["level"]),
            solid=_solid_level(d["solid"]),
            vertices=[np.asarray(p["vertices"], dtype=float).reshape(-1, 3) for p in d["parts"]],
            triangles=[np.asarray(p["triangles"], dtype=np.int64).reshape(-1, 3) for p in d["parts"]],
            embedded=bool(d["embedded"]),
            crossing=d.get("crossing"),
            written=[Path(w) for w in d["written"]],
            notes="".join(d["notes"]),
            printability=Record(d["printability"]) if d.get("printability") else None,
            viewer=d.get("viewer"),
        )

    def view(self, level: int = 1, *, max_cells: Optional[int] = None, limits: Limits = None) -> VolumeRendering:
        """The level-``level`` solid with the rotating WebGL view of ``lacuna report``, which a
        notebook shows inline (no server, no file): ``v.view(2)`` as the last line of a cell."""
        return self.render(level, viewer=True, max_cells=max_cells, limits=limits)

    def measure(
        self,
        level: int,
        *,
        width: float = 100.0,
        resolution: float = 0.4,
        strict: bool = False,
        bed: Tuple[float, float, float] = (200.0, 200.0, 200.0),
        layers: int = 20,
        max_cells: Optional[int] = None,
        limits: Limits = None,
    ) -> Record:
        """The exact topology of the level, the checked mesh (parts, triangles, surface Euler
        characteristic, genus, embedded), its sizes in mm and the printability against
        ``resolution``, as ``lacuna measure --json`` reports them; ``.verified`` is the verdict."""
        return Record(
            json.loads(
                _lacuna.volume_measure(
                    self.source,
                    _natural("level", level),
                    float(width),
                    float(resolution),
                    bool(strict),
                    tuple(float(x) for x in bed),
                    _natural("layers", layers),
                    max_cells,
                    _limits(limits),
                )
            )
        )

    def report(
        self,
        path: Optional[PathLike] = None,
        level: int = 3,
        *,
        max_cells: Optional[int] = None,
        limits: Limits = None,
    ) -> Union[Path, str]:
        """The self-contained HTML report ``lacuna report`` writes: the closure, the exact solid
        of levels 0 to ``level`` (at least 3), the level-``level`` mesh checked against the exact
        topology (at most ``max_cells`` faces, 400 000 by default) with its sizes, a rotating
        WebGL view and an SVG projection. Written to ``path`` (never over the input), which is
        returned; with ``path`` None the HTML text is returned instead."""
        from ._commands import _report

        return _report(self.source, path, level, None, 2048, 4, max_cells, limits)
