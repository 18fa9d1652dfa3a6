"""ModelMetrics of `capred shear` in the JSON's units (issue 28 items 1, 2, 8).

``rmse_kPa`` and ``bias_kPa`` are derived from the one field declaration (``capred.result.user_units``), as
the JSON keys ``rmse_kPa``/``bias_kPa`` and the metrics.csv headers ``rmse [kPa]``/``bias [kPa]`` are; the old
names ``rmse``/``bias`` keep their Pa values for one release with a DeprecationWarning naming the new one, and
capred's own code never reads them.
"""

from __future__ import annotations

import math
import warnings

import pytest

import capred
from capred.pipelines.shear import ModelMetrics, best_of, model_metrics
from capred.result import record_json, record_row


def _hand_metrics() -> ModelMetrics:
    # measured 1 and 3 kPa, predicted 2 and 4 kPa: residuals +1 kPa each -> RMSE = bias = 1 kPa;
    # SS_tot = 2 (1 kPa)^2 = SS_res -> R^2 = 0 (by hand)
    return model_metrics([2000.0, 4000.0], [1000.0, 3000.0])


def test_new_attributes_are_in_kpa_by_hand():
    m = _hand_metrics()
    assert m.n == 2
    assert m.rmse_kPa == pytest.approx(1.0, rel=1e-12)  # float rounding of Pa -> kPa only
    assert m.bias_kPa == pytest.approx(1.0, rel=1e-12)
    assert m.r2 == pytest.approx(0.0, abs=1e-12)
    assert isinstance(m.rmse_kPa, float)  # a number, not a 0-d array


def test_old_names_keep_pa_and_warn_naming_the_replacement():
    m = _hand_metrics()
    with pytest.warns(DeprecationWarning, match=r"ModelMetrics\.rmse_kPa \[kPa\]"):
        assert m.rmse == pytest.approx(1000.0, rel=1e-12)  # Pa, as before this release
    with pytest.warns(DeprecationWarning, match=r"ModelMetrics\.bias_kPa \[kPa\]"):
        assert m.bias == pytest.approx(1000.0, rel=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert m.si.rmse == pytest.approx(1000.0, rel=1e-12)  # the SI view is silent
        repr(m)


def test_json_keys_and_csv_headers_follow_the_declaration():
    m = _hand_metrics()
    assert record_json(m) == {"n": 2, "rmse_kPa": pytest.approx(1.0), "bias_kPa": pytest.approx(1.0), "r2": 0.0}
    assert list(record_row(m)) == ["n [-]", "rmse [kPa]", "bias [kPa]", "r2 [-]"]
    empty = model_metrics([math.nan], [1000.0])  # no prediction: n = 0, every metric null in JSON
    assert record_json(empty) == {"n": 0, "rmse_kPa": None, "bias_kPa": None, "r2": None}


def test_best_of_ranks_without_warning():
    with warnings.catch_warnings():
        warnings.filterwarnings("error", category=DeprecationWarning, module=r"capred(\.|$)")
        better = model_metrics([1100.0, 3100.0], [1000.0, 3000.0])
        assert best_of({"a": _hand_metrics(), "b": better}) == "b"


@pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")
def test_sample_attributes_equal_the_json_and_the_metrics_table():
    with warnings.catch_warnings():
        warnings.filterwarnings(
            "error", category=DeprecationWarning, module=r"capred(\.|$)"
        )  # run, JSON, tables and console: no old name read
        r = capred.run_shear(capred.sample_path("shear"))
        doc = r.to_json()
        table = r.tables()["metrics"]
        r.console_tables()
    for model, met in r.metrics_overall.items():
        assert doc["metrics_overall"][model]["rmse_kPa"] == met.rmse_kPa  # the same float, not just close
        assert doc["metrics_overall"][model]["bias_kPa"] == met.bias_kPa
        row = table[(table["material"] == "(all)") & (table["model"] == model)].iloc[0]
        assert row["rmse [kPa]"] == met.rmse_kPa
        assert row["n [-]"] == met.n
