"""Rendering and measures through the Python API: polygons as NumPy arrays, the files written,
and `lacuna render/measure` on the same inputs."""

import json
import struct
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import lacuna


def shoelace(p):
    """Signed area of a polygon (positive when counter-clockwise)."""
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def test_f0_level_2_has_36_counter_clockwise_cells():
    # N^C_2 = 6² = 36 cells (see the counts), each a simple counter-clockwise polygon.
    r = lacuna.load("F0").render(2)
    assert len(r) == 36 and r.types.shape == (36,)
    assert all(p.ndim == 2 and p.shape[1] == 2 and p.dtype == np.float64 for p in r.polygons)
    assert all(shoelace(p) > 0 for p in r.polygons)
    assert r.written == []


def test_polygons_match_the_command_line_json(cli, tmp_path):
    out = tmp_path / "f0.json"
    code, _ = cli("render", "F0", "--level", 2, "--json-out", out)
    assert code == 0
    data = json.loads(out.read_text())
    r = lacuna.load("F0").render(2)
    assert [c["type"] for c in data["cells"]] == list(r.types)
    for c, p in zip(data["cells"], r.polygons):
        # The command line prints 6 decimals; the arrays hold the full floats.
        assert np.allclose(np.array(c["polygon"]), p, atol=1e-6, rtol=0)


def test_area_of_the_polygons_is_the_measured_area(cli):
    # The measured area at level 2 is the area of the level-2 cells: sum of the shoelace areas.
    f = lacuna.load("F0")
    # A coarse raster keeps the debug build quick; the smallest hole is still resolved.
    m = f.measure(2, raster=256, max_raster=1024)
    area = sum(shoelace(p) for p in f.render(2).polygons)
    assert abs(area - m.area) < 1e-9 * m.area
    code, data = cli("measure", "F0", "--level", 2, "--raster", 256, "--max-raster", 1024, "--json")
    assert code == 0 and m.data == data
    assert m.verified is True and m.holes == 13 and m.components == 1


def test_measure_of_two_quads_matches_the_command_line(cli):
    code, data = cli("measure", "two-quads", "--level", 2, "--raster", 256, "--max-raster", 1024, "--json")
    m = lacuna.load("two-quads").measure(2, raster=256, max_raster=1024)
    assert m.data == data and code == (0 if m.verified else 1)


def test_files_written_are_valid(tmp_path):
    svg, png, stl = tmp_path / "f0.svg", tmp_path / "f0.png", tmp_path / "f0.stl"
    r = lacuna.load("F0").render(2, svg=svg, png=png, stl=stl, size=300)
    assert r.written == [svg, stl, png]
    # SVG: well-formed XML with an <svg> root.
    root = ET.parse(svg).getroot()
    assert root.tag.endswith("svg")
    # PNG: the signature, then IHDR with the width asked for.
    b = png.read_bytes()
    assert b[:8] == b"\x89PNG\r\n\x1a\n" and b[12:16] == b"IHDR"
    assert struct.unpack(">I", b[16:20])[0] == 300
    # Binary STL: an 80-byte header, a triangle count n, then 50 bytes per triangle.
    s = stl.read_bytes()
    n = struct.unpack("<I", s[80:84])[0]
    assert n > 0 and len(s) == 84 + 50 * n
    # ASCII STL.
    a = tmp_path / "f0a.stl"
    lacuna.load("F0").render(1, stl=a, stl_ascii=True)
    text = a.read_text()
    assert text.startswith("solid") and text.rstrip().split("\n")[-1].startswith("endsolid")
    assert text.count("facet normal") == text.count("endfacet") > 0


def test_same_files_as_the_command_line(cli, tmp_path):
    ours, theirs = tmp_path / "a.svg", tmp_path / "b.svg"
    lacuna.load("cycle-sqrt17").render(2, svg=ours)
    code, _ = cli("render", "cycle-sqrt17", "--level", 2, "--svg", theirs)
    assert code == 0 and ours.read_bytes() == theirs.read_bytes()
    ours, theirs = tmp_path / "a.png", tmp_path / "b.png"
    lacuna.load("F0").render(2, png=ours, size=256)
    code, _ = cli("render", "F0", "--level", 2, "--png", theirs, "--size", 256)
    assert code == 0 and ours.read_bytes() == theirs.read_bytes()


def test_parameters_move_the_cells(cli, tmp_path):
    # A free parameter set exactly moves the geometry, as --param does on the command line.
    f = lacuna.load("F0")
    name = f.solve().parameters[0]
    base = f.render(1)
    moved = f.render(1, params={name: "1/7"})
    assert any(not np.allclose(a, b) for a, b in zip(base.polygons, moved.polygons))
    out = tmp_path / "p.json"
    code, _ = cli("render", "F0", "--level", 1, "--param", f"{name}=1/7", "--json-out", out)
    data = json.loads(out.read_text())
    for c, p in zip(data["cells"], moved.polygons):
        assert np.allclose(np.array(c["polygon"]), p, atol=1e-6, rtol=0)


def test_plot_draws_every_cell():
    import matplotlib

    matplotlib.use("Agg")
    ax = lacuna.load("F0").render(1).plot()
    assert len(ax.collections[0].get_paths()) == 6


def test_renderings_show_their_picture_and_give_its_pixels():
    f0 = lacuna.load("F0")
    r = f0.render(2)
    png = r._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    img = r.image
    # 1024 pixels wide, RGBA; F0 is taller than wide by its hexagon's proportions, plus a legend.
    assert img.shape[1] == 1024 and img.shape[2] == 4 and img.dtype.name == "uint8"
    # The drawing is there: pixels of F0's type colour, not only background.
    rgb = img[..., :3].reshape(-1, 3)
    assert (rgb != 255).any(axis=1).mean() > 0.2
    assert "cells=36" in repr(r)
    s = lacuna.load("sierpinski-triangle").render(4)
    assert s._repr_png_()[:4] == b"\x89PNG" and s.image.shape[1] == 1024
    assert "pieces=81" in repr(s)
