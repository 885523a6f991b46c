"""Automata through the Python API: the attractor's pieces, its measures and dimension."""

import math
import struct

import numpy as np

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
