"""Rich display in notebooks (issue #33): faces and automata show a PNG, a closure an HTML table."""

import struct

import lacuna


def _png_size(b):
    assert b[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", b[16:24])


def test_a_face_and_an_automaton_show_a_picture():
    f = lacuna.load("F0")
    w, h = _png_size(f._repr_png_())
    assert w == 480 and h > 0
    a = lacuna.load("sierpinski-triangle")
    w, _ = _png_size(a._repr_png_())
    assert w == 480


def test_the_closure_of_f0_is_a_table_of_its_one_type():
    # F0 (THEORY §3, §5): one type, six sub-faces of its own type, contribution 5/2.
    html = lacuna.load("F0").closure()._repr_html_()
    assert "closed: 1 face type," in html
    assert "<td>6×T0</td>" in html
    assert "<td>5/2</td>" in html
    assert "B2 C2 B2 C2 B2 C2 | C2 B2 B2 | A1" in html


def test_counts_and_verdicts_are_tables():
    # F0 (THEORY §5): N^C_i = 6^i, N^L_i = (6^i − 1)/2 (each lacuna counted once), so at level 2
    # 36 faces and 35/2 lacunas, R_2 = (35/2)/(35/2 + 36) = 35/107.
    rows = lacuna.load("F0").counts(2)
    assert isinstance(rows, list) and len(rows) == 3
    html = rows._repr_html_()
    assert html.count("<tr>") == 4 and "<td>36</td>" in html and "<td>35/2</td>" in html
    assert "<td>35/107</td>" in html
    v = lacuna.load("F0").verify(2)
    html = v._repr_html_()
    assert "<td>verified</td><td>True</td>" in html
