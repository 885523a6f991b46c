"""`lacuna operators` from Python (issue #33): the same report as the command line's `--json`,
and values derived by hand (the de Casteljau operators split at t = 1/2 have eigenvalues 1, 1/2,
1/4)."""

from fractions import Fraction

import pytest

import lacuna

POINTS = "0 0; 1 2; 2 0"


def test_an_automaton_s_operators_are_the_command_line_s(cli):
    code, data = cli("operators", "de-casteljau-edge", "--json")
    assert code == 0
    assert lacuna.load("de-casteljau-edge").operators().data == data


def test_one_operator_and_its_eigenvalues_by_hand(cli):
    r = lacuna.load("de-casteljau-edge").operators(op="e.T0")
    assert r.data == cli("operators", "de-casteljau-edge", "--op", "e.T0", "--json")[1]
    # T0 = [1 1/2 1/4; 0 1/2 1/2; 0 0 1/4] is upper triangular: its diagonal is its spectrum.
    texts = repr(r.data["automaton"])
    for value in ("1/2", "1/4"):
        assert value in texts
    m = lacuna.operators("[1 1/2 1/4; 0 1/2 1/2; 0 0 1/4]")
    values = sorted(Fraction(e["exact"]) for e in m.data["matrices"][0]["eigenvalues"])
    assert values == [Fraction(1, 4), Fraction(1, 2), Fraction(1)]


def test_matrices_by_hand_are_the_command_line_s(cli):
    code, data = cli("operators", "--matrix", "[1 1/2 1/4; 0 1/2 1/2; 0 0 1/4]", "--matrix", "[1/2 0; 0 1/3]", "--json")
    assert code == 0
    rows = [[1, Fraction(1, 2), Fraction(1, 4)], [0, Fraction(1, 2), Fraction(1, 2)], [0, 0, Fraction(1, 4)]]
    assert lacuna.operators(rows, "[1/2 0; 0 1/3]").data == data


def test_curves_with_points_are_the_command_line_s(cli):
    code, data = cli("operators", "de-casteljau-edge", "--points", POINTS, "--at", "3/8", "--json")
    assert code == 0 and data["curves"]
    a = lacuna.load("de-casteljau-edge")
    assert a.operators(points=[[0, 0], [1, 2], [2, 0]], at=["3/8"]).data == data
    assert a.operators(points=POINTS, at=[Fraction(3, 8)]).data == data


def test_a_face_is_instantiated_as_the_command_line_does(cli):
    code, data = cli("operators", "square-B2", "--json")
    assert code == 0
    f = lacuna.load("square-B2")
    assert isinstance(f, lacuna.Face)
    assert f.operators().data == data


def test_errors_are_lacuna_errors_in_python_words():
    a = lacuna.load("de-casteljau-edge")
    with pytest.raises(lacuna.LacunaError) as e:
        a.operators(op="nope")
    assert "nope" in str(e.value)
    with pytest.raises(lacuna.UsageError) as e:
        a.operators(points="0 0; 1 1")
    assert "points=" in str(e.value) and "--points" not in str(e.value)
    with pytest.raises(lacuna.LimitError) as e:
        a.operators(limits={"max_matrix": 2})
    assert "max_matrix" in str(e.value) and "--max" not in str(e.value)
    with pytest.raises(lacuna.LacunaError) as e:
        a.operators(curvature="e.T0", points="0 0; 1 2; 2 0", level=17)
    assert "--level" not in str(e.value)
