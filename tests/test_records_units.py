"""One unit per quantity for the user (issue 28 items 1, 2, 8): shear's per-test records in the JSON's units.

``ModelPrediction`` and ``BackAnalysis`` offer each stress as ``<field>_kPa`` [kPa], the unit of the JSON and
console, derived from the field's one declaration (``capred.result.user_units``); the old names (``tau``,
``sigma_cap`` ...) keep their Pa values for one release and raise a DeprecationWarning naming the new one;
capred's own code paths (pipeline, writers, figures, console) never read an old name.
"""

from __future__ import annotations

import dataclasses
import json
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.pipelines.shear_records import BackAnalysis, ModelPrediction, Sampled
from capred.result import record_columns, record_json_columns

KPA_ATTRS = {
    ModelPrediction: {
        "sigma_eff": "sigma_eff_kPa",
        "tau": "tau_kPa",
        "residual": "residual_kPa",
        "tau_prediction_interval": "tau_prediction_interval_kPa",
        "tau_mean_ci": "tau_mean_ci_kPa",
        "sigma_cap": "sigma_cap_kPa",
    },
    BackAnalysis: {
        "sigma_cap": "sigma_cap_kPa",
        "sigma_cap_se": "sigma_cap_se_kPa",
        "sigma_cap_ci": "sigma_cap_ci_kPa",
    },
}


@pytest.fixture(scope="module")
def run():
    with warnings.catch_warnings():
        warnings.filterwarnings(
            "error", category=DeprecationWarning, module=r"capred(\.|$)"
        )  # the pipeline reads no deprecated name
        warnings.simplefilter("ignore", capred.CapredWarning)  # the sample's pendular-regime notes
        r = capred.run_shear(capred.sample_path("shear"))
        doc = json.loads(json.dumps(r.to_json()))
    return r, doc


def test_renames_derive_from_the_declaration():
    """The new attribute is ``<field>_<unit>`` of every field declared with a kPa output; nothing else changes."""
    for cls, expected in KPA_ATTRS.items():
        assert cls.RENAMED == expected
        for new in expected.values():
            assert isinstance(getattr(cls, new), property)
        # a dimensionless field is not renamed (chi_back is in the same unit everywhere)
    assert "chi_back" not in BackAnalysis.RENAMED and "dof" not in BackAnalysis.RENAMED


def test_kpa_attributes_equal_the_json(run):
    """Each test's τ_pred, residual, σ_cap and intervals in Python equal the JSON's numbers exactly (both are the
    stored SI value times 1e-3, one multiplication: tolerance 0)."""
    r, doc = run
    rows = doc["tests"]
    n = len(rows)
    for m in r.models:
        p = r.predictions[m]
        json_tau = np.array([np.nan if t["tau_pred_kPa"][m] is None else t["tau_pred_kPa"][m] for t in rows])
        assert_array_equal(p.tau_kPa[:n], json_tau)
        json_res = np.array([np.nan if t["residual_kPa"][m] is None else t["residual_kPa"][m] for t in rows])
        assert_array_equal(p.residual_kPa[:n], json_res)
        lo, hi = p.tau_prediction_interval_kPa
        key = "tau_pred_pi95_kPa"
        json_lo = np.array([np.nan if t[key][m][0] is None else t[key][m][0] for t in rows])
        assert_array_equal(lo[:n], json_lo)
    b = r.back
    json_cap = np.array([np.nan if t["sigma_cap_kPa"] is None else t["sigma_cap_kPa"] for t in rows])
    assert_array_equal(b.sigma_cap_kPa[:n], json_cap)
    # a hand check of one wet test: sigma_cap = (tau_max - c)/tan(phi) - sigma_N, all in kPa
    wet = np.flatnonzero(r.tests["condition"] == "wet")[0]
    fit = r.fits[str(r.tests["material"][wet])]
    c, tan_phi = fit.params["c_kPa"].value, fit.params["tan_phi"].value
    expected = (r.tests["tau_max"][wet] / 1e3 - c) / tan_phi - r.tests["sigma_N"][wet] / 1e3
    # c_kPa and tan_phi are rounded nowhere; kPa vs Pa arithmetic differs in the last bits only
    assert b.sigma_cap_kPa[wet] == pytest.approx(expected, rel=1e-9)


def test_old_names_keep_pa_and_warn(run):
    """The old attribute gives the Pa value it gave before (the stored SI array itself) and names its replacement."""
    r, _ = run
    for m in r.models:
        p = r.predictions[m]
        for old, new in ModelPrediction.RENAMED.items():
            with pytest.warns(
                DeprecationWarning, match=rf"ModelPrediction\.{old} \[Pa\].*ModelPrediction\.{new} \[kPa\]"
            ):
                value = getattr(p, old)
            assert value is getattr(p.si, old)  # the very array the pipeline stored: old value, old unit
            new_value = getattr(p, new)
            pairs = zip(value, new_value) if isinstance(value, tuple) else [(value, new_value)]
            for si, kpa in pairs:
                assert_array_equal(np.asarray(si) * 1e-3, kpa)
    for old, new in BackAnalysis.RENAMED.items():
        with pytest.warns(DeprecationWarning, match=rf"BackAnalysis\.{old} \[Pa\].*BackAnalysis\.{new} \[kPa\]"):
            getattr(r.back, old)


def test_warning_points_at_the_caller(run):
    """The DeprecationWarning is attributed to the line that read the old name (a lab script's), not to capred."""
    r, _ = run
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r.back.sigma_cap  # noqa: B018
    assert caught and caught[0].filename == __file__


def test_si_view_and_replace_are_silent(run):
    """``rec.si.tau`` and ``rec.replace`` (capred's long run uses it) read the stored values silently;
    ``dataclasses.replace`` reads every field by its attribute and so meets the old names' warning (no reader is
    told apart by inspecting the call stack)."""
    r, _ = run
    p = r.predictions["bishop"]
    with warnings.catch_warnings():
        warnings.filterwarnings("error", category=DeprecationWarning, module=r"capred(\.|$)")
        q = p.replace(tau=p.si.tau * 2)
        assert_array_equal(q.tau_kPa, p.tau_kPa * 2)
        assert_array_equal(q.si.residual, p.si.residual)
        assert "tau_kPa" in repr(q) and "model='bishop'" in repr(q)
    with pytest.raises(AttributeError, match="no field 'nope'"):
        p.si.nope  # noqa: B018
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        q = dataclasses.replace(p, model="other")
    assert any(w.category is DeprecationWarning and "tau_kPa" in str(w.message) for w in caught)
    assert q.model == "other"
    assert_array_equal(q.si.tau, p.si.tau)


def test_headers_follow_the_declaration(run):
    """results.csv headers and JSON keys of the records are the declared patterns with the unit: unchanged."""
    r, _ = run
    cols = record_columns(r.predictions)
    assert "tau_pred_bishop [kPa]" in cols and "residual_bishop [kPa]" in cols
    assert "tau_pred_bishop_low95 [kPa]" in cols
    assert_array_equal(cols["tau_pred_bishop [kPa]"], r.predictions["bishop"].tau_kPa)
    keys = record_json_columns({None: r.back}, 0, 2)
    assert {"sigma_cap_kPa", "sigma_cap_se_kPa", "sigma_cap_ci95_kPa", "chi_back"} <= set(keys)


def test_sampled_values_scale():
    """A long run's sampled column gives its kPa attribute at the kept rows only."""
    s = Sampled(np.array([1, 4]), np.array([1000.0, 2500.0]), 10)
    rec = BackAnalysis(sigma_cap=s)
    assert_allclose(rec.sigma_cap_kPa[[1, 4]], [1.0, 2.5], rtol=1e-15)
    with pytest.raises(IndexError):
        rec.sigma_cap_kPa[2]


def test_cli_reads_no_deprecated_name(tmp_path):
    """Every figure, the console, the CSV/JSON writers and report.html of `capred shear --figures all`: no
    DeprecationWarning from capred's own code."""
    with warnings.catch_warnings():
        warnings.filterwarnings("error", category=DeprecationWarning, module=r"capred(\.|$)")
        res = CliRunner().invoke(app, ["shear", "--sample", "--figures", "all", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "o" / "results.csv").exists()


def test_user_units_on_any_record():
    """The decorator derives the attribute from the declared unit for any record: 1/kPa -> ``_per_kPa``, mm ->
    ``_mm``; a field without a scale keeps its one name. 2e-4 1/Pa = 0.2 1/kPa; 0.002 m = 2 mm (factors of the
    declarations)."""
    from capred.result import output, unit_suffix, user_units

    @user_units
    @dataclasses.dataclass(frozen=True, eq=False)
    class Toy:
        alpha: np.ndarray = output("alpha_per_kPa", "alpha", "1/kPa", 1e3)
        radius: np.ndarray = output("radius_mm", "radius", "mm", 1e3)
        n: np.ndarray = output("n", "n")

    t = Toy(alpha=np.array([2e-4]), radius=np.array([0.002]), n=np.array([1.5]))
    assert Toy.RENAMED == {"alpha": "alpha_per_kPa", "radius": "radius_mm"}
    assert_allclose(t.alpha_per_kPa, [0.2], rtol=1e-15)
    assert_allclose(t.radius_mm, [2.0], rtol=1e-15)
    with warnings.catch_warnings():
        warnings.filterwarnings("error", category=DeprecationWarning, module=r"capred(\.|$)")
        assert t.n[0] == 1.5  # not renamed: no warning
    with pytest.warns(DeprecationWarning, match=r"Toy\.alpha \[1/Pa\].*Toy\.alpha_per_kPa \[1/kPa\]"):
        assert t.alpha[0] == 2e-4
    assert unit_suffix("cm^3") == "cm3" and unit_suffix("N/m") == "N_per_m"
