"""One meaning per name (issue 18, item 4): no ambiguous name in the public signatures of capred.

Walked: every public function and class defined in a module of capred.physics, capred.fitting,
capred.pipelines and capred.spec (the declarations: options and registries), and every object of the capred API (``capred.__all__``). For a function, its parameters;
for a class, the parameters of its constructor, its dataclass fields, the parameters of its public methods
and its public properties.

Rejected: the bare symbols that carried two or three meanings in capred -- ``theta`` (contact angle, water
content, Lode angle, filling angle), ``alpha`` (van Genuchten's alpha, Brooks-Corey's index), ``phi``,
``rho``, ``kappa`` (elastic slope, url slope, Vanapalli's exponent), ``lam`` -- and any spelling of the
degree of saturation but the glossary's ``S_R`` (``sr``, ``Sr``, ``S_r``, also inside a longer name such as
``sr_max``), and ``theta`` inside a longer name (``theta_deg``). The glossary's names are
capred/nomenclature.py: ``contact_angle``, ``filling_angle``, ``lode_angle``, ``water_content``,
``vg_alpha``, ``bc_lambda``, ``S_R``, ``kappa_elastic``, ``ncl_slope``, ``url_slope``, ``vanapalli_kappa``.
"""

import dataclasses
import importlib
import inspect
import pkgutil
import re
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose

import capred
import capred.fitting
import capred.physics
import capred.pipelines
import capred.spec
from capred.nomenclature import QUANTITIES, renamed_keywords

PACKAGES = (capred.physics, capred.fitting, capred.pipelines, capred.spec)

AMBIGUOUS = {"theta", "alpha", "phi", "rho", "kappa", "lam", "sr", "Sr", "S_r"}
_IN_A_NAME = re.compile(r"(^|_)(theta|sr|Sr|S_r)(_|$)")

#: (object, name) kept on purpose: the paper's own symbol, with one meaning in the glossary.
ALLOWED = {
    # glossary "phi": the friction angle phi [deg] (Prunier et al. 2024 write phi'); Envelope.phi is that angle
    # in degrees, beside c [Pa] -- the one meaning "phi" has in capred/nomenclature.py.
    ("capred.pipelines.triaxial_records.Envelope", "phi"): "glossary 'phi': friction angle [deg]",
    # the shear envelope's numbers, named by their glossary keys (phi: the friction angle [deg], as above)
    ("capred.pipelines.shear_records.EnvelopeNumbers", "phi"): "glossary 'phi': friction angle [deg]",
    # the fitted law chi_power's parameter, named as its JSON key and its registry entry's fitted=("kappa",)
    # (capred.testing calls a law with **entry.typical, keyed by those names): one meaning, the fitted exponent
    ("capred.fitting.chi_laws.chi_power_law", "kappa"): "chi_power's fitted exponent, its JSON key 'kappa'",
}

#: (object, name) whose rename waits for a file another engineer owns this round (non-strict xfail below:
#: an entry that is done shows as XPASS -- then delete it here, and the alias it needed).


def is_ambiguous(name: str) -> bool:
    """True for a name the glossary replaces (see the module docstring)."""
    return name in AMBIGUOUS or bool(_IN_A_NAME.search(name))


def public_names(obj) -> list[str]:
    """Every public name a caller of ``obj`` types: parameters, fields, method parameters, properties."""
    out: list[str] = []
    try:
        out += [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]
    except (TypeError, ValueError):
        pass
    if inspect.isclass(obj):
        if dataclasses.is_dataclass(obj):
            out += [f.name for f in dataclasses.fields(obj)]
        for attr, value in vars(obj).items():
            if attr.startswith("_"):
                continue
            if isinstance(value, (staticmethod, classmethod)):
                value = value.__func__
            if inspect.isfunction(value):
                out += [p for p in inspect.signature(value).parameters if p not in ("self", "cls")]
            elif isinstance(value, property):
                out.append(attr)
    return list(dict.fromkeys(out))


def _walked():
    """(qualified name, object) of every public function and class walked."""
    seen = {}
    for pkg in PACKAGES:
        for info in pkgutil.iter_modules(pkg.__path__):
            module = importlib.import_module(f"{pkg.__name__}.{info.name}")
            for name, obj in vars(module).items():
                if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
                    continue
                if inspect.isfunction(obj) or inspect.isclass(obj):
                    seen[f"{module.__name__}.{name}"] = obj
    for name in capred.__all__:
        if name != "__version__":
            obj = getattr(capred, name)
            target = inspect.unwrap(obj)
            seen.setdefault(f"{target.__module__}.{target.__qualname__}", obj)
    return seen


WALKED = _walked()


def violations() -> set[tuple[str, str]]:
    return {(q, n) for q, obj in WALKED.items() for n in public_names(obj) if is_ambiguous(n)}


def test_the_checker_flags_what_it_should():
    def old(theta, S_r, sr_max, kappa, alpha, lam, theta_deg):
        """Every name here is ambiguous."""

    def new(
        contact_angle_rad,
        S_R,
        S_R_max,
        kappa_elastic,
        vg_alpha,
        bc_lambda,
        contact_angle_deg,
        lode_angle,
        phi_deg,
        tan_phi,
        rho_w,
        kappa_W,
        S_res,
        vanapalli_kappa,
    ):
        """None is: glossary names and names with their unit or subscript."""

    assert [n for n in public_names(old) if is_ambiguous(n)] == list(inspect.signature(old).parameters)
    assert [n for n in public_names(new) if is_ambiguous(n)] == []


def test_the_walk_covers_the_four_packages_and_the_api():
    assert "capred.physics.bridge.bridge" in WALKED
    assert "capred.fitting.chi_laws.chi_power" in WALKED
    assert "capred.spec.calculators.SkemptonOptions" in WALKED
    assert "capred.pipelines.calculators.run_skempton_b" in WALKED
    assert len(WALKED) > 100  # about 200 functions and classes today


def test_no_ambiguous_name_in_public_signatures():
    left = sorted(violations() - set(ALLOWED))
    assert not left, (
        "ambiguous names (use the glossary of capred/nomenclature.py, or a name with its unit): "
        + ", ".join(f"{q}({n})" for q, n in left)
    )


def test_allowed_entries_exist_and_are_glossary_names():
    # an allow-list entry that no longer matches anything is stale; each allowed name is a glossary key
    found = violations()
    for q, n in ALLOWED:
        assert (q, n) in found, f"stale ALLOWED entry {q}({n})"
        assert n in QUANTITIES


# --- the old keywords keep working for one release, and the output keys do not change ---------------------------


def _quiet_run(f, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = f(**kw)
    return res, [w for w in caught if issubclass(w.category, DeprecationWarning)]


def test_run_skempton_b_old_keywords_warn_and_agree():
    # Morvan et al. (2016) eq. 10 by hand: B = 1/(1 + 70e3 * 0.8 * (1 - 0.9)/(0.06 * 130e3)) = 1/(1 + 5600/7800)
    B = 1.0 / (1.0 + 5600.0 / 7800.0)  # 0.58209, their Fig. 2 reads 0.58
    new, w_new = _quiet_run(capred.run_skempton_b, S_R=0.9, kappa_elastic=0.06)
    old, w_old = _quiet_run(capred.run_skempton_b, sr=0.9, kappa=0.06)
    assert_allclose([new.to_json()["B"], old.to_json()["B"]], B, rtol=1e-12)  # closed form: rounding only
    assert not w_new and {str(w.message).split("'")[1] for w in w_old} == {"sr", "kappa"}
    # the JSON keeps the option keys users have
    assert {"sr", "kappa"} <= set(new.to_json()["options"]) and "S_R" not in new.to_json()["options"]
    assert set(new.to_json()["cases"][0]) >= {"S_r", "kappa", "B"}


def test_run_rumpf_and_bridge_curve_old_keywords():
    new, _ = _quiet_run(capred.run_rumpf, shape_factor=1, void_ratio=0.5, S_R=0.3, diameter=2e-4)
    old, w = _quiet_run(capred.run_rumpf, shape_factor=1, void_ratio=0.5, sr=0.3, diameter=2e-4)
    # Prunier et al. (2024) eq. 19 by hand: -(6/1)(0.3/0.5)(0.0728/2e-4) cos 0 = -1310.4 Pa
    assert_allclose([new.to_json()["p_cap_kPa"], old.to_json()["p_cap_kPa"]], -1.3104, rtol=1e-12)
    assert len(w) == 1 and new.to_json()["options"]["sr"] == 0.3
    curve, w = _quiet_run(capred.bridge_curve, points=20, theta_deg=30.0, sr_max=0.1)
    assert len(w) == 2 and curve.to_json()["contact_angle_deg"] == pytest.approx(30.0, rel=1e-12)
    assert curve.to_json()["options"]["sr_max"] == 0.1 and curve.contact_angle_rad == pytest.approx(0.5235987756)


def test_renamed_keywords_refuses_both_spellings():
    @renamed_keywords(sr="S_R")
    def f(S_R=None):
        return S_R

    with pytest.warns(DeprecationWarning, match="use 'S_R'"):
        assert f(sr=0.4) == 0.4
    with pytest.raises(TypeError, match="both 'sr' and its new name 'S_R'"):
        f(sr=0.4, S_R=0.5)
    assert list(inspect.signature(f).parameters) == ["S_R"]


def test_suction_at_neck_takes_ratio_and_still_the_old_rho():
    """R2/R1 is ``ratio`` as in bridge(), from_neck() and the solvers; ``rho=`` keeps working with a warning.
    The suction is recovered from the gap (and the volume) of the bridges from_neck builds at a known s*:
    a root found by Illinois iterations against a closed-form filling angle, so rtol 1e-9 (the root's tol is
    1e-14 in q = s* y0^2/(1 + s* y0^2); the quadrature of gap and volume is the same on both sides)."""
    from capred.physics import bridge as br

    neck, angle, s_true, ratio = [0.3, 0.2], [0.3, 0.3], [5.0, 20.0], [1.0, 2.0]
    _, b = br.from_neck(np.array(neck), np.array(angle), np.array(s_true), np.array(ratio))
    new, w_new = _quiet_run(
        br.suction_at_neck, y0=np.array(neck), th=np.array(angle), ratio=np.array(ratio), target=b.gap, field="gap"
    )
    old, w_old = _quiet_run(
        br.suction_at_neck, y0=np.array(neck), th=np.array(angle), rho=np.array(ratio), target=b.volume, field="volume"
    )
    assert_allclose(new, s_true, rtol=1e-9)
    assert_allclose(old, s_true, rtol=1e-9)
    assert not w_new and len(w_old) == 1 and "use 'ratio'" in str(w_old[0].message)
    assert "rho" not in inspect.signature(br.suction_at_neck).parameters
