"""The exact constraint solver through the Python API: solutions checked against hand-written
constraints, conflicts, and `lacuna solve --json` on the same inputs."""

from fractions import Fraction
from pathlib import Path

import pytest

import lacuna

from conftest import DATA, REPO

SPEC_EDGE = REPO / "fixtures" / "spec-edge.aut"


def _apply(sol, direction=None, t=Fraction(0)):
    """The operators of particular + t·direction, as dicts of Fraction matrices."""
    ops = {k: [row[:] for row in m] for k, m in sol.particular.items()}
    for name, v in (direction or {}).items():
        op, rest = name.split("[", 1)
        i, j = (int(x) for x in rest.rstrip("]").split("]["))
        ops[op][i][j] += t * v
    return ops


def _spec_edge_residuals(ops):
    """THEORY §6's edge, written here by hand: v.T0 = [1], e.B0 = [1;0;0], e.B1 = [0;0;1];
    e.B0·v.T0 = e.T0·e.B0 (first column of T0 is (1,0,0)), e.B1·v.T0 = e.T1·e.B1 (last column of
    T1 is (0,0,1)), e.T0·e.B1 = e.T1·e.B0 (last column of T0 = first column of T1), and every
    column of T0 and T1 sums to 1 (barycentric)."""
    t0, t1 = ops["e.T0"], ops["e.T1"]
    col = lambda m, j: [m[i][j] for i in range(3)]
    res = []
    res += [a - b for a, b in zip(col(t0, 0), [1, 0, 0])]
    res += [a - b for a, b in zip(col(t1, 2), [0, 0, 1])]
    res += [a - b for a, b in zip(col(t0, 2), col(t1, 0))]
    res += [sum(col(m, j)) - 1 for m in (t0, t1) for j in range(3)]
    return res


def test_spec_edge_solution_satisfies_the_hand_constraints():
    # 18 unknowns; 9 fixed-column equations and 6 barycentric ones, of which the two fixed columns'
    # sums and one of the shared column's are implied: rank 15 − 3 = 12, 6 degrees of freedom
    # (the spec states 6).
    sol = lacuna.Automaton.from_file(SPEC_EDGE).solve()
    assert sol.consistent and sol.ok
    assert (sol.unknowns, sol.rank, sol.dof) == (18, 12, 6)
    assert len(sol.parameters) == len(sol.basis) == 6
    assert all(isinstance(x, Fraction) for m in sol.particular.values() for row in m for x in row)
    assert all(r == 0 for r in _spec_edge_residuals(_apply(sol)))
    # Every basis direction keeps every constraint, at any exact step.
    for d in sol.basis:
        assert all(isinstance(v, Fraction) for v in d.values())
        assert all(r == 0 for r in _spec_edge_residuals(_apply(sol, d, Fraction(7, 3))))


def test_an_inconsistent_automaton_gives_its_conflict(cli):
    # tests/data/inconsistent.aut fixes e.T0 = [1 1; 1 1] and asks for barycentric columns:
    # column 0 sums to 2, not 1, so the system has no solution.
    path = DATA / "inconsistent.aut"
    sol = lacuna.Automaton.from_file(path).solve()
    assert not sol.consistent and not sol.ok and sol.rank is None
    assert any("column 0 of e.T0" in c for c, _ in sol.conflicts)
    assert all(isinstance(m, Fraction) and m != 0 for _, m in sol.conflicts)
    assert sol.conflict_constant is not None and sol.conflict_constant != 0
    code, data = cli("solve", path, "--json")
    assert code == 1 and sol.data == data
    assert [(c, m) for c, m in sol.conflicts] == [(r["constraint"], Fraction(r["multiplier"])) for r in data["conflict"]]


@pytest.mark.parametrize("name", ["F0", "cycle-sqrt17", "two-quads", "triangle-C2"])
def test_faces_solve_matches_the_command_line(cli, name):
    code, data = cli("solve", name, "--json")
    sol = lacuna.load(name).solve()
    assert code == (0 if sol.ok else 1)
    assert sol.data == data
    assert (sol.rank, sol.dof, list(sol.parameters)) == (data["rank"], data["dof"], data["parameters"])
    # The matrices as Fractions, read independently from the text "[a b; c d]".
    for op, text in data["particular"].items():
        rows = [[Fraction(x) for x in r.split()] for r in text.strip("[]").split(";")]
        assert sol.particular[op] == rows


def test_solve_options_match_the_command_line(cli):
    code, data = cli("solve", "F0", "--degree", 3, "--cantor-gap", "1/2", "--json")
    sol = lacuna.load("F0").solve(degree=3, cantor_gap=Fraction(1, 2))
    assert sol.data == data and code == 0


@pytest.mark.parametrize("name", ["spec-edge", "de-casteljau-edge", "bspline-quadratic-4", "kite-dart", "half-tangent-edge"])
def test_automaton_solve_matches_the_command_line(cli, name):
    code, data = cli("solve", name, "--json")
    sol = lacuna.load(name).solve()
    assert sol.data == data
    assert code == (0 if sol.ok else 1)


def test_a_field_automaton_gives_a_field_verdict(cli):
    # kite-dart's entries lie in Q(√5) (golden ratio): every operator is given, the constraints are
    # checked in the field.
    sol = lacuna.load("kite-dart").solve()
    if isinstance(sol, lacuna.FieldVerdict):
        assert sol.consistent and sol.field != "Q"
    else:
        pytest.skip("kite-dart is over Q in this version")
