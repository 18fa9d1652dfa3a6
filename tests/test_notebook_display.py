"""A fresh Jupyter kernel shows capred's figures (issue 29.2): a notebook is executed with nbclient and
ipykernel, and its cells' outputs must hold image/png data (before, only '<Figure size 709x530 with 4 Axes>')."""

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

SETUP = """\
import warnings
import capred
warnings.simplefilter("ignore", capred.CapredWarning)
r = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
"""


def _outputs(cells: list[str], tmp_path) -> list[list[dict]]:
    import sys

    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(SETUP)] + [nbformat.v4.new_code_cell(c) for c in cells]
    client = nbclient.NotebookClient(
        nb, timeout=240, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    client.km_kwargs = {"kernel_cmd": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"]}
    client.execute()
    return [c.outputs for c in nb.cells[1:]]


def _types(outputs: list[dict]) -> set[str]:
    return {mime for out in outputs for mime in out.get("data", {})}


@pytest.mark.slow
def test_plot_shows_pngs_in_a_fresh_kernel(tmp_path, monkeypatch):
    import os

    from conftest import ROOT

    # the kernel (a fresh process) imports this checkout's capred, installed or not
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    one, every, summary = _outputs(["r.plot('report_steel_2mm')", "r.plot()", "r"], tmp_path)
    assert "image/png" in _types(one)  # the cell's Figure displays as an image
    pngs = [out for out in every if "image/png" in out.get("data", {})]
    # the sample's four sheets, each shown: the report and the capillary-stress sheet of steel and of sand
    assert len(pngs) == 4
    assert "text/html" in _types(summary)  # a result shows its compact summary
    html = next(o["data"]["text/html"] for o in summary if "text/html" in o.get("data", {}))
    assert len(html.encode("utf-8")) < 30_000 and "data:image/png;base64," in html
