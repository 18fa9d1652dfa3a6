"""Conformance checks of capred's registry entries, shipped so that a lab script can run them on its own entry.

As scikit-learn ships ``utils.estimator_checks``, each check takes one registry entry, runs what every entry of
its family must satisfy on small synthetic inputs whose answers can be checked by hand, and raises
``AssertionError`` naming the entry and what is wrong (``ValueError`` for an argument that is not an entry)::

    from capred.physics.effective_stress_models import REGISTRY, EffectiveStressModel
    from capred.testing import check_effective_stress_model

    half = EffectiveStressModel("half_bishop", "Half Bishop", (), "bishop1959",
                                sigma_eff=lambda d: d.sigma_N + 0.5 * d.S_R * d.suction)
    check_effective_stress_model(half)

capred's own test suite runs every check over every entry of every registry (tests/test_testing.py).

- `check_effective_stress_model`: an entry of `capred.spec.effective_stress.REGISTRY`;
- `check_retention_model`: an entry of `capred.spec.retention_models.MODELS`;
- `check_chi_law`: an entry of `capred.spec.chi_laws.LAWS`;
- `check_bridge_law`: an entry of `capred.spec.bridge_laws.LAWS`;
- `check_command`: an entry of `capred.reductions.REDUCTIONS` (``run=True`` also runs its example).
"""

from __future__ import annotations

import math
import re
from contextlib import contextmanager

import numpy as np

from .references import REFERENCES
from .spec.callables import ref_of, resolve

__all__ = [
    "check_bridge_law",
    "check_chi_law",
    "check_command",
    "check_effective_stress_model",
    "check_retention_model",
]

#: a registry name: what ``--models`` / ``--model`` / JSON keys and CSV columns can spell
NAME = re.compile(r"^[a-z][a-z0-9_]*$")
#: words ``--models`` reads as selections, never model names
RESERVED = ("all", "thesis")
#: the colour names of capred's one palette (Okabe & Ito), which a model's style may use
COLOURS = ("black", "orange", "sky", "green", "yellow", "blue", "vermillion", "purple", "grey")


class _Check:
    """Collect every problem of one entry, then raise once (as capred reports a file's problems)."""

    def __init__(self, kind: str, name):
        self.where = f"{kind} {name!r}"
        self.problems: list[str] = []

    def that(self, ok, problem: str) -> bool:
        if not ok:
            self.problems.append(problem)
        return bool(ok)

    def done(self) -> None:
        if self.problems:
            raise AssertionError(f"{self.where}: " + "; ".join(self.problems))


def _name(chk: _Check, name, registry, entry) -> None:
    chk.that(isinstance(name, str) and NAME.match(name), "name must be lower case letters, digits and _")
    chk.that(name not in RESERVED, f"name {name!r} is a selection word of --models")
    if name in registry:
        chk.that(registry[name] is entry, f"another entry is registered as {name!r}")


def _callable(chk: _Check, entry, field: str, required: bool = False):
    """The callable of a field, or None with the problem noted."""
    ref = ref_of(entry, field)
    if ref is None:
        chk.that(not required, f"{field} is missing")
        return None
    try:
        return resolve(ref)
    except (ValueError, ImportError) as exc:
        chk.that(False, f"{field} {ref!r} does not resolve ({exc})")
        return None


def _reference(chk: _Check, key, what="reference") -> None:
    chk.that(key in REFERENCES, f"{what} {key!r} is not a key of capred.references.REFERENCES")


def _text(chk: _Check, entry, *fields) -> None:
    for f in fields:
        chk.that(isinstance(getattr(entry, f), str) and getattr(entry, f).strip(), f"{f} text is empty")


def _run(chk: _Check, what: str, f, *args, **kw):
    """``f(*args, **kw)``, or None with the exception noted."""
    try:
        return f(*args, **kw)
    except Exception as exc:  # a check reports every failure of the entry's own code
        chk.that(False, f"{what} raised {type(exc).__name__}: {exc}")
        return None


# --- effective-stress models ---------------------------------------------------------------------------------------

#: the synthetic wet tests (SI): four stresses, suctions and degrees of saturation of a pendular sand, R = 0.5 mm
_SIGMA_N = np.array([50e3, 100e3, 150e3, 200e3])  # Pa
_SUCTION = np.array([2e3, 5e3, 10e3, 20e3])  # Pa
_S_R = np.array([0.04, 0.06, 0.08, 0.10])  # -, inside the pendular range of the exact bridge
_C, _TAN_PHI = 2e3, math.tan(math.radians(35.0))  # dry envelope: c = 2 kPa, phi = 35 deg


def _model_params():
    """Run parameters every shipped model can use: Vanapalli's S_res and κ, Khalili's air entry, van Genuchten's."""
    from .pipelines.shear import ModelParams

    return ModelParams(s_res=0.0, vanapalli_kappa=1.5, air_entry=3e3, vg_alpha=1e-4, vg_n=1.8, water_envelope=None)


def _inputs(entry, sigma_N=_SIGMA_N, suction=_SUCTION, S_R=_S_R, fitted=None):
    """Four wet tests of one material on the envelope of Bishop's σ' (τ by hand: c + (σ_N + S_R s) tan φ)."""
    from .physics.effective_stress_models import ModelInputs

    n = sigma_N.size
    tau = _C + (sigma_N + S_R * suction) * _TAN_PHI
    return ModelInputs(
        sigma_N=sigma_N.astype(float),
        suction=suction.astype(float),
        S_R=S_R.astype(float),
        R=np.full(n, 0.5e-3),
        tau_max=tau,
        wet=np.ones(n, bool),
        material=np.full(n, "sand"),
        c=np.full(n, _C),
        tan_phi=np.full(n, _TAN_PHI),
        surface_tension=0.0728,
        params=_model_params(),
        fitted={} if fitted is None else fitted,
    )


def _fitted(entry):
    """The material's fitted law parameters of a fitted model: its χ law's typical values."""
    if not entry.fitted:
        return None
    from .spec.chi_laws import LAWS

    law = LAWS.get(entry.name)
    typical = dict(getattr(law, "typical", None) or {})
    return {entry.name: {"sand": {p: typical.get(p, 1.0) for p in entry.fitted}}}


def check_effective_stress_model(entry) -> None:
    """Check an effective-stress model: its declaration, and its σ'_N (or τ) on four synthetic wet tests.

    Declaration: the name is a ``--models`` token, unique in the registry; label, method and reference (a key of
    `capred.references.REFERENCES`) present; style of the palette; each required parameter a field of
    `capred.pipelines.shear.ModelParams` (or one of the model's own ``parameters``) with its ``--option``;
    exactly one of ``sigma_eff`` and ``tau``; every callable resolves; a fitted model has its χ law. Numbers
    (four wet tests of one material, σ_N 50-200 kPa, s 2-20 kPa, S_R 0.04-0.10, R = 0.5 mm, c = 2 kPa, φ = 35°):

    - σ'_N (or τ) is a finite array of one value per test (NaN only for a model that declares ``no_prediction``);
    - σ'_N − σ_N does not depend on σ_N (shifting σ_N by 10 kPa shifts σ'_N by 10 kPa);
    - a test at zero suction (among three wet ones) has σ'_N = σ_N, unless the model reads the particle radius
      (a term 2γ/R of the meniscus);
      a τ model at S_R = 0 and zero suction gives the dry envelope c + σ_N tan φ;
    - ``chi_of_saturation`` (where given) is ≥ 0, non-decreasing in S_R on [0, 1], 0 at S_R = 0, and
      σ'_N = σ_N + χ(S_R) s on the tests;
    - ``material_values`` gives a dict of JSON-ready values; a ``bridge_curve`` model gives a finite,
      non-negative capillary stress on the unit cell.

    Parameters
    ----------
    entry : capred.spec.effective_stress.EffectiveStressModel
        The model, registered or not.

    Raises
    ------
    AssertionError
        Naming the model and every problem found.
    ValueError
        When ``entry`` is not an EffectiveStressModel.
    """
    from .spec.effective_stress import REGISTRY, EffectiveStressModel

    if not isinstance(entry, EffectiveStressModel):
        raise ValueError(f"an EffectiveStressModel is needed, not {type(entry).__name__}")
    if entry.name in REGISTRY and REGISTRY[entry.name] is not entry:  # never replace another entry, even for a check
        chk = _Check("effective-stress model", entry.name)
        _name(chk, entry.name, REGISTRY, entry)
        chk.done()
    with _registered_for_the_check(entry, REGISTRY):  # its own parameters are read as a registered model's
        _check_effective_stress_model(entry)


@contextmanager
def _registered_for_the_check(entry, registry: dict):
    """Hold ``entry`` in ``registry`` while the check runs; the registry and the glossary as they were after.

    A model checked before it is registered, as the docs show, reads its own parameters as it will once registered.
    """
    from .nomenclature import QUANTITIES

    if registry.get(entry.name) is entry:
        yield
        return
    glossary = dict(QUANTITIES)
    registry[entry.name] = entry
    try:
        yield
    finally:
        del registry[entry.name]
        QUANTITIES.clear()
        QUANTITIES.update(glossary)


def _check_effective_stress_model(entry) -> None:
    from .pipelines.shear import ModelParams
    from .spec.effective_stress import REGISTRY

    chk = _Check("effective-stress model", entry.name)
    _name(chk, entry.name, REGISTRY, entry)
    _text(chk, entry, "label", "method")
    _reference(chk, entry.reference)
    others = {e.label for k, e in REGISTRY.items() if e is not entry and k != entry.name}
    chk.that(entry.label not in others, f"label {entry.label!r} is another model's")
    chk.that(entry.style.get("color") in COLOURS, f"style colour {entry.style.get('color')!r} is not of {COLOURS}")
    chk.that(entry.style.get("marker"), "style has no marker")
    params = set(ModelParams.__dataclass_fields__) | {p.name for p in entry.parameters}  # its own too
    for field_name, option in entry.requires:
        chk.that(field_name in params, f"required {field_name!r} is not a ModelParams field")
        chk.that(isinstance(option, str) and option.startswith("--"), f"required {field_name!r}: option {option!r}")
    sigma_eff, tau = _callable(chk, entry, "sigma_eff"), _callable(chk, entry, "tau")
    chk.that((ref_of(entry, "sigma_eff") is None) != (ref_of(entry, "tau") is None), "give sigma_eff or tau, one")
    chi_of_s = _callable(chk, entry, "chi_of_saturation")
    values = _callable(chk, entry, "material_values")
    if entry.fitted:
        from .spec.chi_laws import LAWS

        chk.that(entry.name in LAWS, f"fitted {entry.fitted} but no χ law {entry.name!r} in capred.spec.chi_laws")
    if chk.problems:
        chk.done()

    fitted = _fitted(entry)
    d = _inputs(entry, fitted=fitted)
    f = sigma_eff or tau
    out = _run(chk, "sigma_eff" if sigma_eff else "tau", f, d)
    if out is not None:
        out = np.asarray(out, float)
        chk.that(out.shape == d.sigma_N.shape, f"gives shape {out.shape} for {d.sigma_N.size} tests")
        finite = np.isfinite(out)
        chk.that(finite.all() or entry.no_prediction is not None, "gives NaN without declaring no_prediction")
        chk.that(finite.any(), "predicts none of four ordinary wet tests")
    if sigma_eff is not None and out is not None and out.shape == d.sigma_N.shape:
        shifted = _run(chk, "sigma_eff", sigma_eff, _inputs(entry, sigma_N=_SIGMA_N + 10e3, fitted=fitted))
        if shifted is not None:
            ok = np.isfinite(out) & np.isfinite(shifted)
            # σ'_N = σ_N + (a term of s, S_R, R): the shift passes through to rounding of 200 kPa numbers
            chk.that(
                np.allclose(np.asarray(shifted)[ok] - out[ok], 10e3, rtol=0, atol=1e-6),
                "σ'_N − σ_N changes with σ_N",
            )
        # a test at zero suction among wet ones (a model fitted on the wet tests still has suctions to fit)
        s0 = np.array([0.0, *_SUCTION[1:]])
        dry = _run(chk, "sigma_eff", sigma_eff, _inputs(entry, suction=s0, fitted=fitted))
        if dry is not None and not entry.uses_radius:
            dry = float(np.asarray(dry, float)[0])
            chk.that(abs(dry - _SIGMA_N[0]) <= 1e-9, f"at zero suction σ'_N = {dry} ≠ σ_N = {_SIGMA_N[0]}")
        if chi_of_s is not None:
            mat = None if fitted is None else fitted[entry.name]["sand"]
            S = np.linspace(0.0, 1.0, 101)
            chi = _run(chk, "chi_of_saturation", chi_of_s, S, d.params, mat)
            if chi is not None:
                chi = np.asarray(chi, float)
                chk.that(chi.shape == S.shape and np.isfinite(chi).all(), "χ(S_R) is not finite on [0, 1]")
                chk.that((chi >= 0).all() and abs(chi[0]) <= 1e-12, "χ(S_R) is negative, or not 0 at S_R = 0")
                chk.that((np.diff(chi) >= -1e-12).all(), "χ(S_R) decreases somewhere on [0, 1]")
                chi_d = np.asarray(chi_of_s(d.S_R, d.params, mat), float)
                want = d.sigma_N + chi_d * d.suction
                chk.that(np.allclose(out, want, rtol=1e-12, atol=1e-9), "σ'_N ≠ σ_N + χ(S_R) s on the tests")
    if tau is not None and out is not None:
        dry = _run(chk, "tau", tau, _inputs(entry, suction=np.zeros(4), S_R=np.zeros(4), fitted=fitted))
        if dry is not None:
            want = _C + _SIGMA_N * _TAN_PHI
            chk.that(np.allclose(dry, want, rtol=1e-12, atol=1e-9), "τ of a dry test (S_R = 0, s = 0) ≠ c + σ_N tan φ")
    if values is not None:
        got = _run(chk, "material_values", values, d)
        if got is not None:
            chk.that(isinstance(got, dict) and got, "material_values gives no dict of values")
            for key, value in dict(got or {}).items():
                chk.that(isinstance(key, str) and NAME.match(key), f"material_values key {key!r} is not a JSON key")
                chk.that(isinstance(value, (str, int, float)), f"material_values {key!r} is {type(value).__name__}")
    if entry.bridge_curve is not None:
        _text(chk, entry.bridge_curve, "label")
        chk.that(
            sigma_eff is not None and not (entry.requires or entry.fitted or entry.wet_parameters),
            "a bridge_curve model must give σ'_N from S_R, s, R and γ alone",
        )
        if chk.problems:
            chk.done()
        from .physics.effective_stress_models import ModelInputs

        unit = ModelInputs.of_unit_cell(0.0, 10e3, np.array([0.01, 0.05, 0.1]), 0.5e-3, 0.0728)
        cap = _run(chk, "sigma_eff on the unit cell", sigma_eff, unit)
        if cap is not None:
            cap = np.asarray(cap, float)
            chk.that(np.isfinite(cap).all() and (cap >= 0).all(), f"unit-cell capillary stress {cap} Pa")
    chk.done()


# --- retention models ----------------------------------------------------------------------------------------------

_UNITS = ("Pa", "1/Pa", "-", "y")
_KINDS = ("residual", "saturated", "suction", "inverse_suction", "absolute", "suction_to_absolute")
#: the synthetic data range: suctions 100 Pa - 1 MPa, θ from 0.05 to 0.40
_S_MIN, _S_MAX, _Y_MIN, _Y_MAX = 1e2, 1e6, 0.05, 0.40


def _typical(p, lo: float, hi: float) -> float:
    """The middle of a parameter's search range on its own scale (logarithmic with its offset, else linear)."""
    if p.log_offset is not None and lo - p.log_offset > 0 and math.isfinite(hi):
        return p.log_offset + math.sqrt((lo - p.log_offset) * (hi - p.log_offset))
    return 0.5 * (lo + hi)


def check_retention_model(entry, fit: bool = True) -> None:
    """Check a retention model: its declaration, its curve at typical parameters and a fit of exact data.

    Declaration: the name is a ``--model`` token, unique; its help line starts with the name; label, equation and
    method present; every reference a key of `capred.references.REFERENCES`; parameter names unique, with
    units, kinds and natural domains; y_s (and y_r for the residual form) first; the names of ``steps``,
    ``grid_order``, ``power_law`` and the mixture weight are parameters; every callable resolves. Numbers, at
    each parameter's middle of its search range for data with suctions 100 Pa - 1 MPa and θ 0.05-0.40:

    - each search range has lower < upper, and the middle inside it;
    - S(s) is finite, in [0, 1], 1 at s = 0 and non-increasing in s from 0 to 10⁸ Pa;
    - the suction at S(s) gives back s (the closed-form inverse, or the root search);
    - a mixture is w S₁ + (1 − w) S₂ of its components; ``canonical`` keeps the curve and is idempotent;
      ``derived`` values are finite;
    - ``fit=True``, for a registered model: `capred.fitting.retention_models.fit_model` on 25 exact points of
      that curve finds a least-squares optimum with an RMS residual below 10⁻⁴ (θ scatter of real data is
      ~10⁻³).

    Parameters
    ----------
    entry : capred.spec.retention_models.RetentionModel
        The model, registered or not.
    fit : bool, default True
        Also fit exact data (~0.1-2 s; a model not in the registry is not fitted).

    Raises
    ------
    AssertionError
        Naming the model and every problem found.
    ValueError
        When ``entry`` is not a RetentionModel.
    """
    from .spec.retention_models import MODELS, RetentionModel

    if not isinstance(entry, RetentionModel):
        raise ValueError(f"a RetentionModel is needed, not {type(entry).__name__}")
    chk = _Check("retention model", entry.name)
    _name(chk, entry.name, MODELS, entry)
    _text(chk, entry, "label", "equation", "method", "help")
    chk.that(entry.help.startswith(entry.name + ":"), f"help {entry.help!r} does not start with '{entry.name}:'")
    chk.that(entry.references, "no reference")
    for key in entry.references:
        _reference(chk, key)
    names = entry.names
    chk.that(len(set(names)) == len(names), f"parameter names repeat: {names}")
    chk.that("y_s" in names, "no y_s")
    first = ("y_r", "y_s") if entry.residual_form else ("y_s",)
    chk.that(names[: len(first)] == first, f"parameters must start with {first}")
    for p in entry.parameters:
        chk.that(p.unit in _UNITS and p.kind in _KINDS, f"parameter {p.name}: unit {p.unit!r} or kind {p.kind!r}")
        chk.that(p.domain.strip() and p.description.strip(), f"parameter {p.name}: no domain or description")
    pairs = [*entry.steps, entry.grid_order, entry.power_law]
    used = {n for pair in pairs if pair for n in pair}
    mixture = _run(chk, "mixture", lambda: entry.mixture)
    if ref_of(entry, "mixture") is not None and mixture is not None:
        used.add(mixture[0])
    chk.that(used <= set(names), f"steps, grid_order, power_law or mixture name {sorted(used - set(names))}")
    saturation = _callable(chk, entry, "saturation", required=True)
    for f in ("inverse", "canonical"):
        _callable(chk, entry, f)
    derived = _run(chk, "derived", lambda: entry.derived) or ()
    chk.done()

    p = {}
    for par in entry.parameters:
        lo, hi = par.bounds(_S_MIN, _S_MAX, _Y_MIN, _Y_MAX)
        if not chk.that(lo < hi, f"parameter {par.name}: search range [{lo:g}, {hi:g}] is empty"):
            continue
        p[par.name] = {"y_r": _Y_MIN, "y_s": _Y_MAX}.get(par.name, _typical(par, lo, hi))
        chk.that(lo <= p[par.name] <= hi, f"parameter {par.name}: middle {p[par.name]:g} outside [{lo:g}, {hi:g}]")
    chk.done()
    shape = {k: v for k, v in p.items() if k not in ("y_r", "y_s")}
    s = np.concatenate([[0.0], np.logspace(-2, 8, 201)])
    S = _run(chk, "saturation", saturation, s, **shape)
    if S is not None:
        S = np.asarray(S, float)
        chk.that(S.shape == s.shape and np.isfinite(S).all(), "S(s) is not finite from 0 to 1e8 Pa")
        chk.that(((S >= -1e-12) & (S <= 1 + 1e-12)).all(), f"S(s) leaves [0, 1]: {S.min():g} to {S.max():g}")
        chk.that(abs(S[0] - 1.0) <= 1e-9, f"S(0) = {S[0]:g}, not 1")
        chk.that((np.diff(S) <= 1e-12).all(), "S(s) increases somewhere")
        inner = (S > 1e-6) & (S < 1 - 1e-6) & (s > 0)
        back = _run(chk, "suction", entry.suction, S[inner], **shape)
        if back is not None and inner.any():
            # the round trip S(s) -> s: a closed form to rounding, a root search to its tolerance (1e-10 in ln s)
            chk.that(np.allclose(back, s[inner], rtol=1e-6), "suction(S(s)) does not give s back")
        se = _run(chk, "effective_saturation", entry.effective_saturation, s, p)
        if se is not None:  # (y - y_r)/(y_s - y_r) of y = y_r + (y_s - y_r) S, or y/y_s of y = y_s S
            chk.that(np.allclose(se, S, atol=1e-9), "effective_saturation ≠ S")
    if mixture is not None and S is not None:
        w = mixture[0]
        comps = _run(chk, "mixture components", mixture[1], s, **{k: v for k, v in shape.items() if k != w})
        if comps is not None:
            chk.that(np.allclose(shape[w] * comps[0] + (1 - shape[w]) * comps[1], S, atol=1e-12), "S ≠ w S₁ + (1-w) S₂")
    if ref_of(entry, "canonical") is not None and S is not None:
        q = _run(chk, "canonical", entry.canonical, p)
        if q is not None:
            chk.that(entry.canonical(q) == q, "canonical is not idempotent")
            Sq = saturation(s, **{k: v for k, v in q.items() if k not in ("y_r", "y_s")})
            chk.that(np.allclose(Sq, S, atol=1e-12), "canonical changes the curve")
    for key, f in derived:
        v = _run(chk, f"derived {key}", f, p)
        chk.that(v is not None and np.isfinite(v), f"derived {key} = {v}")
    chk.done()
    if fit and MODELS.get(entry.name) is entry:
        from .fitting.retention_models import fit_model

        sd = np.logspace(math.log10(_S_MIN), math.log10(_S_MAX), 25)
        yd = entry.water(sd, **p)
        result = _run(chk, "fit_model", fit_model, entry.name, sd, yd)
        if result is not None:
            rms = math.sqrt(result.rss / sd.size)
            # exact data: the optimum's RMS is ~0; 1e-4 is 10x below the θ scatter of a good laboratory curve
            chk.that(rms < 1e-4, f"fit of exact data leaves RMS {rms:.2e}")
    chk.done()


# --- χ laws --------------------------------------------------------------------------------------------------------


def check_chi_law(entry, fit: bool = True) -> None:
    """Check a χ law: its declaration, χ on a grid and a fit of exact synthetic wet tests.

    Declaration: the law has the name of an effective-stress model whose ``fitted`` parameters are the law's;
    each parameter is a key of `capred.fitting.chi_laws.LAW_PARAMETERS` (its JSON name and unit) with a typical
    value; ``chi``, ``fit`` and ``refit_batch`` resolve. Numbers:

    - χ at the typical parameters is finite and in [0, 1] on S_R in [0, 1] × s in [0, 1 MPa], and 1 for a
      saturated test (S_R = 1, s = 0);
    - the effective-stress model of its name, given those parameters as its material's fit, has
      σ'_N = σ_N + χ s on four synthetic wet tests;
    - ``fit=True``: on eight wet tests whose τ = c + (σ_N + χ s) tan φ exactly (c = 2 kPa, φ = 35°, the
      typical parameters), ``fit`` returns those parameters (relative 10⁻³), and ``refit_batch`` on two
      replicates with unit weights returns them too.

    Parameters
    ----------
    entry : capred.spec.chi_laws.ChiLaw
        The law, registered or not.
    fit : bool, default True
        Also fit the synthetic tests (~0.1 s).

    Raises
    ------
    AssertionError
        Naming the law and every problem found.
    ValueError
        When ``entry`` is not a ChiLaw.
    """
    from .fitting.chi_laws import LAW_PARAMETERS
    from .spec.chi_laws import LAWS, ChiLaw
    from .spec.effective_stress import REGISTRY

    if not isinstance(entry, ChiLaw):
        raise ValueError(f"a ChiLaw is needed, not {type(entry).__name__}")
    chk = _Check("χ law", entry.name)
    _name(chk, entry.name, LAWS, entry)
    model = REGISTRY.get(entry.name)
    if chk.that(model is not None, "no effective-stress model of its name"):
        chk.that(set(model.fitted) == set(entry.parameters), f"parameters {entry.parameters} ≠ model's {model.fitted}")
    chk.that(entry.parameters, "no parameters")
    for name in entry.parameters:
        chk.that(name in LAW_PARAMETERS, f"parameter {name!r} is not a key of LAW_PARAMETERS (JSON name, unit)")
        chk.that(isinstance(entry.typical.get(name), (int, float)), f"no typical value of {name!r}")
    chi = _callable(chk, entry, "chi", required=True)
    fit_f = _callable(chk, entry, "fit", required=True)
    refit = _callable(chk, entry, "refit_batch", required=True)
    chk.done()

    S_R, s = np.meshgrid(np.linspace(0.0, 1.0, 21), np.concatenate([[0.0], np.logspace(2, 6, 21)]))
    x = _run(chk, "chi", chi, S_R, s, **entry.typical)
    if x is not None:
        x = np.asarray(x, float)
        chk.that(x.shape == S_R.shape and np.isfinite(x).all(), "χ is not finite on the grid")
        chk.that(((x >= -1e-12) & (x <= 1 + 1e-12)).all(), f"χ leaves [0, 1]: {np.nanmin(x):g} to {np.nanmax(x):g}")
        one = np.asarray(entry.chi(np.array([1.0]), np.array([0.0]), **entry.typical), float)
        chk.that(np.allclose(one, 1.0, atol=1e-12), f"χ(S_R = 1, s = 0) = {one}, not 1")
    if model is not None and model.sigma_eff is not None and x is not None:
        # the law and its model agree: the model's σ'_N with the law's parameters is σ_N + χ s
        d = _inputs(model, fitted={entry.name: {"sand": dict(entry.typical)}})
        got = _run(chk, "the model's sigma_eff", model.sigma_eff, d)
        if got is not None:
            want = d.sigma_N + np.asarray(chi(d.S_R, d.suction, **entry.typical), float) * d.suction
            chk.that(np.allclose(got, want, rtol=1e-12, atol=1e-9), "the model's σ'_N ≠ σ_N + χ s of the law")
    chk.done()
    if not fit:
        return
    from .physics.effective_stress_models import ModelInputs
    from .pipelines.shear import ModelParams

    n = 8
    sigma_N = np.linspace(25e3, 200e3, n)
    suction = np.logspace(3, 5.3, n)  # 1-200 kPa: either side of an air entry of tens of kPa
    S_R_w = np.linspace(0.9, 0.3, n)  # drier as the suction grows
    chi_w = np.asarray(chi(S_R_w, suction, **entry.typical), float)
    tau = _C + (sigma_N + chi_w * suction) * _TAN_PHI
    full = np.ones(n)
    w = ModelInputs(
        sigma_N,
        suction,
        S_R_w,
        full * 0.5e-3,
        tau,
        full > 0,
        np.full(n, "sand"),
        full * _C,
        full * _TAN_PHI,
        0.0728,
        None,
    )
    mp = ModelParams(s_res=0.0)
    law = _run(chk, "fit", fit_f, w, mp)
    if law is not None:
        for name in entry.parameters:
            got, want = law.values.get(name) if hasattr(law, "values") else None, entry.typical[name]
            if name == "eta" and not mp.fit_eta:
                continue  # held at --eta
            chk.that(got is not None and abs(got - want) <= 1e-3 * abs(want), f"fit gives {name} = {got}, not {want}")
        start = {k: entry.typical[k] for k in entry.parameters}
        out = _run(chk, "refit_batch", refit, w, mp, np.full(2, _C), np.full(2, _TAN_PHI), np.ones((2, n)), start)
        if out is not None:
            params, resid = out
            for name in entry.parameters:
                got = np.asarray(params[name], float) if name in params else None
                chk.that(
                    got is not None and np.allclose(got, entry.typical[name], rtol=1e-3),
                    f"refit_batch gives {name} = {got}, not {entry.typical[name]}",
                )
            chk.that(np.shape(resid) == (2, n), f"refit_batch residuals of shape {np.shape(resid)}, not (2, {n})")
    chk.done()


# --- bridge laws ---------------------------------------------------------------------------------------------------

_DOI = re.compile(r"^10\.\d{4,9}/\S+$")
_RATIO = {"equal": 1.0, "unequal": 3.0, "plane": math.inf}


def check_bridge_law(entry) -> None:
    """Check a closed-form capillary-force law: its declaration and its force on each geometry it declares.

    Declaration: the name is a token, unique; label, citation (with a year), equation and validity present; the
    DOI of the form ``10.NNNN/...``; geometries a non-empty subset of ``equal``, ``unequal``, ``plane``; ``force``
    resolves. Numbers, with θ = 20°, V/R³ = 10⁻³ and D/R from 0 to 0.05 on each declared geometry (R2/R = 1, 3,
    ∞):

    - the force F/(2πR₁γ) is finite and non-negative at every positive gap and non-increasing with the gap;
    - at zero gap it is finite and non-negative, or NaN (a law written for D > 0);
    - near contact (D/R = 10⁻³) it lies within a factor 2 of Derjaguin's limit cos θ R*/R₁ (catches a force in
      the wrong units or without its 2π).

    Parameters
    ----------
    entry : capred.spec.bridge_laws.Law
        The law, registered or not.

    Raises
    ------
    AssertionError
        Naming the law and every problem found.
    ValueError
        When ``entry`` is not a Law.
    """
    from .spec.bridge_laws import GEOMETRIES, LAWS, Law

    if not isinstance(entry, Law):
        raise ValueError(f"a bridge Law is needed, not {type(entry).__name__}")
    chk = _Check("bridge law", entry.name)
    _name(chk, entry.name, LAWS, entry)
    _text(chk, entry, "label", "citation", "equation", "validity")
    chk.that(re.search(r"\b(1[89]|20)\d\d\b", entry.citation or ""), "citation has no year")
    chk.that(isinstance(entry.doi, str) and _DOI.match(entry.doi), f"DOI {entry.doi!r} is not 10.NNNN/...")
    chk.that(entry.geometries and set(entry.geometries) <= set(GEOMETRIES), f"geometries {entry.geometries!r}")
    force = _callable(chk, entry, "force", required=True)
    chk.done()
    theta, V = math.radians(20.0), 1e-3
    D = np.linspace(0.0, 0.05, 26)
    for geometry in entry.geometries:
        rho = _RATIO[geometry]
        F = _run(
            chk, f"force ({geometry})", force, np.full(D.shape, theta), np.full(D.shape, V), D, np.full(D.shape, rho)
        )
        if F is None:
            continue
        F = np.asarray(F, float)
        if not chk.that(F.shape == D.shape, f"{geometry}: force of shape {F.shape} for {D.size} gaps"):
            continue
        chk.that(np.isfinite(F[1:]).all() and (F[1:] >= 0).all(), f"{geometry}: force not finite and ≥ 0 at D > 0")
        chk.that(np.isnan(F[0]) or F[0] >= 0, f"{geometry}: force {F[0]:g} at zero gap")
        chk.that((np.diff(F[1:]) <= 1e-12).all(), f"{geometry}: force grows with the gap")
        r_star = 2.0 if math.isinf(rho) else 2.0 * rho / (1.0 + rho)
        near = float(np.asarray(force(theta, V, 1e-3, rho), float))
        limit = math.cos(theta) * r_star
        chk.that(0.5 * limit <= near <= 2.0 * limit, f"{geometry}: force {near:g} near contact, Derjaguin {limit:g}")
    chk.done()


# --- commands ------------------------------------------------------------------------------------------------------


def check_command(reduction, run: bool = False, out=None) -> None:
    """Check a command's registry entry (`capred.reductions.Reduction`), and with ``run`` its example run.

    Declaration: the name is one or two lower-case words; its run function and options class resolve; the
    source kind is ``required``, ``optional`` or ``none`` (a required source needs a sample); the sample is a key
    of `capred.samples.SAMPLES` whose file exists; summary and method text present; every reference a key of
    `capred.references.REFERENCES`; the options class builds with its defaults and with the example's options,
    each of which is a field of it. With ``run=True`` (seconds to a minute): the example runs through the API; its
    result names the command, its JSON document holds the command, version and options, and with ``out`` a
    folder, `capred.report.outputs.write_outputs` writes the JSON document (``json_name``) and one CSV per table.

    Parameters
    ----------
    reduction : capred.reductions.Reduction
        The command's entry.
    run : bool, default False
        Also run the example (slower).
    out : str or pathlib.Path, optional
        With ``run``: a folder to write the outputs into (replaced).

    Raises
    ------
    AssertionError
        Naming the command and every problem found.
    ValueError
        When ``reduction`` is not a Reduction.
    """
    import dataclasses
    from pathlib import Path

    from .reductions import REDUCTIONS, Reduction
    from .samples import SAMPLES, sample_path

    if not isinstance(reduction, Reduction):
        raise ValueError(f"a Reduction is needed, not {type(reduction).__name__}")
    chk = _Check("command", reduction.name)
    chk.that(re.match(r"^[a-z][a-z-]*( [a-z][a-z-]*)?$", reduction.name), "name is not one or two lower-case words")
    if reduction.name in REDUCTIONS:
        chk.that(REDUCTIONS[reduction.name] is reduction, "another entry is registered under its name")
    _callable(chk, reduction, "run_path", required=True)
    options_cls = _callable(chk, reduction, "options_path", required=True)
    chk.that(reduction.source in ("required", "optional", "none"), f"source {reduction.source!r}")
    chk.that(reduction.source != "required" or reduction.sample, "a required source and no sample")
    if reduction.sample is not None:
        if chk.that(reduction.sample in SAMPLES, f"sample {reduction.sample!r} is not a key of capred.samples"):
            chk.that(Path(sample_path(reduction.sample)).is_file(), f"sample file of {reduction.sample!r} is missing")
    _text(chk, reduction, "summary", "out_prefix")
    chk.that(reduction.method and all(m.strip() for m in reduction.method), "no method text")
    for key in reduction.references:
        _reference(chk, key)
    example = dict(reduction.example)
    if options_cls is not None:
        names = {f.name for f in dataclasses.fields(options_cls)} if dataclasses.is_dataclass(options_cls) else set()
        chk.that(set(example) <= names, f"example options {sorted(set(example) - names)} are not options")
        _run(chk, "options with defaults", reduction.options)
        opts = _run(chk, "options of the example", reduction.options, **example)
    chk.done()
    if not run:
        return
    source = sample_path(reduction.sample) if reduction.sample is not None else None
    result = _run(chk, "the example run", reduction.run, source, opts)
    if result is not None:
        chk.that(result.command == reduction.name, f"the result names command {result.command!r}")
        doc = _run(chk, "to_json", result.to_json)
        if doc is not None:
            chk.that(isinstance(doc, dict) and doc, "an empty JSON document")
        if out is not None:
            from .report.outputs import write_outputs

            written = _run(chk, "write_outputs", write_outputs, result, out, plots=False, html=False)
            if written is not None:
                files = {Path(p).name for p in written}
                chk.that(result.json_name in files, f"{result.json_name} not written ({sorted(files)})")
                for stem in result.csv_tables():
                    chk.that(f"{stem}.csv" in files, f"table {stem}.csv not written")
    chk.done()
