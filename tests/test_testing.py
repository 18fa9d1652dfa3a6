"""capred.testing: the shipped conformance checks pass on every registry entry, catch broken entries, and pick up
an entry registered at run time (issue 42 item 4: adding a model is one declaration, checked by the shipped checks).
"""

import dataclasses
import re

import numpy as np
import pytest

from capred import testing
from capred.fitting import retention_models as rm
from capred.physics import bridge_laws as bl
from capred.physics import effective_stress_models as esm
from capred.reductions import REDUCTIONS, Reduction
from capred.spec import chi_laws

# --- every check over every entry of its registry --------------------------------------------------------------


@pytest.mark.parametrize("name", list(esm.REGISTRY))
def test_every_effective_stress_model_passes_its_check(name):
    testing.check_effective_stress_model(esm.REGISTRY[name])


@pytest.mark.parametrize("name", list(rm.MODELS))
def test_every_retention_model_passes_its_check(name):
    testing.check_retention_model(rm.MODELS[name])


@pytest.mark.parametrize("name", list(chi_laws.LAWS))
def test_every_chi_law_passes_its_check(name):
    testing.check_chi_law(chi_laws.LAWS[name])


@pytest.mark.parametrize("name", list(bl.LAWS))
def test_every_bridge_law_passes_its_check(name):
    testing.check_bridge_law(bl.LAWS[name])


@pytest.mark.parametrize("name", list(REDUCTIONS))
def test_every_command_passes_its_declaration_check(name):
    testing.check_command(REDUCTIONS[name])


@pytest.mark.parametrize("name", list(REDUCTIONS))
def test_every_command_example_runs_and_writes_its_declared_outputs(name, tmp_path):
    # without figures and report.html (those are test_conformance's): well under a second a command here
    testing.check_command(REDUCTIONS[name], run=True, out=tmp_path / "o")
    assert any((tmp_path / "o").glob("*.json"))


# --- the checks fail on broken entries ------------------------------------------------------------------------


def _half_bishop(**changes):
    kw = dict(
        name="half_bishop",
        label="Half Bishop",
        requires=(),
        reference="bishop1959",
        sigma_eff=lambda d: d.sigma_N + 0.5 * d.S_R * d.suction,
        style={"color": "blue", "marker": "x"},
        method="Half Bishop: σ'_N = σ_N + S_R Δu/2.",
    )
    return esm.EffectiveStressModel(**{**kw, **changes})


def test_a_sound_script_model_passes():
    testing.check_effective_stress_model(_half_bishop())


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"name": "Half Bishop"}, "name must be lower case"),
        ({"name": "all"}, "selection word"),
        ({"name": "bishop"}, "another entry is registered"),
        ({"label": "Bishop"}, "another model's"),
        ({"reference": "nobody2099"}, "not a key of capred.references"),
        ({"method": " "}, "method text is empty"),
        ({"style": {"color": "red", "marker": "o"}}, "style colour"),
        ({"requires": (("kappa_x", "--kappa-x"),)}, "not a ModelParams field"),
        ({"sigma_eff": "capred.physics.effective_stress_models:_nothing"}, "does not resolve"),
        ({"tau": lambda d: d.sigma_N}, "give sigma_eff or tau, one"),
        ({"sigma_eff": lambda d: d.sigma_N + 0.5 * d.S_R * d.suction + 1e3}, "at zero suction"),
        ({"sigma_eff": lambda d: d.sigma_N[:2]}, "gives shape (2,)"),
        ({"sigma_eff": lambda d: d.sigma_N * (1 + d.S_R * d.suction / 1e5)}, "changes with σ_N"),
        ({"sigma_eff": lambda d: d.sigma_N * np.nan}, "NaN without declaring no_prediction"),
        ({"chi_of_saturation": lambda S, p, f: np.asarray(S)}, "σ'_N ≠ σ_N + χ(S_R) s"),
        ({"chi_of_saturation": lambda S, p, f: 0.5 - np.asarray(S)}, "negative"),
        ({"fitted": ("kappa",)}, "no χ law"),
        ({"material_values": lambda d: {"phi b": 1.0}}, "not a JSON key"),
    ],
)
def test_a_broken_effective_stress_model_is_caught(changes, message):
    with pytest.raises(AssertionError, match=re.escape(message)) as err:
        testing.check_effective_stress_model(_half_bishop(**changes))
    assert "effective-stress model" in str(err.value)


def test_a_check_refuses_what_is_not_an_entry():
    with pytest.raises(ValueError, match="EffectiveStressModel is needed"):
        testing.check_effective_stress_model(rm.MODELS["vg"])
    for check in (testing.check_retention_model, testing.check_chi_law, testing.check_bridge_law):
        with pytest.raises(ValueError, match="is needed"):
            check(esm.REGISTRY["bishop"])
    with pytest.raises(ValueError, match="Reduction is needed"):
        testing.check_command("shear")


def _toy_exp(**changes):
    a = rm._p("a_exp", "$a$", "1/Pa", "decay rate", "inverse_suction", 1e-3, 1e3, 0.0, 6)
    a = dataclasses.replace(a, domain="a > 0 (a toy)")
    kw = dict(
        name="toy_exp",
        label="Exponential",
        equation="Sₑ = exp(−a s)",
        parameters=(rm.Y_R, rm.Y_S, a),
        saturation=lambda s, a_exp: np.exp(-a_exp * np.asarray(s, float)),
        references=("vangenuchten1980",),
        method="Toy: θ = θ_r + (θ_s − θ_r) exp(−a s).",
        help="toy_exp: exponential toy",
        inverse=lambda S, a_exp: -np.log(S) / a_exp,
    )
    return rm.RetentionModel(**{**kw, **changes})


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"help": "an exponential toy"}, "does not start with 'toy_exp:'"),
        ({"references": ("nobody2099",)}, "not a key of capred.references"),
        ({"parameters": (rm.Y_S, rm.Y_R, rm.MODELS["vg"].parameter("alpha"))}, "must start with"),
        ({"saturation": lambda s, a_exp: 1.0 - np.exp(-a_exp * np.asarray(s, float))}, "S\\(0\\) = 0"),
        ({"saturation": lambda s, a_exp: 2.0 * np.exp(-a_exp * np.asarray(s, float))}, "leaves \\[0, 1\\]"),
        ({"inverse": lambda S, a_exp: -np.log(S) / (2 * a_exp)}, "does not give s back"),
        ({"steps": (("alpha2", "n2"),)}, "steps, grid_order"),
    ],
)
def test_a_broken_retention_model_is_caught(changes, message):
    testing.check_retention_model(_toy_exp(), fit=False)  # the sound one passes
    with pytest.raises(AssertionError, match=message):
        testing.check_retention_model(_toy_exp(**changes), fit=False)


def test_a_broken_chi_law_is_caught(monkeypatch):
    sound = chi_laws.LAWS["chi_power"]

    def check(broken):
        monkeypatch.setitem(chi_laws.LAWS, "chi_power", broken)  # in its model's name, where a law belongs
        testing.check_chi_law(broken)

    with pytest.raises(AssertionError, match="leaves \\[0, 1\\]"):
        check(dataclasses.replace(sound, chi=lambda S_R, s, kappa: 2 * np.asarray(S_R) + 0 * s))

    def off(w, mp, start=None, dry=None):
        law = sound.fit(w, mp, start, dry)
        return dataclasses.replace(law, values={"kappa": 1.1 * law.values["kappa"]})

    with pytest.raises(AssertionError, match="fit gives kappa"):
        check(dataclasses.replace(sound, fit=off))
    with pytest.raises(AssertionError, match="no typical value"):
        check(dataclasses.replace(sound, typical={}))
    # a χ that is not its model's (S_R^(κ+1) instead of S_e^κ): in [0, 1] and 1 at saturation all the same
    with pytest.raises(AssertionError, match="the model's σ'_N ≠ σ_N \\+ χ s of the law"):
        check(dataclasses.replace(sound, chi=lambda S_R, s, kappa: np.asarray(S_R, float) ** (kappa + 1) + 0 * s))
    with pytest.raises(AssertionError, match="another entry is registered"):
        monkeypatch.setitem(chi_laws.LAWS, "chi_power", sound)
        testing.check_chi_law(dataclasses.replace(sound, typical={"kappa": 3.0}))


def _toy_contact(**changes):
    kw = dict(
        name="toy_contact",
        label="Toy contact",
        citation="Israelachvili (2011), Intermolecular and Surface Forces, 3rd ed.",
        doi="10.1016/C2009-0-21560-1",
        equation="F/(2πR*γ) = cos θ",
        validity="spheres in contact",
        geometries=("equal", "unequal", "plane"),
        force=lambda theta, V, D, rho: bl.effective_radius(rho) * np.cos(theta) / (1 + np.asarray(D) / 0.1) + 0 * V,
    )
    return bl.Law(**{**kw, **changes})


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"doi": "doi:10.1016/x"}, "is not 10.NNNN"),
        ({"citation": "Israelachvili, Intermolecular and Surface Forces"}, "no year"),
        ({"geometries": ("cube",)}, "geometries"),
        # a force in N of a 1 mm sphere instead of F/(2 pi R gamma): 2 pi R gamma = 4.6e-4 of the dimensionless one
        (
            {"force": lambda theta, V, D, rho: 2 * np.pi * 1e-3 * 0.0728 * np.cos(theta) + 0 * np.asarray(D)},
            "Derjaguin",
        ),
        (
            {"force": lambda theta, V, D, rho: np.cos(theta) * (np.asarray(D) - 0.01)},
            "not finite and ≥ 0",
        ),
        ({"force": lambda theta, V, D, rho: np.cos(theta) * (1 + np.asarray(D))}, "grows with the gap"),
    ],
)
def test_a_broken_bridge_law_is_caught(changes, message):
    testing.check_bridge_law(_toy_contact())  # the sound one passes
    with pytest.raises(AssertionError, match=message):
        testing.check_bridge_law(_toy_contact(**changes))


def test_a_broken_command_is_caught():
    sound = REDUCTIONS["bridge curve"]
    with pytest.raises(AssertionError, match="does not resolve"):
        testing.check_command(
            dataclasses.replace(sound, name="bridge curvy", options_path="capred.pipelines.bridge:Nope")
        )
    with pytest.raises(AssertionError, match="are not options"):
        testing.check_command(dataclasses.replace(sound, name="bridge curvy", example=(("pointz", 5),)))
    with pytest.raises(AssertionError, match="not a key of capred.samples"):
        testing.check_command(dataclasses.replace(sound, name="bridge curvy", sample="nothing"))
    with pytest.raises(AssertionError, match="another entry is registered"):
        testing.check_command(dataclasses.replace(sound, summary="another"))
    with pytest.raises(AssertionError, match="options of the example raised"):
        testing.check_command(dataclasses.replace(sound, name="bridge curvy", example=(("points", -5),)))
    with pytest.raises(AssertionError, match="the example run raised"):  # its run function is another command's
        wrong = dataclasses.replace(sound, name="bridge curvy", run_path="capred.pipelines.bridge:compare_measured")
        testing.check_command(wrong, run=True)
    assert isinstance(sound, Reduction)


# --- one declaration, picked up by the registry's lookups and by its check ------------------------------------


def test_an_effective_stress_model_registered_at_run_time_is_checked_and_listed(monkeypatch):
    entry = _half_bishop(chi_of_saturation=lambda S, p, f: 0.5 * np.asarray(S, float))
    monkeypatch.setitem(esm.REGISTRY, "half_bishop", entry)
    testing.check_effective_stress_model(entry)
    assert "half_bishop" in esm.resolve_models("all") and esm.resolve_models("half-bishop") == ("half_bishop",)
    assert esm.MODEL_LABELS["half_bishop"] == "Half Bishop"
    # predict(): σ'_N of a wet test by hand, 100 kPa + 0.5 * 0.5 * 20 kPa = 105 kPa
    d = esm.ModelInputs.of_unit_cell(100e3, 20e3, 0.5, np.nan, 0.0728)
    d = dataclasses.replace(d, c=np.array(0.0), tan_phi=np.array(1.0))
    eff, tau = esm.predict("half_bishop", d)
    assert float(eff) == pytest.approx(105e3, rel=1e-15) and float(tau) == pytest.approx(105e3, rel=1e-15)


def test_a_retention_model_registered_at_run_time_is_checked_and_fitted(monkeypatch):
    # declared with "module:function" strings, as the shipped models are, and with callables, as a script may
    entry = _toy_exp(
        name="vg_copy",
        help="vg_copy: van Genuchten again",
        parameters=rm.MODELS["vg"].parameters,
        saturation="capred.fitting.retention_models:_vg_saturation",
        inverse="capred.fitting.retention_models:_vg_inverse",
    )
    monkeypatch.setitem(rm.MODELS, "vg_copy", entry)
    testing.check_retention_model(entry)  # includes a fit of exact data through fit_model("vg_copy", ...)
    toy = _toy_exp()
    monkeypatch.setitem(rm.MODELS, "toy_exp", toy)
    testing.check_retention_model(toy)
    assert {"vg_copy", "toy_exp"} <= set(rm.REGISTRY)
    s = np.array([0.0, 1e4])
    assert np.allclose(entry.saturation(s, alpha=1e-4, n=2.0), [1.0, 2**-0.5], rtol=1e-15)  # [1 + 1]^(-1/2)


def test_a_chi_law_registered_at_run_time_is_checked_and_listed(monkeypatch):
    # chi = S_R^a with a fitted: the law (its fit reuses chi_power's, a renamed) and its effective-stress model
    from capred.fitting import chi_laws as fit_chi

    def chi(S_R, s, a):
        return fit_chi.chi_power_law(S_R, s, a)

    def fit(w, mp, start=None, dry=None):
        law = fit_chi.fit_chi_power(w.sigma_N, w.suction, w.S_R, w.tau_max, w.c, w.tan_phi, 0.0, None, dry)
        return dataclasses.replace(law, values={"a": law.values["kappa"]})

    def refit(w, mp, c, b, weights, start):
        p, r = fit_chi.refit_chi_power_batch(w.sigma_N, w.suction, w.S_R, w.tau_max, c, b, weights, start["a"])
        return {"a": p["kappa"]}, r

    monkeypatch.setitem(fit_chi.LAW_PARAMETERS, "a", ("a", 1.0, "-", "exponent a of χ = S_R^a"))
    law = chi_laws.ChiLaw(fit, refit, name="toy_power", parameters=("a",), typical={"a": 1.5}, chi=chi)
    model = _half_bishop(
        name="toy_power",
        label="χ = S_R^a (fitted)",
        sigma_eff=lambda d: d.sigma_N + d.S_R ** d.per_test("toy_power", "a") * d.suction,
        fitted=("a",),
        method="Toy: χ = S_R^a with a fitted per material.",
    )
    monkeypatch.setitem(chi_laws.LAWS, "toy_power", law)
    monkeypatch.setitem(esm.REGISTRY, "toy_power", model)
    testing.check_chi_law(law)
    testing.check_effective_stress_model(model)
    assert "toy_power" in esm.resolve_models("all") and "toy_power" in fit_chi.LAWS


def test_a_bridge_law_registered_at_run_time_is_checked_and_used(monkeypatch):
    law = _toy_contact()
    monkeypatch.setitem(bl.LAWS, "toy_contact", law)
    testing.check_bridge_law(law)
    # law_force reads the registry: cos(0) * R*/R1 at contact, R* = 2 R1 on a plane, NaN for no geometry missing
    assert bl.law_force("toy_contact", 0.0, 1e-3, 0.0, np.inf) == pytest.approx(2.0, rel=1e-15)
    assert list(bl.LAWS)[-1] == "toy_contact"


def test_registrations_are_undone():
    # monkeypatch removed every entry the tests above registered
    assert not {"half_bishop", "toy_power"} & set(esm.REGISTRY)
    assert not {"vg_copy", "toy_exp"} & set(rm.MODELS)
    assert "toy_contact" not in bl.LAWS and "toy_power" not in chi_laws.LAWS


def test_the_contributing_guide_example_passes_its_check():
    # docs/contributing.md's half_bishop block, run as written: its check passes and it is registered
    from pathlib import Path

    text = (Path(__file__).parents[1] / "docs" / "contributing.md").read_text(encoding="utf-8")
    (block,) = [b for b in re.findall(r"```python\n(.*?)```", text, re.S) if "half_bishop" in b]
    try:
        exec(compile(block, "contributing.md", "exec"), {})
        assert esm.REGISTRY["half_bishop"].label == "Half Bishop"
        assert "half_bishop" in esm.resolve_models("all")
    finally:
        esm.REGISTRY.pop("half_bishop", None)
    assert "half_bishop" not in esm.REGISTRY
