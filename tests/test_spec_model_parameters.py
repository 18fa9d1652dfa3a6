"""A model's own parameter, declared once in its registry entry (issue 42, "an effective-stress model with a CLI
parameter is one declaration"): `capred shear` takes ``--<name>`` with the declared unit and range, the API takes
``ModelParams(extra=...)``, the model reads ``d.params.<name>``.

The registry entry's field is ``parameters`` (a tuple of capred.spec.shear.ModelParameter).
"""

import dataclasses
import json
import math

import pytest
from typer.testing import CliRunner

import capred.nomenclature as nom
import capred.spec.effective_stress as es
from capred.cli import app
from capred.errors import OptionError
from capred.spec.shear import ModelParameter, ModelParams, model_parameters

runner = CliRunner()


def _scaled_bishop(d):
    """σ'_N = σ_N + κ S_R Δu: Bishop's χ = S_R scaled by the model's own κ (κ = 1 is Bishop, κ = 0 no suction)."""
    return d.sigma_N + d.params.my_kappa * d.S_R * d.suction


KAPPA = ModelParameter(
    "my_kappa", nom.Quantity("κ_my", "-", 1.0, "dimensionless", "scale of Bishop's χ of the scaled model", 0.0, 2.0)
)


@pytest.fixture
def scaled_bishop(monkeypatch):
    entry = es.EffectiveStressModel(
        "scaled_bishop",
        "scaled Bishop",
        (("my_kappa", "--my-kappa"),),
        "bishop1959",
        _scaled_bishop,
        parameters=(KAPPA,),
        method="σ'_N = σ_N + κ S_R Δu.",
    )
    monkeypatch.setitem(es.REGISTRY, "scaled_bishop", entry)
    monkeypatch.setitem(nom.QUANTITIES, "my_kappa", KAPPA.quantity)  # registered by model_parameters; undone here
    return entry


def _run(*args):
    res = runner.invoke(app, ["shear", "--sample", "--json", "--bootstrap", "0", "--no-plots", "--no-html", *args])
    return res, (json.loads(res.stdout) if res.exit_code == 0 else None)


def test_the_declared_parameter_is_an_option_of_shear_with_its_unit_and_range(scaled_bishop):
    res = runner.invoke(app, ["shear", "--help"], terminal_width=200)
    text = " ".join(res.stdout.split())
    assert "--my-kappa NUMBER Scale of Bishop's χ of the scaled model κ_my [0 to 2]; of model scaled_bishop." in text
    assert "my_kappa" in model_parameters()


def test_kappa_one_is_bishop_and_kappa_zero_no_suction(scaled_bishop):
    """κ = 1 gives Bishop's σ'_N exactly and κ = 0 the dry one: the predictions equal those models' to rounding
    (the same operations on the same numbers: relative 1e-12)."""
    for kappa, same_as in (("1", "bishop"), ("0", "no_suction")):
        res, js = _run("--models", f"{same_as},scaled_bishop", "--my-kappa", kappa)
        assert res.exit_code == 0, res.output
        assert js["options"]["model_params"]["extra"] == {"my_kappa": float(kappa)}
        wet = [t for t in js["tests"] if t["condition"] == "wet"]
        assert wet
        for t in wet:
            assert t["tau_pred_kPa"]["scaled_bishop"] == pytest.approx(t["tau_pred_kPa"][same_as], rel=1e-12)


def test_the_declared_range_and_the_requirement_are_checked(scaled_bishop):
    res, _ = _run("--models", "scaled_bishop", "--my-kappa", "3")
    assert res.exit_code == 1 and "my_kappa (--my-kappa)" in res.stderr and "Traceback" not in res.output
    res, _ = _run("--models", "scaled_bishop")
    assert res.exit_code == 1 and "model 'scaled_bishop' needs --my-kappa" in res.stderr


def test_the_api_takes_it_in_extra_and_the_record_keeps_it_only_when_given(scaled_bishop):
    p = ModelParams(extra={"my_kappa": 0.5})
    assert p.my_kappa == 0.5 and p.extra == {"my_kappa": 0.5}
    assert "extra" not in ModelParams().record()[0]  # JSON keys of a run without one unchanged
    assert ModelParams().my_kappa is None  # declared, not given
    with pytest.raises(OptionError, match="no registered model declares nope"):
        ModelParams(extra={"nope": 1.0})
    with pytest.raises(OptionError, match="my_kappa"):
        ModelParams(extra={"my_kappa": math.nan})


def test_triaxial_takes_the_declared_parameter_too(scaled_bishop):
    res = runner.invoke(app, ["triaxial", "--help"], terminal_width=200)
    assert "--my-kappa NUMBER" in " ".join(res.stdout.split())


def test_a_model_with_its_own_parameter_is_checked_before_it_is_registered():
    """docs/contributing.md checks a model, then registers it: the check reads the model's own parameter at its
    declared default (κ = 1: Bishop) and leaves the registry and the glossary as they were."""
    from capred.testing import check_effective_stress_model

    entry = es.EffectiveStressModel(
        "scaled_bishop_unregistered",
        "scaled Bishop (unregistered)",
        (),
        "bishop1959",
        _scaled_bishop,
        parameters=(dataclasses.replace(KAPPA, default=1.0),),
        style={"color": "blue", "marker": "x"},
        method="σ'_N = σ_N + κ S_R Δu.",
    )
    before, glossary = dict(es.REGISTRY), dict(nom.QUANTITIES)
    check_effective_stress_model(entry)
    assert es.REGISTRY == before and nom.QUANTITIES == glossary
