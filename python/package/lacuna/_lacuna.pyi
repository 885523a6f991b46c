"""Type stubs of the native module `lacuna._lacuna` (built from python/src/lib.rs).

Every function takes an input as the command line names it (face notation, a file path or a
library name). Reports cross as JSON text in the layout of the command line's `--json`; exact
numbers in them are strings. Errors are raised as `lacuna.LacunaError` subclasses.
"""

from os import PathLike
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple, Union

__version__: str

_Limits = Optional[Dict[str, int]]
_Params = Sequence[Tuple[str, str]]
_Path = Optional[Union[str, PathLike[str]]]

def kind(input: str) -> Tuple[str, str]:
    """(``"faces"`` | ``"automaton"`` | ``"volume"``, name); parses the input completely."""

def rule_text(input: str) -> Optional[str]:
    """The rule text an automaton was compiled from; None for a hand-written automaton."""

def start_faces(input: str) -> Tuple[List[str], int]:
    """The canonical notation of each start face of faces, and the number of shared edges."""

def canonical(notation: str) -> str:
    """The canonical notation of one face."""

def library() -> List[Tuple[str, str]]:
    """(name, text) of every named structure."""

def closure(input: str, limits: _Limits = None) -> str:
    """The closure, as `lacuna closure --json`."""

def counts(input: str, levels: int, limits: _Limits = None) -> str:
    """Exact counts per level, as `lacuna counts --json`."""

def ratio(input: str, digits: int, limits: _Limits = None) -> str:
    """The exact limit ratio, as `lacuna ratio --json`."""

def solve(input: str, degree: int = 2, cantor_gap: str = "1", limits: _Limits = None) -> str:
    """The constraint system's solution, as `lacuna solve --json`."""

def verify(input: str, levels: int = 5, limits: _Limits = None) -> str:
    """The whole verification, as `lacuna verify --json`."""

def certificate(input: str, limits: _Limits = None) -> str:
    """The certificate's JSON text."""

def automaton_certificate(input: str, limits: _Limits = None) -> str:
    """An automaton's or a rule's certificate, as JSON text."""

def check_text(text: str) -> Tuple[str, bool, bool]:
    """The checker's report JSON, whether all is proved, whether the certificate is partial."""

def read_text(path: str) -> str:
    """A UTF-8 text file, as lacuna reads its inputs."""

def polygons(
    input: str,
    level: int,
    params: _Params = ...,
    segments: int = 4,
    max_cells: Optional[int] = None,
    limits: _Limits = None,
    corners: Optional[str] = None,
    template: Optional[str] = None,
    goals: List[str] = ...,
) -> Tuple[List[int], List[int], List[float]]:
    """(types, offsets, interleaved x y coordinates) of the cells of the level; faces placed by
    `corners` and chosen by `template` and `goals` (`--corners`, `--template`, `--goal`)."""

def automaton_shapes(
    input: str,
    level: int,
    params: _Params = ...,
    max_cells: Optional[int] = None,
    limits: _Limits = None,
    state: Optional[str] = None,
) -> Tuple[str, List[str], bool]:
    """(shapes JSON, state names, whether the constraints hold); `state` draws that state's
    attractor instead of the start state's."""

def render(
    input: str,
    level: int,
    params: _Params = ...,
    svg: _Path = None,
    png: _Path = None,
    stl: _Path = None,
    stl_ascii: bool = False,
    size: int = 1024,
    legend: bool = True,
    transparent: bool = False,
    width: Optional[float] = None,
    thickness: Optional[float] = None,
    segments: int = 4,
    max_cells: Optional[int] = None,
    limits: _Limits = None,
    corners: Optional[str] = None,
    template: Optional[str] = None,
    goals: List[str] = ...,
    state: Optional[str] = None,
) -> List[Path]:
    """Writes the files asked for; returns their paths (`state`: that state of an automaton
    instead of its start state)."""

def measure(
    input: str,
    level: int,
    params: _Params = ...,
    raster: int = 2048,
    max_raster: int = 8192,
    digits: int = 30,
    width: Optional[float] = None,
    resolution: Optional[float] = None,
    segments: int = 4,
    max_cells: Optional[int] = None,
    limits: _Limits = None,
    corners: Optional[str] = None,
    template: Optional[str] = None,
    goals: List[str] = ...,
    state: Optional[str] = None,
) -> str:
    """The measures, as `lacuna measure --json` (`state`: that state of an automaton)."""

# Volumes and volume assemblies (volume notation, a volume file or a library name of volumes).

def volume_closure(input: str, limits: _Limits = None) -> str:
    """The closure of volume types, as `lacuna closure --json` for a volume."""

def volume_counts_json(input: str, levels: int, limits: _Limits = None) -> str:
    """{"input", "types", "levels": cells, lacunas and R_i per level, "solid": the level-n
    solid's cells, χ, components, voids and tunnels per level}, as `lacuna counts --json`."""

def volume_ratio(input: str, digits: int, limits: _Limits = None) -> str:
    """The exact limit ratio of a volume, as `lacuna ratio --json`."""

def volume_solve(input: str, degree: int = 2, cantor_gap: str = "1", limits: _Limits = None) -> str:
    """The constraint system of the volume states, as `lacuna solve --json`."""

def volume_verify(input: str, levels: int = 5, limits: _Limits = None) -> str:
    """The whole verification of a volume, as `lacuna verify --json`."""

def volume_certificate(input: str, levels: int = 5, limits: _Limits = None) -> str:
    """A volume's certificate (closure, counts, R, the level-n solid for levels 0..levels), as
    JSON text."""

def volume_render(
    input: str,
    level: int,
    targets: Dict[str, Union[str, bool, int, None]],
    width: float = 100.0,
    resolution: float = 0.4,
    strict: bool = False,
    bed: Tuple[float, float, float] = (200.0, 200.0, 200.0),
    layers: int = 20,
    max_cells: Optional[int] = None,
    limits: _Limits = None,
) -> str:
    """Builds and checks the level's solid and writes the files of `targets` (keys `svg`, `png`,
    `stl`, `stl_ascii`, `threemf`, `threemf_style` ("plain", "colours", "parts"), `obj`, `claims`,
    `size`, `transparent`, `orient` ("keep", "auto"), `viewer`); returns JSON: `written`, `notes`,
    `embedded`, `crossing`, `solid`, `printability`, `parts` (flat vertices and triangles),
    `viewer` (the WebGL view's HTML, when asked)."""

def volume_measure(
    input: str,
    level: int,
    width: float = 100.0,
    resolution: float = 0.4,
    strict: bool = False,
    bed: Tuple[float, float, float] = (200.0, 200.0, 200.0),
    layers: int = 20,
    max_cells: Optional[int] = None,
    limits: _Limits = None,
) -> str:
    """The measures of a volume's level-n solid, as `lacuna measure --json`."""

def explore_shard(
    edges: str,
    max_length: int,
    params: str,
    algorithm: str,
    properties: str,
    random: Optional[int],
    seed: int,
    shard: int,
    shards: int,
    shrink_budget: int,
    threads: int,
    limits: _Limits = None,
) -> str:
    """Shard `shard` (from 0) of `shards` of a family, as `lacuna explore --shard i/n --json`:
    JSON `{"results": [...], "summary": {...}}` (the holes property is refused)."""

def census(
    edges: str,
    params: str,
    algorithms: str,
    max_length: int,
    threads: Optional[int] = None,
    limits: _Limits = None,
) -> str:
    """`lacuna census --json` with every face."""

def check_mesh(
    bytes: bytes,
    name: str,
    expect_euler: Optional[int] = None,
    expect_parts: Optional[int] = None,
    claims: Optional[Tuple[str, str]] = None,
    max_triangles: int = 20000000,
) -> str:
    """`lacuna check-mesh --json` on a file's bytes (claims: the claims file's text and name);
    its `passed` says whether every check and expectation held."""

def decode_png(data: bytes) -> Tuple[int, int, bytes]:
    """The pixels of a PNG lacuna wrote: (height, width, RGBA bytes row by row)."""

def operators(
    input: Optional[str] = None,
    matrices: List[str] = ...,
    op: Optional[str] = None,
    points: Optional[str] = None,
    at: List[str] = ...,
    level: int = 8,
    curvature: Optional[str] = None,
    limits: _Limits = None,
) -> str:
    """`lacuna operators [INPUT] --json`: the eigen analysis of the operators of `input` (an
    automaton, or faces instantiated with the default parameters) and of `matrices`."""

def design(eigenvalues: str, eigenvectors: str, check: Optional[str] = None, op: Optional[str] = None) -> str:
    """`lacuna design --json`: T = V·D·V⁻¹ exact (`matrix`), its `analysis` and the `check`
    against an automaton's operator `op`."""

def export(
    input: str,
    format: str = "aut",
    path: Optional[str] = None,
    degree: int = 2,
    cantor_gap: str = "1",
    limits: _Limits = None,
) -> str:
    """`lacuna export INPUT --format F [-o PATH]`: the generated automaton's text."""

def report(
    input: str,
    level: int = 3,
    path: Optional[str] = None,
    params: List[Tuple[str, str]] = ...,
    raster: int = 2048,
    segments: int = 4,
    max_cells: Optional[int] = None,
    limits: _Limits = None,
    corners: Optional[str] = None,
    template: Optional[str] = None,
    goals: List[str] = ...,
) -> Tuple[str, bool]:
    """`lacuna report INPUT --out PATH`: the HTML page of faces, an automaton or volumes and its
    verdict; written to `path` too when given."""

def classify(
    a: str,
    b: str,
    levels: int = 4,
    volume_levels: int = 2,
    max_cells: int = 200000,
    multiplicity: str = "contacts",
    limits: _Limits = None,
) -> str:
    """`lacuna classify A B --json`, with the inputs' `kinds` and the printed `text`."""

def morph(
    a: Optional[str] = None,
    b: Optional[str] = None,
    a_params: List[Tuple[str, str]] = ...,
    b_params: List[Tuple[str, str]] = ...,
    on: Optional[str] = None,
    frames: int = 9,
    level: int = 2,
    size: int = 512,
    seconds: float = 0.5,
    svg: Optional[str] = None,
    png: Optional[str] = None,
    max_cells: int = 200000,
    limits: _Limits = None,
) -> Tuple[str, List[Tuple[List[int], List[int], List[float], List[bool]]], List[Path]]:
    """`lacuna morph A B [--on INPUT] --json`, every frame's cells (types, point offsets, x/y
    interleaved, closed) and the files written: the animated SVG to `svg`, one PNG per frame to
    the pattern `png` (`{}` the frame number) when given."""
