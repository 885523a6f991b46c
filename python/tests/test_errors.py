"""Bad input through the Python API: exceptions with the code, message and span of the command
line's error for the same input."""

import pytest

import lacuna
from lacuna import (
    FileError,
    GeometryError,
    InputError,
    LacunaError,
    LimitError,
    RunawayError,
    Span,
    UsageError,
)

from conftest import DATA


def _cli_error(cli, *args):
    code, data = cli(*args)
    assert code in (1, 2) and data is not None, (code, data)
    return data["error"]


def test_unknown_edge_type_points_at_the_token(cli):
    # "C2 X2 | …": the bad token starts at column 4 and is 2 characters long.
    with pytest.raises(InputError) as e:
        lacuna.Face("C2 X2 | B2 B2 B2 | A1")
    err = e.value
    assert err.code == "E0103" and err.span == Span(1, 4, 2)
    assert isinstance(err, LacunaError) and isinstance(err, ValueError)
    assert "^^" in err.rendered and "X2" in err.message
    cli_err = _cli_error(cli, "closure", "C2 X2 | B2 B2 B2 | A1", "--json")
    assert (err.code, err.message) == (cli_err["code"], cli_err["message"])
    assert tuple(err.span) == (cli_err["span"]["line"], cli_err["span"]["col"], cli_err["span"]["len"])


@pytest.mark.parametrize(
    "text, code",
    [
        ("", "E0101"),
        ("C2 B2 | C2 B2 B2", "E0102"),
        ("B1 B2 | C2 B2 B2 | A1", "E0104"),
        ("B2^0 B2 | C2 B2 B2 | A1", "E0105"),
        ("C2 B2 | C2 B2 | A1", "E0107"),
        ("C2 B2 | C2 B2 B2 | A9", "E0108"),
    ],
)
def test_bad_notation_codes_match_the_command_line(cli, text, code):
    with pytest.raises(InputError) as e:
        lacuna.Face(text)
    assert e.value.code == code
    assert e.value.span is not None
    assert e.value.code == _cli_error(cli, "closure", text, "--json")["code"]


def test_a_missing_file_is_a_file_error(cli):
    with pytest.raises(FileError) as e:
        lacuna.Assembly.from_file("no/such/file.txt")
    assert e.value.code == "E0601" and isinstance(e.value, OSError)
    with pytest.raises(FileError) as e:
        lacuna.check("no/such/cert.json")
    assert e.value.code == "E0601"


def test_a_file_that_is_not_utf8(cli):
    path = DATA / "not-utf8.txt"
    with pytest.raises(FileError) as e:
        lacuna.Assembly.from_file(path)
    assert e.value.code == "E0602" == _cli_error(cli, "closure", path, "--json")["code"]


def test_limits_are_errors_and_can_be_raised(cli):
    f = lacuna.Face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1")
    with pytest.raises(LimitError) as e:
        f.counts(2000)
    # Python's words for the command line's flag: the keyword that raises it.
    assert e.value.code == "E0501" and "limits={'max_level': …}" in e.value.message
    assert "--max-level" not in e.value.message
    assert e.value.message == _cli_error(cli, "counts", "F0", "--levels", 2000, "--json")["message"].replace(
        "--max-level", "limits={'max_level': …}"
    )
    rows = f.counts(1001, limits={"max_level": 1001})
    assert rows[-1].faces == 6**1001
    with pytest.raises(UsageError) as e:
        f.counts(3, limits={"max_levels": 5})
    assert e.value.code == "E0504"


def test_a_runaway_closure_raises_where_a_closure_is_needed(cli):
    src = "B2 C3 | B2 B2 C3 | {joint}"
    with pytest.raises(RunawayError) as e:
        lacuna.Face(src).counts(1)
    assert e.value.code == "E0502" == _cli_error(cli, "counts", src, "--levels", 1, "--json")["code"]


def test_geometry_errors(cli, tmp_path):
    f0 = lacuna.load("F0")
    with pytest.raises(GeometryError) as e:
        f0.render(1, params={"T0.T9[0][0]": "1/7"})
    assert e.value.code == "E1002"
    with pytest.raises(InputError) as e:
        f0.render(1, params={"T0.T0[1][4]": "x"})
    assert e.value.code == "E1007" and e.value.span is not None
    with pytest.raises(UsageError):
        f0.render(1, params={"T0.T0[1][4]": 0.25})  # a float is not exact
    with pytest.raises(LimitError) as e:
        f0.render(9)
    assert e.value.code == "E1003"
    with pytest.raises(FileError) as e:
        f0.render(1, svg=tmp_path / "no" / "such" / "x.svg")
    assert e.value.code == "E1005"
    with pytest.raises(UsageError) as e:
        f0.measure(1, raster=100)
    assert e.value.code == "E0503"


def test_automaton_errors(tmp_path):
    sier = lacuna.load("sierpinski-triangle")
    with pytest.raises(InputError) as e:
        sier.render(1, params={"t.T9[0][0]": "x"})
    assert e.value.code == "E1007"
    with pytest.raises(UsageError) as e:
        sier.render(1, svg=tmp_path / "s.svg", size=0)
    assert e.value.code == "E0503"
    with pytest.raises(UsageError):
        lacuna.Automaton("F0")
    with pytest.raises(UsageError):
        lacuna.Assembly("sierpinski-triangle")
    bad = tmp_path / "bad.aut"
    bad.write_text("state e 2\nhello\n")
    with pytest.raises(InputError) as e:
        lacuna.Automaton.from_file(bad)
    assert e.value.code == "E0701" and e.value.span.line == 2


def test_every_documented_code_has_its_own_class():
    # docs/ERRORS.md lists every code; each maps to a subclass that names its kind.
    import re

    from conftest import REPO
    from lacuna._errors import error_class

    codes = re.findall(r"^\| (E\d{4}) \|", (REPO / "docs" / "ERRORS.md").read_text(), re.M)
    assert len(codes) > 60
    for code in codes:
        cls = error_class(code)
        assert cls is not LacunaError and issubclass(cls, LacunaError), code
    assert error_class("E0103") is InputError and error_class("E0601") is FileError
    assert error_class("E1041") is GeometryError and error_class("E0502") is RunawayError


def test_an_output_never_overwrites_the_input(tmp_path):
    # As on the command line (E0504): the input file is left as it was.
    src = tmp_path / "f0.txt"
    src.write_text(lacuna.library_text("F0"))
    with pytest.raises(UsageError) as e:
        lacuna.Assembly.from_file(src).render(1, svg=src)
    assert e.value.code == "E0504" and src.read_text() == lacuna.library_text("F0")
    with pytest.raises(UsageError):
        lacuna.load("F0").render(1, svg=tmp_path / "x", png=tmp_path / "x")


@pytest.mark.parametrize("call", [
    lambda f: f.counts(-1),
    lambda f: f.counts(2**64),
    lambda f: f.counts("three"),
    lambda f: f.ratio(digits=-5),
    lambda f: f.verify(levels=-1),
])
def test_a_negative_or_huge_number_is_a_lacuna_error_not_an_overflow(call):
    # Issue #33: counts(-1) raised Python's OverflowError from the conversion to an unsigned
    # integer; it is bad input, so a LacunaError (E0503) like every other.
    f0 = lacuna.Face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1")
    with pytest.raises(LacunaError) as e:
        call(f0)
    assert e.value.code == "E0503"
    assert not isinstance(e.value, OverflowError)
