"""Automata through the Python API: the attractor's pieces, its measures and dimension."""

import math
import struct

import numpy as np
import pytest

import lacuna

from conftest import REPO


def test_sierpinski_level_3_has_27_triangles(tmp_path):
    # Three maps of ratio 1/2: 3³ = 27 triangles of side 1/8 at level 3.
    a = lacuna.Automaton.from_file(REPO / "fixtures" / "sierpinski-triangle.aut")
    s = a.render(3)
    assert len(s) == 27 and set(s.kinds) == {"polygon"} and s.consistent
    assert s.space == 2 and all(p.shape == (3, 2) for p in s.points)
    sides = [np.linalg.norm(p[1] - p[0]) for p in s.points]
    # The file's start triangle has side 1 (points 0 0, 1 0, 1/2 0.433): each piece has side 1/8.
    assert all(abs(x - 1 / 8) < 1e-9 for x in sides)


def test_automaton_shapes_match_the_command_line(cli, tmp_path):
    import json

    out = tmp_path / "b.json"
    code, _ = cli("render", "bspline-quadratic-4", "--level", 3, "--json-out", out)
    data = json.loads(out.read_text())
    s = lacuna.load("bspline-quadratic-4").render(3)
    assert code == 0 and len(s) == len(data["shapes"])
    assert s.kinds == [x["kind"] for x in data["shapes"]]
    for x, p in zip(data["shapes"], s.points):
        assert np.array(x["points"]).shape == p.shape and np.allclose(np.array(x["points"]), p)


def test_similarity_dimension_of_sierpinski_is_log3_over_log2(cli):
    m = lacuna.load("sierpinski-triangle").measure(3, digits=30)
    d = m.similarity_dimension
    assert d.exact == "log 3 / log 2"
    # log 3 / log 2 = 1.58496250072115618145373894394781650875981440769248…
    assert "1.584962500721156181453738943947816508759814407692".startswith(d.decimal)
    assert abs(float(d.decimal) - math.log(3) / math.log(2)) < 1e-15
    assert [lv.pieces for lv in m.levels] == [1, 3, 9, 27]
    code, data = cli("measure", "sierpinski-triangle", "--level", 3, "--json")
    assert code == 0 and m.data == data


def test_automaton_files_written(tmp_path):
    svg, png = tmp_path / "k.svg", tmp_path / "k.png"
    s = lacuna.load("kite-dart").render(3, svg=svg, png=png, size=200)
    assert s.written == [svg, png]
    assert svg.read_text().lstrip().startswith(("<?xml", "<svg"))
    b = png.read_bytes()
    assert b[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">I", b[16:20])[0] == 200


def test_state_draws_the_dart_from_its_frame(cli, tmp_path):
    import json

    from lacuna import UsageError

    kd = lacuna.load("kite-dart")
    # The start state by name is the picture without a state.
    kite, kite_a = kd.render(4), kd.render(4, state="a")
    assert kite.states == kite_a.states
    assert all(np.array_equal(p, q) for p, q in zip(kite.points, kite_a.points))
    # The dart: its frame is the kite's (a.T0, the first operator reaching b, is the identity),
    # and its level 3 is its own pieces, not the kite's.
    dart0 = kd.render(0, state="b")
    assert dart0.states == ["b"]
    assert np.allclose(dart0.points[0], [[-4, -0.5], [4, -0.5], [0, 5]])
    dart = kd.render(3, state="b")
    out = tmp_path / "b.json"
    code, _ = cli("render", "kite-dart", "--state", "b", "--level", 3, "--json-out", out)
    data = json.loads(out.read_text())
    assert code == 0 and dart.states == [x["state"] for x in data["shapes"]]
    assert all(np.allclose(np.array(x["points"]), p) for x, p in zip(data["shapes"], dart.points))
    assert any(not np.allclose(p, q) for p, q in zip(dart.points, kd.render(3).points))
    png = tmp_path / "b.png"
    assert kd.render(3, state="b", png=png, size=100).written == [png]
    with pytest.raises(UsageError) as e:
        kd.render(1, state="c")
    assert e.value.code == "E0504" and "`c`" in str(e.value) and "a, b" in str(e.value)


def test_measure_state_is_the_cli_s_and_the_areas_tend_to_phi(cli):
    kd = lacuna.load("kite-dart")
    dart = kd.measure(10, state="b")
    code, data = cli("measure", "kite-dart", "--state", "b", "--level", 10, "--json")
    assert code == 0
    assert data["state"] == "b" and dart["state"] == "b"
    assert [x["area"] for x in data["levels"]] == [x["area"] for x in dart["levels"]]
    kite = kd.measure(10)
    assert "state" not in kite.data
    # The kite and dart areas are in ratio φ in the limit (Bandt–Gummelt); at level 10 within 1e-2.
    phi = (1 + 5 ** 0.5) / 2
    assert abs(kite["levels"][10]["area"] / dart["levels"][10]["area"] - phi) < 1e-2
