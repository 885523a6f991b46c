"""Choosing the parameters of faces from Python as `lacuna render/measure/report` do with
`--corners`, `--template` and `--goal` (issue #33): the same pictures, measures and pages as the
command line, and errors that name the keyword. Expected values come from the command line's
files and from facts (a face placed on its corners has them as its level-0 corners; a goal the
fit does not meet moves the cells, and so does a template with its targets moved)."""

from fractions import Fraction

import numpy as np
import pytest

import lacuna

# A convex hexagon, counter-clockwise, for F0's six corners.
HEXAGON = [(0, 0), (2, 0), (3, 2), (2, 4), (0, 4), (-1, 2)]
HEXAGON_TEXT = "0 0, 2 0, 3 2, 2 4, 0 4, -1 2"
# The goals the default fit of F0 does not meet: the LP moves the point (tests/parameters.rs).
MOVING = ["min-lacuna=1/2", "nonnegative"]


def _same(a, b):
    return len(a.polygons) == len(b.polygons) and all(
        p.shape == q.shape and np.allclose(p, q, atol=1e-12, rtol=0) for p, q in zip(a.polygons, b.polygons)
    )


def test_corners_place_the_face(cli, tmp_path):
    f = lacuna.load("F0")
    r = f.render(0, corners=HEXAGON_TEXT)
    # Level 0 is the face itself: its polygon starts each edge at the corner given.
    cell = r.polygons[0]
    for x, y in HEXAGON:
        assert np.abs(cell - [x, y]).sum(axis=1).min() < 1e-12, (x, y)
    assert not _same(r, f.render(0))
    # (x, y) pairs of exact values are the same corners.
    assert _same(f.render(2, corners=HEXAGON), f.render(2, corners=HEXAGON_TEXT))
    ours, theirs = tmp_path / "ours.svg", tmp_path / "theirs.svg"
    f.render(2, corners=HEXAGON, svg=ours)
    code, _ = cli("render", "F0", "--level", 2, "--corners", HEXAGON_TEXT, "--svg", theirs)
    assert code == 0 and ours.read_bytes() == theirs.read_bytes()


def test_corners_of_several_faces_name_the_keyword():
    with pytest.raises(lacuna.InputError) as e:
        lacuna.load("two-quads").render(1, corners="0 0, 1 0, 1 1, 0 1")
    assert e.value.code == "E0215" and "corners=…" in e.value.message and "--" not in e.value.message
    with pytest.raises(lacuna.UsageError):
        lacuna.load("F0").render(1, corners=[(0, 0), (1.5, 0), (1, 1)])


def test_goals_move_the_cells_as_on_the_command_line(cli, tmp_path):
    f = lacuna.load("F0")
    moved = f.render(1, goal=MOVING)
    assert not _same(moved, f.render(1))
    # One goal is a string, several a list; the order is the command line's.
    assert _same(f.render(1, goal="nonnegative"), f.render(1, goal=["nonnegative"]))
    ours, theirs = tmp_path / "ours.svg", tmp_path / "theirs.svg"
    f.render(1, goal=MOVING, svg=ours)
    code, _ = cli("render", "F0", "--level", 1, "--goal", MOVING[0], "--goal", MOVING[1], "--svg", theirs)
    assert code == 0 and ours.read_bytes() == theirs.read_bytes()
    m = f.measure(2, raster=256, max_raster=1024, goal=MOVING)
    code, data = cli("measure", "F0", "--level", 2, "--raster", 256, "--max-raster", 1024, "--goal", MOVING[0], "--goal", MOVING[1], "--json")
    assert code == 0 and m.data == data
    assert m.data != f.measure(2, raster=256, max_raster=1024).data


def test_a_bad_goal_names_the_keyword():
    f = lacuna.load("F0")
    with pytest.raises(lacuna.InputError) as e:
        f.render(1, goal="positive")
    assert e.value.code == "E1030" and e.value.message.startswith("goal `positive`: expected nonnegative")
    assert "--" not in e.value.message and e.value.span == (1, 1, len("positive"))
    # Goals that cannot be met together: an error naming them, as on the command line.
    with pytest.raises(lacuna.GeometryError) as e:
        f.render(1, goal=["nonnegative", "min-lacuna=2"])
    assert e.value.code == "E1031" and "`nonnegative`, `min-lacuna=2`" in e.value.message


def _shrunk(line):
    """A `sub` line of a template with every target nearer the centre (9/10 of its position)."""
    if not line.startswith("sub "):
        return line
    ty, k, points = line.split(None, 3)[1:]
    moved = [" ".join(str(Fraction(c) * Fraction(9, 10)) for c in p.split()) for p in points.split(";")]
    return f"sub {ty} {k} " + "; ".join(moved)


def test_a_template_as_on_the_command_line(cli, tmp_path):
    tpl = tmp_path / "f0-template.txt"
    code, _ = cli("render", "F0", "--level", 1, "--write-template", tpl)
    assert code == 0 and tpl.exists()
    tpl.write_text("\n".join(_shrunk(line) for line in tpl.read_text().splitlines()) + "\n")
    f = lacuna.load("F0")
    ours, theirs = tmp_path / "ours.svg", tmp_path / "theirs.svg"
    r = f.render(1, template=tpl, svg=ours)
    # The targets moved by a tenth of the template's size: so do the free control points.
    assert max(np.abs(p - q).max() for p, q in zip(r.polygons, f.render(1).polygons)) > 0.01
    code, _ = cli("render", "F0", "--level", 1, "--template", tpl, "--svg", theirs)
    assert code == 0 and ours.read_bytes() == theirs.read_bytes()
    # The same template as text path; the picture of the rendering is drawn with it.
    assert _same(r, f.render(1, template=str(tpl)))
    assert r.image.shape[1] == 1024
    m = f.measure(1, raster=256, max_raster=1024, template=tpl)
    code, data = cli("measure", "F0", "--level", 1, "--raster", 256, "--max-raster", 1024, "--template", tpl, "--json")
    assert code == 0 and m.data == data


def test_a_template_is_never_overwritten_and_must_read(cli, tmp_path):
    tpl = tmp_path / "t.txt"
    code, _ = cli("render", "F0", "--level", 1, "--write-template", tpl)
    assert code == 0
    text = tpl.read_text()
    f = lacuna.load("F0")
    for call in (lambda: f.render(1, template=tpl, png=tpl), lambda: f.report(tpl, level=1, template=tpl)):
        with pytest.raises(lacuna.UsageError) as e:
            call()
        assert e.value.code == "E0504"
        assert tpl.read_text() == text
    tpl.write_text("not a template\n")
    with pytest.raises(lacuna.InputError) as e:
        f.render(1, template=tpl)
    assert e.value.span is not None
    with pytest.raises(lacuna.FileError):
        f.render(1, template=tmp_path / "missing.txt")


def test_report_with_goals_is_the_page_the_command_line_writes(cli, tmp_path):
    f = lacuna.load("F0")
    page = f.report(level=1, goal=MOVING)
    theirs = tmp_path / "cli.html"
    code, _ = cli("report", "F0", "--level", 1, "--goal", MOVING[0], "--goal", MOVING[1], "--out", theirs)
    assert code == 0 and theirs.read_text() == page
    assert page != f.report(level=1)
    out = tmp_path / "ours.html"
    assert f.report(out, level=1, corners=HEXAGON) == out
    code, _ = cli("report", "F0", "--level", 1, "--corners", HEXAGON_TEXT, "--out", theirs)
    assert code == 0 and theirs.read_text() == out.read_text()
