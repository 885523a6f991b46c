"""Families from Python (issue #33): explore split into shards on an executor gives the results
of one run of the command line; census and check-mesh are the command line's."""

import json
from concurrent.futures import ProcessPoolExecutor

import pytest

import lacuna

# A small family: boundaries of B2 and C2 up to length 3, Ea/El/Ec from C2 and B2, A1.
FAMILY = dict(edges="B2,C2", max_length=3, params="C2,B2", algorithm="A1")


def _cli_lines(cli_text, *extra):
    code, out = cli_text(
        "explore",
        "--edges", FAMILY["edges"],
        "--max-length", FAMILY["max_length"],
        "--params", FAMILY["params"],
        "--algorithm", FAMILY["algorithm"],
        "--json",
        *extra,
    )
    lines = [json.loads(l) for l in out.splitlines() if l.strip()]
    return code, [l for l in lines if "summary" not in l], lines[-1]["summary"]


def test_explore_is_the_command_line_s_run(cli_text):
    code, lines, summary = _cli_lines(cli_text)
    e = lacuna.explore(**FAMILY)
    assert [r.data for r in e.results] == lines
    for k in ("boundaries", "passed", "failed", "refused", "limit"):
        assert e.summary[k] == summary[k], k
    assert e.ok == (code == 0)
    assert "faces in 1 shard" in repr(e)
    assert "<table>" in e._repr_html_()


def test_shards_on_a_process_pool_merge_to_one_run(cli_text):
    whole = lacuna.explore(**FAMILY)
    with ProcessPoolExecutor(max_workers=2) as pool:
        split = lacuna.explore(**FAMILY, shards=3, executor=pool)
    assert [r.data for r in split.results] == [r.data for r in whole.results]
    assert split.summary.boundaries == whole.summary.boundaries
    assert split.counterexamples == whole.counterexamples
    # Each shard is the command line's `--shard i/n`: boundary k in shard k mod 3.
    _, lines, _ = _cli_lines(cli_text, "--shard", "2/3")
    assert [l["index"] for l in lines] == [r.index for r in whole.results if r.index % 3 == 1]


def test_shards_on_a_dask_cluster_merge_to_one_run():
    distributed = pytest.importorskip("distributed")
    whole = lacuna.explore(**FAMILY)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            split = lacuna.explore(**FAMILY, shards=4, executor=client.get_executor())
    assert [r.data for r in split.results] == [r.data for r in whole.results]
    assert split.summary.shards == 4 and split.summary.boundaries == whole.summary.boundaries


def test_explore_as_a_dataframe():
    pd = pytest.importorskip("pandas")
    e = lacuna.explore(**FAMILY)
    df = e.dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == len(e) == e.summary.boundaries
    assert list(df["face"]) == [r.face for r in e.results]


def test_the_holes_property_is_the_command_line_s(cli_text):
    # The holes property measures every face's geometry: the same results as
    # `lacuna explore --properties holes`, and the same limit, worded for Python.
    code, lines, summary = _cli_lines(cli_text, "--properties", "holes")
    e = lacuna.explore(**FAMILY, properties="holes")
    assert [r.data for r in e.results] == lines
    assert e.summary.passed == summary["passed"] and e.ok == (code == 0)
    with pytest.raises(lacuna.LimitError) as err:
        lacuna.explore(**FAMILY, properties="holes", max_holes_cells=10)
    assert "max_holes_cells=" in str(err.value) and "--max" not in str(err.value)
    with pytest.raises(lacuna.LimitError) as err:
        lacuna.explore(**FAMILY, properties="holes", holes_level=7)
    assert "holes_level=" in str(err.value)


def test_explore_refuses_what_it_cannot_run():
    with pytest.raises(lacuna.UsageError):
        lacuna.explore(**FAMILY, shards=0)
    with pytest.raises(lacuna.InputError):
        lacuna.explore(edges="B2,X9", max_length=2)


def test_census_is_the_command_line_s(cli):
    code, data = cli(
        "census", "--edges", "B2,C2", "--params", "C2,B2", "--algorithms", "A1,A2", "--max-length", 3, "--json"
    )
    assert code == 0
    c = lacuna.census("B2,C2", "C2,B2", "A1,A2", 3)
    assert c.data == data
    assert c.faces == c.closed + c.runaway + c.refused + c.data.get("over_limit", 0)


def test_check_mesh_reads_what_render_writes(tmp_path):
    stl, claims = tmp_path / "cube.stl", tmp_path / "cube.json"
    lacuna.load("cube-B2").render(1, stl=stl, claims=claims)
    r = lacuna.check_mesh(stl, claims=claims)
    # The level-1 cube: one closed part of genus 5 (χ = 2 − 2·5 = −8).
    assert r.passed and r.euler == -8 and r.genus == 5 and len(r.parts) == 1
    assert not lacuna.check_mesh(stl, expect_parts=2).passed
    broken = tmp_path / "broken.stl"
    broken.write_bytes(stl.read_bytes()[:-50])
    with pytest.raises(lacuna.LacunaError):
        lacuna.check_mesh(broken)
