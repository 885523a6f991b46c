"""docs/lacuna.ipynb runs from top to bottom without error, draws its plots, and is committed
without outputs (kept small)."""

import nbclient
import nbformat

from conftest import REPO

NOTEBOOK = REPO / "docs" / "lacuna.ipynb"


def test_the_committed_notebook_has_no_outputs():
    nb = nbformat.read(NOTEBOOK, as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code and all(not c.outputs and c.execution_count is None for c in code)


def test_the_notebook_runs_and_draws(tmp_path):
    nb = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(
        nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    client.execute()  # raises CellExecutionError on the first failing cell
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    pngs = [o for o in outputs if "image/png" in o.get("data", {})]
    # F0's R_i, F0 at level 3, the type graph, |R_i − R|, the √17 cycle, the half-tangent curves,
    # Koch's curve, three frames of F0's morph.
    assert len(pngs) == 8
    # The cube's WebGL view, inline.
    html = [o["data"]["text/html"] for o in outputs if "text/html" in o.get("data", {})]
    assert any("<canvas" in h and "getContext('webgl'" in h for h in html)
    text = "".join(o.get("text", "") for o in outputs)
    assert "R = 1/3" in text and "equals (sqrt(17) - 3)/4: True" in text
    assert "log 4 / log 3" in text
    assert "minimal counterexample: C2 | B2 B2 B2 | A1 breaks no-collapse" in text
    assert "degrees of freedom 2" in text and "all proved: True" in text
    # Seed 002: the lemniscate fractal's pieces coincide in pairs, the rose's in triples.
    assert "same class: False" in text
    assert "5 frames, every one verified: True" in text
