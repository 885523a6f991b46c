"""Certificates and the independent checker through the Python API, against `lacuna check`."""

import json

import pytest

import lacuna


@pytest.mark.parametrize("name", ["F0", "cycle-sqrt17", "two-quads"])
def test_a_certificate_checks_here_and_on_the_command_line(cli, tmp_path, name):
    path = tmp_path / f"{name}.json"
    cert = lacuna.load(name).certificate(path)
    assert path.read_text(encoding="utf-8") == cert.text
    assert cert.data["format"] == "lacuna-certificate"
    report = lacuna.check(path)
    assert report.all_proved and not report.partial and report.missing == ()
    assert [s.outcome for s in report.steps] == ["proved"] * len(report.steps)
    assert cert.check() == report
    code, data = cli("check", path, "--json")
    assert code == 0 and report.data == data


def test_a_certificate_without_a_step_is_partial(cli, tmp_path):
    # Drop the last step (the limit ratio): every step present is proved, the claim lacks one.
    cert = lacuna.load("F0").certificate()
    data = cert.data
    data["steps"] = data["steps"][:-1]
    path = tmp_path / "partial.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    report = lacuna.check(path)
    assert report.partial and not report.all_proved and report.missing
    code, cli_data = cli("check", path, "--json")
    assert code == 3 and report.data == cli_data


def test_a_forged_ratio_fails(cli, tmp_path):
    # Claim R = 1/4 for F0 (it is 1/3): the checker must refuse the step.
    text = lacuna.load("F0").certificate().text
    assert text.count('"1/3"') >= 1
    path = tmp_path / "forged.json"
    path.write_text(text.replace('"1/3"', '"1/4"'), encoding="utf-8")
    report = lacuna.check(path)
    assert not report.all_proved and not report.partial
    code, cli_data = cli("check", path, "--json")
    assert code == 1 and report.data == cli_data


def test_an_automaton_certificate_checks_here_and_on_the_command_line(cli, tmp_path):
    # The Koch curve: four maps of ratio 1/3 (entries in Q(sqrt 3)), s = log 4 / log 3
    # = 1.2618595071429148741990542286855... (a published constant).
    path = tmp_path / "koch.json"
    cert = lacuna.load("koch").certificate(path)
    assert [s["step"] for s in cert.data["steps"]] == [
        "constraints-hold",
        "contraction",
        "similarity-dimension",
    ]
    report = lacuna.check(path)
    assert report.all_proved and not report.partial
    verdicts = [s.verdict for s in report.steps]
    assert any("similarity dimension = 1.261859507142914874199054228685" in v for v in verdicts)
    code, data = cli("check", path, "--json")
    assert code == 0 and report.data == data
