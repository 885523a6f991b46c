"""The guide's table "Command line → Python" (issue #33) names every subcommand of
`lacuna --help`, and every Python counterpart it names exists."""

import re

import lacuna
from conftest import REPO


def _subcommands(cli_text):
    code, out = cli_text("--help")
    assert code == 0
    block = out.split("Commands:")[1].split("Options:")[0]
    return [m.group(1) for m in re.finditer(r"^  ([a-z][a-z-]*)\s", block, re.M)]


def _table():
    text = (REPO / "docs" / "guide.template.md").read_text()
    rows = re.findall(r"^\| `lacuna ([a-z-]+)` \| (.*) \|$", text, re.M)
    return dict(rows)


def test_every_subcommand_has_a_row(cli_text):
    commands = _subcommands(cli_text)
    assert "operators" in commands and "man" in commands
    table = _table()
    assert sorted(table) == sorted(commands)
    for name in ("operators", "design", "export", "report", "classify", "morph"):
        assert "none yet" not in table[name]


def test_the_named_functions_exist():
    for row in _table().values():
        for name in re.findall(r"lacuna\.([a-z_]+)\(", row):
            assert callable(getattr(lacuna, name)), name
    for cls in (lacuna.Face, lacuna.Assembly, lacuna.Automaton):
        assert callable(cls.operators) and callable(cls.export)
    for cls in (lacuna.Face, lacuna.Assembly, lacuna.Automaton, lacuna.Volume):
        assert callable(cls.report)
