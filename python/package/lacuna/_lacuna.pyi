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
) -> Tuple[List[int], List[int], List[float]]:
    """(types, offsets, interleaved x y coordinates) of the cells of the level."""

def automaton_shapes(
    input: str,
    level: int,
    params: _Params = ...,
    max_cells: Optional[int] = None,
    limits: _Limits = None,
) -> Tuple[str, List[str], bool]:
    """(shapes JSON, state names, whether the constraints hold)."""

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
) -> List[Path]:
    """Writes the files asked for; returns their paths."""

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
) -> str:
    """The measures, as `lacuna measure --json`."""
