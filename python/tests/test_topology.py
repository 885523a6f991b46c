"""Faces, closures, counts and limit ratios through the Python API, against hand derivations and
against `lacuna … --json` on the same inputs."""

from fractions import Fraction

import networkx as nx
import numpy as np
import pytest
import sympy

import lacuna

F0 = "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1"
FACE_INPUTS = ["F0", "cycle-sqrt17", "two-quads", "triangle-C2", "square-B2", "delayed-B2-C2", "shared-radius-pentagons"]


def test_face_notation_is_canonical():
    # The canonical form is the least rotation of the boundary with B < C: the rotation of
    # C2 B2 C2 B2 C2 B2 that starts with B2 (THEORY §2); E and the algorithm are kept.
    f = lacuna.Face(F0)
    assert f.notation == "B2 C2 B2 C2 B2 C2 | C2 B2 B2 | A1"
    assert repr(f) == f"Face('{f.notation}')"


def test_f0_closes_on_one_type_with_six_children():
    # THEORY §3: F0 subdivides into 6 sub-faces, each F0 again, with 5 lacunas on shared edges
    # (counted half on each side): contribution 5/2.
    c = lacuna.Face(F0).closure()
    assert c.closed and c.runaway is None
    assert [t.id for t in c.types] == ["T0"]
    assert c.types[0].children == ("T0",) * 6
    assert c.types[0].contribution == Fraction(5, 2)
    assert c.edges == [("T0", "T0", {"count": 6})]
    assert c.matrix() == [[6]]


def test_cycle_sqrt17_type_graph_is_the_hand_matrix():
    # fixtures/cycle-sqrt17.txt derives M = [[3, 2], [2, 4]] by hand (A: three B2→B2 runs give A,
    # two runs give B; B: two give A, four give B) with contributions 3/2 and 2.
    c = lacuna.load("cycle-sqrt17").closure()
    assert c.matrix() == [[3, 2], [2, 4]]
    assert [t.contribution for t in c.types] == [Fraction(3, 2), Fraction(2)]
    g = nx.DiGraph(c.edges)
    assert g["T0"]["T1"]["count"] == 2 and g["T1"]["T1"]["count"] == 4
    g2 = c.graph()
    assert g2.nodes["T1"]["contribution"] == Fraction(2)
    # The Perron root of M, computed independently in floats: (7 + √17)/2.
    rho = max(np.linalg.eigvals(np.array(c.matrix(), dtype=float)).real)
    assert abs(rho - (7 + 17**0.5) / 2) < 1e-12


@pytest.mark.parametrize("name", FACE_INPUTS)
def test_closure_matches_the_command_line(cli, name):
    code, data = cli("closure", name, "--json")
    assert code == 0
    c = lacuna.load(name).closure()
    assert c.data == data
    assert [t.face for t in c.types] == [t["face"] for t in data["types"]]
    assert [t.contribution for t in c.types] == [Fraction(t["contribution"]) for t in data["types"]]


def test_runaway_is_a_result_not_an_error(cli):
    # A closure that does not close is reported (THEORY §4), like `lacuna closure` (exit 1).
    src = "B2 C3 | B2 B2 C3 | {joint}"
    code, data = cli("closure", src, "--json")
    assert code == 1
    c = lacuna.Face(src).closure()
    assert not c.closed and c.runaway is not None
    assert c.data == data
    assert c.runaway.data == data["runaway"] and "reason" in c.runaway


def test_f0_counts_are_powers_of_six_at_level_200():
    # One type with 6 children: N^C_i = 6^i; each subdivision adds 5/2 lacunas per face:
    # N^L_i = 5/2 · (1 + 6 + … + 6^(i−1)) = (6^i − 1)/2; R_i = N^L_i / (N^C_i + N^L_i).
    rows = lacuna.Face(F0).counts(200)
    assert [r.level for r in rows] == list(range(201))
    for r in rows:
        assert isinstance(r.faces, int)
        assert r.faces == 6**r.level
        assert r.lacunas == Fraction(6**r.level - 1, 2)
        assert r.ratio == r.lacunas / (r.faces + r.lacunas)
    assert rows[200].faces.bit_length() > 500  # a Python int, no overflow


@pytest.mark.parametrize("name", FACE_INPUTS)
def test_counts_match_the_command_line(cli, name):
    code, data = cli("counts", name, "--levels", 25, "--json")
    assert code == 0
    rows = lacuna.load(name).counts(25)
    assert [(r.faces, r.lacunas, r.ratio) for r in rows] == [
        (int(d["faces"]), Fraction(d["lacunas"]), Fraction(d["ratio"])) for d in data["levels"]
    ]


def test_f0_ratio_is_one_third():
    # From the counts above: R_i → (1/2)/(1 + 1/2) = 1/3.
    r = lacuna.Face(F0).ratio()
    assert r.exists and r.rational and r.value == Fraction(1, 3)
    assert r.exact == "1/3" and r.perron_root == "6"
    assert r.decimal == "0." + "3" * 30
    assert r.sympy() == sympy.Rational(1, 3)


def test_cycle_sqrt17_ratio_is_exact_in_sympy():
    # fixtures/cycle-sqrt17.txt: ρ = (7 + √17)/2 and R = (√17 − 3)/4 (derived by hand in
    # tests/ratio.rs); the coordinates (a, b) on the basis (1, ρ) give the same number:
    # −5/2 + ρ/2 = −5/2 + 7/4 + √17/4 = (√17 − 3)/4.
    r = lacuna.load("cycle-sqrt17").ratio(digits=40)
    assert r.exists and r.quadratic and not r.rational and r.value is None
    expected = (sympy.sqrt(17) - 3) / 4
    assert sympy.simplify(sympy.sympify(r.exact) - expected) == 0
    assert sympy.simplify(r.sympy() - expected) == 0
    a, b = r.coordinates
    assert sympy.simplify(sympy.Rational(a.numerator, a.denominator) + sympy.Rational(b.numerator, b.denominator) * r.rho() - expected) == 0
    assert sympy.simplify(r.rho() - (7 + sympy.sqrt(17)) / 2) == 0
    # Certified decimals are truncated: they agree with SymPy's 60-digit value.
    assert str(sympy.N(expected, 60)).startswith(r.decimal)
    assert len(r.decimal.split(".")[1]) == 40


@pytest.mark.parametrize("name", FACE_INPUTS)
def test_ratio_matches_the_command_line(cli, name):
    code, data = cli("ratio", name, "--digits", 20, "--json")
    assert code == 0
    r = lacuna.load(name).ratio(digits=20)
    assert r.data == data
    assert r.exists == data["exists"] and r.exact == data["exact"]
    if data["coordinates"] is not None:
        assert list(r.coordinates) == [Fraction(c) for c in data["coordinates"]]
    assert [p.exact for p in r.limit_points] == [p["exact"] for p in data["limit_points"]]


def test_sympy_of_a_higher_degree_ratio_agrees_with_its_decimals():
    # Whatever the degree of ρ, .sympy() is the polynomial on the coordinates in the exact root
    # of the minimal polynomial; its value agrees with the certified decimals.
    for name in FACE_INPUTS:
        r = lacuna.load(name).ratio(digits=25)
        if r.exists:
            assert str(sympy.N(r.sympy(), 40)).startswith(r.decimal[:-1]), name


def test_verify_matches_the_command_line(cli):
    code, data = cli("verify", "F0", "--levels", 4, "--json")
    assert code == 0
    rep = lacuna.load("F0").verify(levels=4)
    assert rep.verified is True
    assert rep.data == data


def test_sympy_conversion_of_a_cubic_ratio():
    # The conversion on data in the layout of `lacuna ratio --json` (no face of the fixtures has a
    # cubic ρ): ρ the real root of x³ − 2 = ∛2, R = 1/2 − ρ/4 + ρ²/8 on the power basis.
    rho = sympy.cbrt(2)
    data = {
        "exists": True,
        "exact": "1/2 - 1/4*rho + 1/8*rho^2 where rho = root of x^3 - 2 in [1, 2]",
        "decimal": None,
        "coordinates": ["1/2", "-1/4", "1/8"],
        "perron_root": "root of x^3 - 2 in [1, 2]",
        "perron_decimal": "1.25992104989487316476",
        "perron_min_poly": "x^3 - 2",
        "period": 1,
        "limit_points": [],
        "reasons": [],
    }
    r = lacuna._ratio(data)
    assert r.degree == 3 and not r.quadratic and not r.rational
    assert sympy.simplify(r.rho() - rho) == 0
    assert sympy.simplify(r.sympy() - (sympy.Rational(1, 2) - rho / 4 + rho**2 / 8)) == 0
