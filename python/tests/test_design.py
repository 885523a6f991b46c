"""`lacuna design` from Python (issue #33): the exact T = V·D·V⁻¹, its analysis and the check
against an automaton, the same as the command line's `--json`."""

from fractions import Fraction as F

import pytest

import lacuna

VECTORS = "[1 0 0; -1 1 0; 1 -2 1]"


def test_the_de_casteljau_operator_from_its_eigenvalues():
    # The eigenvectors of the de Casteljau split T0 (rows) with eigenvalues 1, 1/2, 1/4 give T0
    # back: V^T D (V^T)^-1 worked by hand.
    d = lacuna.design([1, F(1, 2), F(1, 4)], [[1, 0, 0], [-1, 1, 0], [1, -2, 1]])
    assert d.matrix == [[1, F(1, 2), F(1, 4)], [0, F(1, 2), F(1, 2)], [0, 0, F(1, 4)]]
    assert all(isinstance(x, F) for row in d.matrix for x in row)
    assert sorted(F(e["exact"]) for e in d.analysis.data["eigenvalues"]) == [F(1, 4), F(1, 2), 1]
    assert d.check is None and d.ok


def test_the_same_json_as_the_command_line(cli):
    code, data = cli("design", "--eigenvalues", "1 1/4 1/8", "--eigenvectors", VECTORS, "--json")
    assert code == 0
    d = lacuna.design("1 1/4 1/8", VECTORS)
    assert d.data == data
    assert d.matrix == [[1, F(3, 4), F(5, 8)], [0, F(1, 4), F(1, 4)], [0, 0, F(1, 8)]]


@pytest.mark.parametrize("values", ["1 1/2 1/4", "1 1/4 1/8"])
def test_a_check_against_an_automaton_is_the_command_line_s(cli, values):
    code, data = cli("design", "--eigenvalues", values, "--eigenvectors", VECTORS, "--check", "de-casteljau-edge", "--op", "e.T0", "--json")
    d = lacuna.design(values, VECTORS, check=lacuna.load("de-casteljau-edge"), op="e.T0")
    assert d.data == data
    assert d.ok == (code == 0)
    assert d.check.operator == "e.T0"
    # T0 itself is valid; 1, 1/4, 1/8 breaks the adjacency T0 B1 = T1 B0 (exit 1).
    assert d.ok == (values == "1 1/2 1/4")


def test_errors_are_lacuna_errors():
    with pytest.raises(lacuna.LacunaError):
        lacuna.design("1 1", VECTORS)  # two eigenvalues, three eigenvectors
    with pytest.raises(lacuna.LacunaError):
        lacuna.design("1 1/2 1/4", "[1 0 0; 2 0 0; 0 0 1]")  # not independent
    with pytest.raises(lacuna.UsageError):
        lacuna.design("1 1/2 1/4", VECTORS, check="F0", op="e.T0")
    with pytest.raises(lacuna.UsageError):
        lacuna.design("1 1/2 1/4", VECTORS, op="e.T0")
