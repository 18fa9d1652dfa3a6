"""report/ reads records, never the JSON document (issue 28 item 1): the console and HTML tables of
`capred shear` are built from the typed results (envelopes' ``fit.params``, ``ModelMetrics``, fitted laws,
bootstrap rankings, the back-analysis), and show the numbers the JSON holds."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import capred
from capred.report.render import fmt
from capred.report.shear_tables import shear_tables

pytestmark = pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")


def _forbid_json(result, monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("report/ read the JSON document")

    for name in ("to_json", "json_lazy", "payload"):
        monkeypatch.setattr(result, name, refuse)


@pytest.fixture(scope="module")
def run():
    # a fitted chi law and a short bootstrap, so that every table of the command is built
    return capred.run_shear(
        capred.sample_path("shear"),
        capred.ShearOptions(models=("bishop", "own1", "chi_power"), bootstrap=50),
    )


def test_tables_are_built_without_the_json_and_without_old_names(run, monkeypatch):
    _forbid_json(run, monkeypatch)
    with warnings.catch_warnings():
        warnings.filterwarnings(
            "error", category=DeprecationWarning, module=r"capred(\.|$)"
        )  # no Pa attribute read (ModelMetrics.rmse ...)
        titles = [t.title for t in shear_tables(run)]
    assert any(t.startswith("Dry envelope") for t in titles)
    assert any(t.startswith("Wet tests: model comparison") for t in titles)
    assert any(t.startswith("How sure is the ranking?") for t in titles)
    assert any(t.startswith("Fitted χ laws") for t in titles)


def test_tables_show_the_numbers_of_the_json(run):
    doc = run.to_json()  # the same numbers as the JSON document, formatted
    tables = {t.title.split(" ")[0] + t.title.split(" ")[1]: t for t in shear_tables(run)}
    dry = tables["Dryenvelope"]
    for row in dry.rows:
        m = doc["materials"][row[0]]
        assert row[1:7] == [
            fmt(m["n"]),
            fmt(m["c_kPa"]),
            fmt(m["c_se_kPa"]),
            fmt(m["phi_deg"]),
            fmt(m["phi_se_deg"]),
            fmt(m["tan_phi"]),
        ]
    wet = tables["Wettests:"]
    mat = ""
    for row in wet.rows:
        mat = row[0] or mat
        scores = doc["metrics_overall"] if mat == "(all)" else doc["metrics"][mat]
        model = next(k for k in scores if capred.physics.effective_stress_models.MODEL_LABELS[k] == row[1])
        v = scores[model]
        assert row[2:6] == [fmt(v["n"]), fmt(v["rmse_kPa"]), fmt(v["bias_kPa"], sign=True), fmt(v["r2"])]
    boot = tables["Howsure"]
    for row in boot.rows:
        b = doc["bootstrap"][row[0]]
        lo, hi = b["rmse_difference_ci95_kPa"]  # kPa in the JSON: converted once
        # printed at the resolution the adaptive bootstrap resolved (issue 44.2), given in the JSON
        res = b["rmse_difference_resolution_kPa"]
        places = max(0, -int(np.floor(np.log10(res))))
        assert row[4] == f"{round(lo / res) * res:.{places}f} to {round(hi / res) * res:.{places}f}"
        assert abs(float(row[4].split(" to ")[0]) - lo) <= res / 2 * (1 + 1e-9)
    laws = tables["Fittedχ"]
    for row in laws.rows:
        law = doc["fitted"][row[0]]["chi_power"]
        assert row[3:5] == [fmt(law["params"][row[2]]), fmt(law["se"][row[2]])]
