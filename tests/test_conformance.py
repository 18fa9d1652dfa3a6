"""One generic check per registry entry (issue 28): every command, effective-stress model and retention model runs
through the API, the CLI, the JSON, the CSV files, a figure and report.html — the entries are read from the
registries, so a new entry is tested the moment it is registered, with no test file edited (as scikit-learn's
``parametrize_with_checks`` and pastas' ``test_rfuncs.py`` do).
"""

import csv
import json
import re
from html import unescape

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.fitting.retention_models import MODELS as RETENTION_MODELS
from capred.physics.effective_stress_models import REGISTRY as STRESS_MODELS
from capred.pipelines.shear import model_params_from_retention
from capred.reductions import REDUCTIONS

runner = CliRunner()

#: a CSV header cell is ``name [unit]`` or a bare name (an identifier, a label, a flag) that does not hide a unit
HEADER = re.compile(r"^[^\[\]]+ \[[^\[\]]+\]$")
UNIT_SUFFIX = re.compile(r"_(kPa|Pa|MPa|deg|mm|cm|cm3|mm3|m|N|mN|g|kg|per_kPa|kPa2|pct)$")


def _csv_headers(folder):
    for path in sorted(folder.rglob("*.csv")):
        with path.open(encoding="utf-8-sig", newline="") as fh:
            yield path, next(csv.reader(fh), [])


def _bad_headers(folder) -> list[str]:
    bad = []
    for path, header in _csv_headers(folder):
        for cell in header:
            if "[" in cell and not HEADER.match(cell) or UNIT_SUFFIX.search(cell):
                bad.append(f"{path.name}: {cell!r}")
    return bad


def _api_result(red):
    source = capred.sample_path(red.sample) if red.sample is not None else None
    return red.run(source, red.options(**dict(red.example)))


@pytest.fixture(scope="module")
def retention_fit(tmp_path_factory):
    """fits.json of the retention sample: gives every effective-stress model the inputs it may need."""
    out = tmp_path_factory.mktemp("fit") / "o"
    res = runner.invoke(app, ["retention", "--sample", "--no-plots", "--out", str(out)])
    assert res.exit_code == 0, res.output
    return out / "fits.json"


@pytest.mark.parametrize("name", list(REDUCTIONS))
def test_command_conforms(name, tmp_path):
    red = REDUCTIONS[name]
    out = tmp_path / "o"
    res = runner.invoke(app, [*red.example_args(), "--out", str(out)])
    assert res.exit_code == 0, res.output
    assert "Traceback" not in res.output
    result = _api_result(red)
    # the JSON on disk is the API's document (the CLI and Python speak one language)
    on_disk = json.loads((out / result.json_name).read_text(encoding="utf-8"))
    assert on_disk == result.to_json()
    assert on_disk["command"] == name and isinstance(on_disk["warnings"], list)
    # provenance beside the outputs, naming every file the run wrote
    prov = json.loads((out / "provenance.json").read_text(encoding="utf-8"))
    written = {p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()} - {"provenance.json"}
    assert written <= set(prov["outputs"]) | {"provenance.json"}, sorted(written - set(prov["outputs"]))
    # one file style: every CSV header is `name [unit]` or a bare identifier
    assert _bad_headers(out) == []
    # report.html, and PNGs only of figure sheets the command's presenter draws (the main ones by default)
    assert (out / "report.html").is_file()
    stems = set(result.figures())
    written_png = {p.stem for p in out.glob("*.png")}
    assert written_png <= stems and bool(written_png) == bool(stems)


@pytest.mark.parametrize("model", list(STRESS_MODELS))
def test_effective_stress_model_conforms(model, retention_fit, tmp_path):
    entry = STRESS_MODELS[model]
    out = tmp_path / "o"
    models = "bishop" if model == "bishop" else f"bishop,{model}"
    args = ["shear", "--sample", "--models", models, "--retention", str(retention_fit), "--bootstrap", "0"]
    res = runner.invoke(app, [*args, "--out", str(out)])
    assert res.exit_code == 0, res.output
    doc = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert model in doc["models"]
    with (out / "results.csv").open(encoding="utf-8") as fh:
        header = next(csv.reader(fh))
    assert f"tau_pred_{model} [kPa]" in header
    html = unescape((out / "report.html").read_text(encoding="utf-8"))
    assert entry.label in html
    assert any(out.glob("report_*.png"))
    # the same run from Python: the model's predictions are a typed record in the user's units on the page
    params = model_params_from_retention(retention_fit)
    r = capred.run_shear(
        capred.sample_path("shear"),
        capred.ShearOptions(models=tuple(models.split(",")), bootstrap=0, model_params=params),
    )
    assert model in r.predictions


@pytest.mark.parametrize("model", list(RETENTION_MODELS))
def test_retention_model_conforms(model, tmp_path):
    entry = RETENTION_MODELS[model]
    out = tmp_path / "o"
    res = runner.invoke(app, ["retention", "--sample", "--model", model, "--out", str(out)])
    assert res.exit_code == 0, res.output
    doc = json.loads((out / "fits.json").read_text(encoding="utf-8"))
    branch = next(iter(doc["branches"]))
    fit_json = doc["branches"][branch]["fits"][model]
    html = unescape((out / "report.html").read_text(encoding="utf-8"))
    assert entry.label in html
    assert (out / "retention.png").is_file()
    assert _bad_headers(out) == []
    # Python speaks the JSON's names and units: fit.params[NAME].value is the JSON value
    r = capred.run_retention(capred.sample_path("retention"), capred.RetentionOptions(models=(model,)))
    fit = r.fits[branch][model]
    assert len(fit.params) > 0
    for key, p in fit.params.items():
        assert p.name == key and fit_json[key] == pytest.approx(p.value, rel=1e-12), key
