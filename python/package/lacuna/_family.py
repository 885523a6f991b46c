"""Families of faces: property-based exploration on one machine or many, the census of
closures, and the independent mesh checker.

:func:`explore` splits a family into shards exactly as ``lacuna explore --shard i/n`` does
(boundary k of the family belongs to shard k mod n) and runs them on any
:class:`concurrent.futures.Executor` — a ``ProcessPoolExecutor``, or Dask's
``Client.get_executor()`` for a cluster — then merges the shards: the merged results are those
of one run, whatever the number of shards or workers.
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

from . import _lacuna
from . import _natural, _limits, _html_table, Record, Limits, PathLike


def _explore_shard(args: Mapping[str, Any], shard: int, shards: int) -> Dict[str, Any]:
    """One shard of an exploration (module level, so that executors can pickle it)."""
    return json.loads(_lacuna.explore_shard(shard=shard, shards=shards, **args))


class Exploration:
    """The merged result of :func:`explore`.

    ``results`` has one :class:`Record` per boundary of the family, in the family's order, as
    ``lacuna explore --json`` prints them (``index``, ``face``, ``refused``, ``types``,
    ``ratio``, ``failures`` with their shrunk minimal counterexamples); ``summary`` counts them
    like the command line's summary line; ``counterexamples`` lists the distinct minimal
    counterexamples with the property each breaks.
    """

    def __init__(self, shards: List[Dict[str, Any]]):
        results = [r for s in shards for r in s["results"]]
        results.sort(key=lambda r: r["index"])
        self.shards = len(shards)
        self.results: List[Record] = [Record(r) for r in results]
        total: Dict[str, Any] = {
            "shards": len(shards),
            "boundaries": 0,
            "passed": 0,
            "failed": 0,
            "refused": 0,
            "limit": 0,
            "failures": {},
        }
        for s in shards:
            summary = s["summary"]
            for k in ("boundaries", "passed", "failed", "refused", "limit"):
                total[k] += summary[k]
            for p, n in summary["failures"].items():
                total["failures"][p] = total["failures"].get(p, 0) + n
        seen = []
        for r in results:
            for f in r.get("failures", []):
                key = (f["shrunk"]["face"], f["property"])
                if key not in seen:
                    seen.append(key)
        self.counterexamples: List[Tuple[str, str]] = seen
        total["counterexamples"] = [list(c) for c in seen]
        self.summary = Record(total)

    @property
    def ok(self) -> bool:
        """Whether every property held on every boundary."""
        return self.summary.failed == 0

    def dataframe(self):
        """The results as a pandas DataFrame (one row per boundary; needs pandas)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Exploration.dataframe() needs pandas: pip install pandas") from e
        rows = []
        for r in self.results:
            d = r.data
            rows.append(
                {
                    "index": d["index"],
                    "face": d["face"],
                    "refused": d.get("refused"),
                    "types": d.get("types"),
                    "ratio": d.get("ratio"),
                    "failures": ",".join(f["property"] for f in d.get("failures", [])),
                }
            )
        return pd.DataFrame(rows)

    def __len__(self) -> int:
        return len(self.results)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"Exploration({s.boundaries} faces in {self.shards} shard"
            f"{'' if self.shards == 1 else 's'}: {s.passed} pass, {s.failed} fail, "
            f"{s.refused} refused, {s.limit} stopped by a limit)"
        )

    def _repr_html_(self) -> str:
        s = self.summary
        head = _html_table(
            ["faces", "pass", "fail", "refused", "stopped by a limit"],
            [[s.boundaries, s.passed, s.failed, s.refused, s.limit]],
        )
        if not self.counterexamples:
            return head
        return head + _html_table(
            ["minimal counterexample", "property"], [list(c) for c in self.counterexamples]
        )


def explore(
    edges: str = "B2,C2",
    max_length: int = 4,
    params: str = "C2,B2",
    algorithm: str = "A1",
    properties: str = "closes,consistent,no-collapse,ratio",
    *,
    random: Optional[int] = None,
    seed: int = 0,
    shrink_budget: int = 400,
    shards: int = 1,
    executor=None,
    threads: Optional[int] = None,
    holes_level: int = 2,
    max_holes_cells: int = 8192,
    limits: Limits = None,
) -> Exploration:
    """Checks properties on every face of a family (``lacuna explore``): boundaries of the
    ``edges`` up to ``max_length``, every combination of ``params`` for Ea, El, Ec, the
    ``algorithm``; ``random=N`` samples N boundaries (seeded). Properties: ``closes``,
    ``consistent``, ``no-collapse``, ``ratio``, ``certificate`` and ``holes`` (each face placed
    and measured up to ``holes_level``: the observed holes must equal the exact ones; its work,
    the family's faces times 4^level, is checked against ``max_holes_cells`` before anything
    runs). A failure is shrunk to a minimal counterexample.

    ``shards=n`` splits the family as ``--shard i/n`` does; with an ``executor`` (any
    :class:`concurrent.futures.Executor`) the shards run on it, else one after the other here.
    The merged :class:`Exploration` is the same for every ``shards`` and executor.
    """
    shards = _natural("shards", shards)
    if shards < 1:
        from ._errors import UsageError

        raise UsageError("E0503", "shards must be at least 1")
    args = {
        "edges": edges,
        "max_length": _natural("max_length", max_length),
        "params": params,
        "algorithm": algorithm,
        "properties": properties,
        "random": None if random is None else _natural("random", random),
        "seed": _natural("seed", seed),
        "shrink_budget": _natural("shrink_budget", shrink_budget),
        "threads": _natural("threads", threads) if threads is not None else (os.cpu_count() or 1),
        "holes_level": _natural("holes_level", holes_level),
        "max_holes_cells": _natural("max_holes_cells", max_holes_cells),
        "limits": _limits(limits),
    }
    if executor is None:
        parts = [_explore_shard(args, i, shards) for i in range(shards)]
    else:
        futures = [executor.submit(_explore_shard, args, i, shards) for i in range(shards)]
        parts = [f.result() for f in futures]
    return Exploration(parts)


def census(
    edges: str = "B2,C2,B3,C3",
    params: str = "B2,C2",
    algorithms: str = "A1,A2",
    max_length: int = 6,
    *,
    threads: Optional[int] = None,
    limits: Limits = None,
) -> Record:
    """The closures of a whole family (``lacuna census --json``, with its defaults): how many
    close, run away or are
    refused, the distribution of type counts, the largest closure, and ``per_face`` (every face
    with its verdict, type count and exact R)."""
    return Record(
        json.loads(
            _lacuna.census(
                edges,
                params,
                algorithms,
                _natural("max_length", max_length),
                None if threads is None else _natural("threads", threads),
                _limits(limits),
            )
        )
    )


def check_mesh(
    path: PathLike,
    *,
    expect_euler: Optional[int] = None,
    expect_parts: Optional[int] = None,
    claims: Optional[PathLike] = None,
    max_triangles: int = 20_000_000,
) -> Record:
    """The independent mesh checker (``lacuna check-mesh --json``) on an STL or 3MF file: closed
    and oriented, every vertex link one cycle, no two triangles crossing (exact predicates on the
    file's coordinates), parts with V, E, F, χ and genus; ``expect_euler``, ``expect_parts`` and
    a ``claims`` file written by ``render(..., claims=...)`` are compared. The record's
    ``passed`` says whether every check and expectation held."""
    p = os.fspath(path)
    with open(p, "rb") as f:
        data = f.read()
    claim = None
    if claims is not None:
        c = os.fspath(claims)
        claim = (_lacuna.read_text(c), c)
    text = _lacuna.check_mesh(
        data, p, expect_euler, expect_parts, claim, _natural("max_triangles", max_triangles)
    )
    return Record(json.loads(text))
