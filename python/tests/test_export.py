"""`lacuna export` from Python (issue #33): the generated automaton of faces in lacuna's format
and as the MODITERE model, the same text as the command line's."""

import pytest

import lacuna


@pytest.mark.parametrize("source", ["F0", "two-quads", "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1"])
@pytest.mark.parametrize("format", ["aut", "moditere"])
def test_the_text_is_the_command_line_s(cli_text, source, format):
    code, out = cli_text("export", source, "--format", format)
    assert code == 0 and out
    s = lacuna.load(source)
    assert isinstance(s, (lacuna.Face, lacuna.Assembly))
    assert s.export(format=format) == out


def test_written_to_a_file_as_with_output(cli_text, tmp_path):
    p = tmp_path / "f0.aut"
    q = tmp_path / "cli.aut"
    code, _ = cli_text("export", "F0", "--format", "aut", "--degree", "3", "--cantor-gap", "1/2", "-o", q)
    assert code == 0
    text = lacuna.load("F0").export(p, degree=3, cantor_gap="1/2")
    assert p.read_text() == text == q.read_text()
    assert "Bézier degree 3, Cantor gap/piece ratio 1/2" in text


def test_the_export_solves_as_the_faces_do(tmp_path):
    # The header's promise: `solve` of the exported file gives the input's rank and freedom.
    p = tmp_path / "sq.aut"
    f = lacuna.load("square-B2")
    f.export(p)
    a, s = lacuna.Automaton.from_file(p).solve(), f.solve()
    assert (a.rank, a.dof, a.unknowns) == (s.rank, s.dof, s.unknowns)


def test_an_automaton_is_written_back_in_lacuna_s_format(cli_text):
    code, out = cli_text("export", "de-casteljau-edge", "--format", "aut")
    assert code == 0
    assert lacuna.load("de-casteljau-edge").export() == out


def test_errors_are_lacuna_errors(tmp_path):
    f = lacuna.load("F0")
    with pytest.raises(lacuna.UsageError):
        f.export(format="obj")
    with pytest.raises(lacuna.LacunaError) as e:
        f.export(degree=9)
    assert "degree" in str(e.value) and "--degree" not in str(e.value)
    with pytest.raises(lacuna.InputError):
        f.export(cantor_gap="0")
    with pytest.raises(lacuna.UsageError):
        lacuna.load("de-casteljau-edge").export(format="moditere")
    src = tmp_path / "in.txt"
    src.write_text(lacuna.library_text("two-quads"))
    with pytest.raises(lacuna.UsageError):
        lacuna.Assembly.from_file(src).export(src)
    assert src.read_text() == lacuna.library_text("two-quads")
    with pytest.raises(lacuna.LacunaError):
        f.export(tmp_path / "no" / "such" / "dir.aut")
