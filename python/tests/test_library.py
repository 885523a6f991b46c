"""The library and loading: names as `lacuna library --json` lists them, each loaded as the right
kind, files read like the command line reads them."""

import pytest

import lacuna

from conftest import REPO


def test_library_names_match_the_command_line(cli):
    code, data = cli("library", "--json")
    assert code == 0
    lib = lacuna.library()
    assert list(lib) == [d["name"] for d in data]
    assert [lib[d["name"]] for d in data] == [d["about"] for d in data]
    assert lacuna.library_text("F0").startswith("#")
    with pytest.raises(lacuna.FileError):
        lacuna.library_text("no-such-entry")


def test_load_gives_the_kind_of_each_entry(cli):
    # The command line's own list says which entries are volumes (one or several glued).
    code, data = cli("library", "--json")
    assert code == 0
    volumes = {e["name"] for e in data if e["kind"] == "volume"}
    assert {"cube-B2", "tetrahedron-B2", "two-cubes"} <= volumes
    for name in lacuna.library():
        if name in volumes:
            v = lacuna.load(name)
            assert isinstance(v, lacuna.Volume) and v.name == name
            continue
        obj = lacuna.load(name)
        assert obj.name == name
        # The library ships automata as fixtures/NAME.aut, production rules (compiled to
        # automata) as fixtures/NAME.rule, faces as fixtures/NAME.txt.
        is_automaton = (REPO / "fixtures" / f"{name}.aut").exists() or (
            REPO / "fixtures" / f"{name}.rule"
        ).exists()
        assert is_automaton or (REPO / "fixtures" / f"{name}.txt").exists()
        assert isinstance(obj, lacuna.Automaton) == is_automaton
        assert isinstance(obj, lacuna.Structure) == (not is_automaton)
        # A production rule is a Rule (an Automaton) that keeps its text: the fixture's.
        rule = REPO / "fixtures" / f"{name}.rule"
        assert isinstance(obj, lacuna.Rule) == rule.exists(), name
        if rule.exists():
            assert obj.text == rule.read_text(encoding="utf-8"), name
        if not is_automaton:
            # One face without shared edges is a Face (issue #33: load("F0") gave an Assembly);
            # more are an Assembly. A fixture of faces has one `face NAME:` line per face.
            text = (REPO / "fixtures" / f"{name}.txt").read_text(encoding="utf-8")
            lines = [l for l in text.splitlines() if l.strip() and not l.lstrip().startswith("#")]
            one = sum(l.lstrip().startswith("face ") and ":" in l for l in lines) == 1
            one = one and not any("~" in l or l.lstrip().startswith("share") for l in lines)
            assert isinstance(obj, lacuna.Face) == one, name
            assert isinstance(obj, lacuna.Assembly) == (not one), name
    assert isinstance(lacuna.load("C2 B2 B2 | C2 B2 B2 | A1"), lacuna.Face)


def test_files_and_library_names_give_the_same_results():
    by_name = lacuna.load("two-quads")
    by_file = lacuna.Assembly.from_file(REPO / "fixtures" / "two-quads.txt")
    autofrac = lacuna.Assembly.from_file(REPO / "fixtures" / "autofrac-two-quads.txt")
    assert isinstance(by_file, lacuna.Assembly) and by_file.name.endswith("two-quads.txt")
    # fixtures/two-quads.txt is "the same structure as autofrac-two-quads.txt in lacuna's
    # assembly format": same types, same counts.
    assert [t.face for t in by_name.closure().types] == [t.face for t in by_file.closure().types]
    assert by_name.counts(6) == by_file.counts(6) == autofrac.counts(6)
    # A face given in notation is the one-face assembly of the library.
    f0 = lacuna.Face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1")
    assert f0.counts(8) == lacuna.load("F0").counts(8)
    assert f0.ratio().exact == lacuna.load("F0").ratio().exact


def test_the_module_docstring_examples_run():
    import doctest

    result = doctest.testmod(lacuna)
    assert result.attempted >= 4 and result.failed == 0


def test_a_rule_is_only_what_a_rule_compiles_to():
    assert "initiator" in lacuna.Rule("koch").text
    with pytest.raises(lacuna.UsageError, match="hand-written automaton, not a rule"):
        lacuna.Rule("sierpinski-triangle")
    with pytest.raises(lacuna.UsageError):
        lacuna.Rule("F0")


def test_a_face_from_its_notation_is_the_face():
    f = lacuna.Face.from_notation("B2 C2 B2 C2 B2 C2 | C2 B2 B2 | A1")
    # Canonical: the least rotation of the boundary, as Face() gives it.
    assert f.notation == lacuna.Face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1").notation
    assert isinstance(f, lacuna.Face)
