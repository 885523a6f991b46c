"""`lacuna report`, `lacuna classify` and `lacuna morph` from Python (issue #33): the report page
of faces, automata and volumes, the classes of inputs by their invariants, and the frames of a
metamorphosis. Expected values come from facts (a face's class holds its rotations; the gasket
family against the carpet as docs/GALLERY.md states it; a morph's ends are the renderings of its
two choices), not from the command line's answers."""

import re
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import lacuna

F0 = "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1"


# ---------------------------------------------------------------------------------------------
# report


def test_face_report_is_the_page_the_command_line_writes(cli, tmp_path):
    f = lacuna.Face(F0)
    out = tmp_path / "f0.html"
    written = f.report(out, level=2)
    assert written == out and isinstance(written, Path)
    page = out.read_text()
    assert page.lstrip().lower().startswith("<!doctype html")
    assert "VERIFIED" in page and "NOT VERIFIED" not in page
    assert "<svg" in page or "<img" in page
    # Without a path, the text itself; the same page as lacuna report writes.
    assert f.report(level=2) == page
    theirs = tmp_path / "cli.html"
    code, _ = cli("report", F0, "--level", 2, "--out", theirs)
    assert code == 0 and theirs.read_text() == page


def test_report_of_a_runaway_says_so():
    # The runaway of docs/GUIDE.md: the page is a negative verdict, not an exception.
    page = lacuna.Face("B2 C3 | B2 B2 C3 | {joint}").report(level=1, limits={"max_boundary": 30})
    assert "NOT VERIFIED" in page and "did not close" in page


def test_automaton_and_volume_reports(cli, tmp_path):
    page = lacuna.load("sierpinski-triangle").report(level=3)
    assert "sierpinski-triangle" in page and ("<svg" in page or "<img" in page)
    # A level of the triangle has 3^k pieces: the measures table goes to level 3 (27 pieces).
    assert "27" in page
    out = tmp_path / "cube.html"
    assert lacuna.load("cube-B2").report(out, level=1) == out
    vol = out.read_text()
    assert "VERIFIED" in vol and "cube-B2" in vol
    # The pages lacuna report writes, byte for byte.
    for name, level, ours in (("sierpinski-triangle", 3, page), ("cube-B2", 1, vol)):
        theirs = tmp_path / f"{name}.html"
        code, _ = cli("report", name, "--level", level, "--out", theirs)
        assert code == 0 and theirs.read_text() == ours, name


def test_report_refuses_the_input_and_speaks_python(tmp_path):
    src = tmp_path / "f.txt"
    src.write_text(f"face f0: {F0}\n")
    with pytest.raises(lacuna.UsageError):
        lacuna.load(src).report(src, level=1)
    with pytest.raises(lacuna.UsageError) as e:
        lacuna.Face(F0).report(level=1, raster=100)
    assert "raster" in e.value.message and "--" not in e.value.message
    with pytest.raises(lacuna.LimitError) as e:
        lacuna.Face(F0).report(level=3, max_cells=10)
    assert "max_cells" in e.value.message and "--max" not in e.value.message


# ---------------------------------------------------------------------------------------------
# classify


def _rotations(notation):
    boundary, rest = notation.split("|", 1)
    edges = boundary.split()
    return [" ".join(edges[k:] + edges[:k]) + " |" + rest for k in range(len(edges))]


def test_a_face_is_in_the_class_of_its_rotations():
    # A face written from another corner is the same face: one class, every invariant equal.
    face = "C2 B2 B2 C2 B2 | C2 B2 B2 | A1"
    rotations = _rotations(face)
    assert len(set(rotations)) == 5
    c = lacuna.classify(face, *rotations[1:3])
    assert c.same_class and len(c) == 1 and c.classes == [[face, *rotations[1:3]]]
    for v in c.comparisons:
        assert v.same_class and v.differs is None and v.kinds == ("faces", "faces")


def test_the_gasket_family_against_the_carpet():
    # docs/GALLERY.md, seed 002: with the paper's multiplicity the octagonal gasket is in the
    # carpet's class; the triangular gasket is not (3 pieces of level 1 against the carpet's 8,
    # one piece per map of each IFS).
    g8, carpet, g3 = (lacuna.load(n) for n in ("gasket-8", "sierpinski-carpet", "gasket-3"))
    c = lacuna.classify(g8, carpet, g3, multiplicity="coincidences")
    assert c.classes == [[g8, carpet], [g3]] and not c.same_class
    assert c.comparison(0, 1).same_class
    d = c.comparison(2, 1).differs  # the pair (1, 2): A is the carpet
    assert (d.group, d.invariant, d.level) == ("cardinality", "pieces", 1)
    assert (d.a, d.b) == (8, 3)
    assert "DIFFERENT CLASSES" in c.comparison(1, 2).text
    # The paper's multiplicity is the default, decided at every level (the distinct maps satisfy
    # the open-set condition); contacts at images of fixed corners differ (16 and 15 points) but
    # only show in a note: they depend on how each automaton is written.
    dflt = lacuna.classify(g8, carpet, levels=2).comparison(0, 1)
    assert dflt.same_class and dflt.every_level
    contacts = lacuna.classify(g8, carpet, multiplicity="contacts").comparison(0, 1)
    assert contacts.same_class and any("not a class invariant" in n for n in contacts.notes)
    assert "<table>" in c._repr_html_()


def test_faces_that_differ_at_level_1():
    # F0 has 6 sub-faces, the square of Bézier edges 4: the counts of level 1 tell them apart.
    f0, sq = lacuna.Face(F0), lacuna.load("square-B2")
    c = lacuna.classify(f0, sq)
    d = c.comparison(0, 1).differs
    assert d.level == 1 and d.group == "cardinality"
    assert (d.a, d.b) == (f0.counts(1)[1].faces, sq.counts(1)[1].faces)
    # Exact shares of the valences are Fractions summing to 1.
    shares = c.comparison(0, 1).limit_shares.b.shares
    assert all(isinstance(s.share, Fraction) for s in shares)
    assert sum(s.share for s in shares) == 1


def test_classify_errors_speak_python():
    with pytest.raises(lacuna.UsageError):
        lacuna.classify(F0)
    with pytest.raises(lacuna.UsageError) as e:
        lacuna.classify(F0, F0, multiplicity="some")
    assert "contacts" in e.value.message and "--" not in e.value.message
    with pytest.raises(lacuna.LimitError) as e:
        lacuna.classify(F0, F0, levels=50, limits={"max_level": 10})
    assert "max_level" in e.value.message and "--max" not in e.value.message


# ---------------------------------------------------------------------------------------------
# morph


def _same_cells(polys_a, polys_b):
    return len(polys_a) == len(polys_b) and all(
        p.shape == q.shape and np.allclose(p, q, atol=1e-9, rtol=0) for p, q in zip(polys_a, polys_b)
    )


def test_morph_of_faces_starts_and_ends_at_its_two_choices(tmp_path):
    f = lacuna.load("F0")
    name = f.solve().parameters[0]
    svg = tmp_path / "m.svg"
    m = lacuna.morph(None, {name: "1/7"}, on=f, frames=4, level=1, size=128, svg=svg)
    assert len(m.frames) == 4 and [fr.index for fr in m.frames] == [0, 1, 2, 3]
    assert [fr.t for fr in m.frames] == [Fraction(k, 3) for k in range(4)]
    # The ends are the renderings of the two choices (8 segments per Bézier edge, as drawn).
    start = f.render(1, segments=8)
    end = f.render(1, params={name: "1/7"}, segments=8)
    assert _same_cells(m.frames[0].polygons, start.polygons)
    assert _same_cells(m.frames[-1].polygons, end.polygons)
    assert not _same_cells(m.frames[1].polygons, start.polygons)
    assert list(m.frames[0].types) == list(start.types) and m.frames[0].closed.all()
    assert m.changing >= 1 and m.verified == all(fr.verified for fr in m.frames)
    text = svg.read_text()
    assert m.written == [svg] and "<animate" in text and text.count('class="frame"') == 4


def test_morph_between_two_automata(tmp_path):
    # The de Casteljau edge split at 1/2 and at 1/3 (T0 restricts the parabola to [0, 1/3], T1
    # to [1/3, 1]): one shape, so every frame keeps the constraints.
    text = lacuna.library_text("de-casteljau-edge")
    third = "\n".join(
        "sub   e.T0 : e <- e = [1 2/3 4/9; 0 1/3 4/9; 0 0 1/9]"
        if line.startswith("sub   e.T0")
        else "sub   e.T1 : e <- e = [4/9 0 0; 4/9 2/3 0; 1/9 1/3 1]"
        if line.startswith("sub   e.T1")
        else line
        for line in text.splitlines()
    )
    b = tmp_path / "third.aut"
    b.write_text(third + "\n")
    a = lacuna.load("de-casteljau-edge")
    m = lacuna.morph(a, lacuna.Automaton.from_file(b), frames=3, level=3)
    assert len(m) == 3 and m.verified and m.changing == 2
    for frame, shapes in ((m.frames[0], a.render(3)), (m.frames[-1], lacuna.Automaton.from_file(b).render(3))):
        assert _same_cells(frame.polygons, [p[:, :2] for p in shapes.points])
    with pytest.raises(lacuna.LacunaError) as e:
        lacuna.morph(a, lacuna.load("sierpinski-triangle"))
    assert e.value.code == "E1403"


def test_morph_errors_speak_python():
    f = lacuna.load("F0")
    with pytest.raises(lacuna.UsageError) as e:
        lacuna.morph(None, None, on=f, frames=1)
    assert "frames" in e.value.message and "--" not in e.value.message
    with pytest.raises(lacuna.LimitError) as e:
        lacuna.morph(None, None, on=f, level=3, max_cells=10)
    assert "max_cells" in e.value.message and "--max" not in e.value.message
    with pytest.raises(lacuna.UsageError):
        lacuna.morph(f, f)  # faces without on=


def test_a_frame_plots_its_cells():
    import matplotlib

    matplotlib.use("Agg")
    f = lacuna.load("F0")
    m = lacuna.morph(None, None, on=f, frames=2, level=1, size=64)
    ax = m.frames[1].plot()
    drawn = sum(len(c.get_paths()) for c in ax.collections)
    assert drawn == len(m.frames[1]) == f.counts(1)[1].faces
    assert "<table>" in m._repr_html_() and m._repr_html_().count("<tr>") == 3


# ---------------------------------------------------------------------------------------------
# morph: PNG frames


def _png_size(data):
    """(width, height) of a PNG: its signature, then the IHDR chunk first."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
    return tuple(int.from_bytes(data[i : i + 4], "big") for i in (16, 20))


def test_morph_of_faces_writes_one_png_per_frame(cli, tmp_path):
    f = lacuna.load("F0")
    name = f.solve().parameters[0]
    svg = tmp_path / "m.svg"
    m = lacuna.morph(None, {name: 1}, on=f, frames=4, level=1, size=256, svg=svg, png=str(tmp_path / "frame-{}.png"))
    # `{}` becomes the frame number in three digits, one file per frame and nothing else.
    pngs = [tmp_path / f"frame-{k:03d}.png" for k in range(4)]
    assert sorted(tmp_path.iterdir()) == sorted(pngs + [svg])
    assert m.written == [svg] + pngs
    for p in pngs:
        assert _png_size(p.read_bytes())[0] == 256
    # The ends are the pictures of the two choices, without the legend, as render draws them.
    start, end = tmp_path / "start.png", tmp_path / "end.png"
    f.render(1, png=start, size=256, legend=False)
    f.render(1, png=end, size=256, legend=False, params={name: 1})
    assert pngs[0].read_bytes() == start.read_bytes()
    assert pngs[-1].read_bytes() == end.read_bytes() != start.read_bytes()
    # The frames lacuna morph --png writes, byte for byte.
    code, _ = cli("morph", "default", f"{name}=1", "--on", "F0", "--frames", 4, "--level", 1, "--size", 256, "--png", tmp_path / "cli-{}.png")
    assert code == 0
    for k, p in enumerate(pngs):
        assert (tmp_path / f"cli-{k:03d}.png").read_bytes() == p.read_bytes(), k


def test_morph_of_automata_writes_square_png_frames(cli, tmp_path):
    # Two automata of one shape (the triangle twice): frames of size × size pixels.
    a = tmp_path / "a.aut"
    a.write_text(lacuna.library_text("sierpinski-triangle"))
    m = lacuna.morph(lacuna.load("sierpinski-triangle"), a, frames=3, level=3, size=64, png=tmp_path / "t{}.png")
    assert m.written == [tmp_path / f"t{k:03d}.png" for k in range(3)]
    for p in m.written:
        assert _png_size(p.read_bytes()) == (64, 64)
    code, _ = cli("morph", "sierpinski-triangle", a, "--frames", 3, "--level", 3, "--size", 64, "--png", tmp_path / "c{}.png")
    assert code == 0
    for k, p in enumerate(m.written):
        assert (tmp_path / f"c{k:03d}.png").read_bytes() == p.read_bytes(), k


def test_morph_png_errors_speak_python(tmp_path):
    f = lacuna.load("F0")
    with pytest.raises(lacuna.UsageError) as e:
        lacuna.morph(None, None, on=f, png=tmp_path / "x.png")
    assert e.value.code == "E1401" and e.value.message.startswith("png `") and "--" not in e.value.message
    assert not (tmp_path / "x.png").exists()
    # A frame never overwrites an input, nor the SVG.
    b = tmp_path / "b000.aut"
    b.write_text(lacuna.library_text("sierpinski-triangle"))
    with pytest.raises(lacuna.UsageError) as e:
        lacuna.morph("sierpinski-triangle", b, frames=2, level=1, png=tmp_path / "b{}.aut")
    assert e.value.code == "E0504" and b.read_text() == lacuna.library_text("sierpinski-triangle")
    with pytest.raises(lacuna.UsageError) as e:
        lacuna.morph(None, None, on=f, frames=2, level=1, svg=tmp_path / "f001.png", png=tmp_path / "f{}.png")
    assert e.value.code == "E0504" and not list(tmp_path.glob("f*.png"))
