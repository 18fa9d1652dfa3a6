r"""The water-retention models of `capred retention`: one registry entry each, and their fitting.

Each :class:`RetentionModel` of :data:`MODELS` (declared in `capred.spec.retention_models`, re-exported here)
holds everything about a model:
its name, label, equation (matplotlib mathtext), parameters with units and
valid ranges, references (keys of :mod:`capred.references`), the method text
of report.html, the help text and the line style. Adding a model is adding one
entry.

Suction s is in Pa inside. Every model gives

.. math:: y(s) = y_r + (y_s - y_r)\, S(s)

except Fredlund-Xing with its correction factor, :math:`y = y_s\, C(s) S(s)`.
The fit (:func:`fit_model`) reaches the global least-squares optimum inside
the bounds by

1. *variable projection*: y_r and y_s enter linearly, so for given shape
   parameters they are the exact bounded weighted least-squares solution
   (Golub & Pereyra 1973); the search runs over the shape parameters only;
2. a *grid* over the shape parameters (log-spaced on each parameter's own
   scale, dense over the data's suction range and reaching the bounds), its
   projected residual evaluated at once for every grid point from each
   curve's weighted moments; for a mixture weight (Durner's w1) the weights
   are projected too;
3. a bounded Levenberg-Marquardt refinement from the best grid minima, all
   starts iterated together: first loosely (on at most 200 points of a large
   data set), then the best to full precision on all points;
   a parameter whose model has kinks at the data suctions (Brooks-Corey's
   air-entry suction) is refined within each interval between neighbouring
   data suctions separately, where the objective is smooth.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass, field, fields

import numpy as np

from ..errors import FitError
from ..parameters import Parameter as _UserParameter
from ..parameters import Parameters, deprecated, fit_report
from ..physics import retention as rp
from ..spec.retention_models import (  # noqa: F401  (the registry, declared without numerics)
    MODELS,
    N_POSITIVE,
    REGISTRY,
    Y_R,
    Y_S,
    Parameter,
    RetentionModel,
)
from ..spec.retention_models import make_parameter as _p  # noqa: F401  (the name scripts and tests use)
from .nonlinear import NonlinearFit, fit_curve, summarize_fit

_SCREEN_POINTS = 100  # data points used to rank the start grid (all points are used for the refinement)
_CHUNK = 2_000_000  # grid points x data points evaluated at once


# ---------------------------------------------------------------------------------------------------------------
# the registry


def _durner_components(s, alpha1, n1, alpha2, n2):
    return rp.vg_effective_saturation(s, alpha1, n1), rp.vg_effective_saturation(s, alpha2, n2)


def _durner_canonical(p: dict) -> dict:
    if p["alpha1"] >= p["alpha2"]:
        return p
    return {**p, "w1": 1.0 - p["w1"], "alpha1": p["alpha2"], "n1": p["n2"], "alpha2": p["alpha1"], "n2": p["n1"]}


def _bc_inverse(S, s_e, lam):
    ok = (S > 0) & (S <= 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(ok, rp.bc_suction(np.where(ok, S, 1.0), s_e, lam), np.nan)


def _vg_saturation(s, alpha, n):
    return rp.vg_effective_saturation(s, alpha, n)


def _vg_inverse(S, alpha, n):
    return rp.vg_suction(S, alpha, n)


def _vg_m(p: dict) -> float:
    """The m = 1 - 1/n of van Genuchten (Mualem's constraint) of the fitted parameters."""
    return 1.0 - 1.0 / p["n"]


def _vg_m_free_saturation(s, alpha, n, m):
    return rp.vg_effective_saturation(s, alpha, n, m)


def _vg_m_free_inverse(S, alpha, n, m):
    return rp.vg_suction(S, alpha, n, m)


def _bc_saturation(s, s_e, lam):
    return rp.bc_effective_saturation(s, s_e, lam)


def _kosugi_saturation(s, s_m, sigma):
    return rp.kosugi_effective_saturation(s, s_m, sigma)


def _kosugi_inverse(S, s_m, sigma):
    return rp.kosugi_suction(S, s_m, sigma)


def _fx_saturation(s, a, n, m, s_r):
    return rp.fx_correction(s, s_r) * rp.fx_shape(s, a, n, m)


def _fx_no_c_saturation(s, a, n, m):
    return rp.fx_shape(s, a, n, m)


def _durner_saturation(s, w1, alpha1, n1, alpha2, n2):
    return rp.durner_effective_saturation(s, w1, alpha1, n1, alpha2, n2)


def model_suction(model: RetentionModel, S, **shape):
    """Suction [Pa] at which ``model``'s S(s) equals ``S`` [-] (NaN where no suction gives it).

    Parameters
    ----------
    model : RetentionModel
        A registry entry.
    S : array_like
        Value of the model's ``saturation`` [-] (S_e, or C·S_e for Fredlund-Xing with C).
    **shape
        The shape parameters by internal name, in SI units.

    Returns
    -------
    numpy.ndarray
        Suction [Pa]: the model's closed-form ``inverse`` where it has one, else a monotone root search
        (`capred.physics.retention.monotone_suction`).

    References
    ----------
    .. [1] The model's own paper (``model.references``); van Genuchten (1980), eq. 21, for its inverse
       s = [(S^(-1/m) - 1)^(1/n)]/α. doi:10.2136/sssaj1980.03615995004400050002x
    """
    S = np.asarray(S, float)
    if model.inverse is not None:
        return model.inverse(S, **shape)
    return rp.monotone_suction(lambda x: model.saturation(x, **shape), S)


def bounds_for(s, y, model: str | None = None) -> dict[str, tuple[float, float]]:
    """Search bounds of the retention parameters for data (s, y).

    Parameters
    ----------
    s : array_like
        Suctions [Pa].
    y : array_like
        Water contents [m³/m³] or degrees of saturation [-].
    model : str, optional
        A key of :data:`MODELS`: only its parameters; all models' when None.

    Returns
    -------
    dict[str, tuple[float, float]]
        ``{name: (lower, upper)}`` in the parameters' units (Pa, 1/Pa, -, unit of y); the rules are in
        each :class:`Parameter` (``range_text``).

    References
    ----------
    The parameters are those of the models' papers (each entry's ``references``); the ranges are capred's,
    wide enough to hold the fits of SWRC Fit (Seki 2007, Hydrol. Earth Syst. Sci. Discuss. 4:407-437).
    """
    s = np.asarray(s, float)
    y = np.asarray(y, float)
    pos = s[s > 0]
    smin = float(pos.min()) if pos.size else 1.0
    smax = float(s.max()) if s.size and s.max() > 0 else 1.0
    models = [MODELS[model]] if model is not None else list(MODELS.values())
    out: dict[str, tuple[float, float]] = {}
    for m in models:
        for p in m.parameters:
            out.setdefault(p.name, p.bounds(smin, smax, float(np.min(y)), float(np.max(y))))
    return out


# ---------------------------------------------------------------------------------------------------------------
# the fit record


# ---------------------------------------------------------------------------------------------------------------
# the user's names and units (the JSON's): one table, read by fits, records, JSON and tables

#: internal parameter -> (JSON name, factor SI -> JSON unit, JSON unit); y_r and y_s are named by the data kind
JSON_NAMES: dict[str, tuple[str, float, str]] = {
    "alpha": ("alpha_per_kPa", 1e3, "1/kPa"),
    "alpha1": ("alpha1_per_kPa", 1e3, "1/kPa"),
    "alpha2": ("alpha2_per_kPa", 1e3, "1/kPa"),
    "alpha_d": ("alpha_d_per_kPa", 1e3, "1/kPa"),
    "alpha_w": ("alpha_w_per_kPa", 1e3, "1/kPa"),
    "s_e": ("s_e_kPa", 1e-3, "kPa"),
    "s_m": ("s_m_kPa", 1e-3, "kPa"),
    "a": ("a_kPa", 1e-3, "kPa"),
    "s_r": ("s_r_kPa", 1e-3, "kPa"),
    "lam": ("lambda", 1.0, "-"),
    "n": ("n", 1.0, "-"),
    "m": ("m", 1.0, "-"),
    "n1": ("n1", 1.0, "-"),
    "n2": ("n2", 1.0, "-"),
    "w1": ("w1", 1.0, "-"),
    "sigma": ("sigma", 1.0, "-"),
}


def default_models() -> tuple[str, ...]:
    """The models `capred retention` fits when none are named (registry entries with ``default``).

    Returns
    -------
    tuple of str
        Registry keys, in registry order.

    References
    ----------
    Each entry's ``references`` (van Genuchten 1980, doi:10.2136/sssaj1980.03615995004400050002x; Brooks &
    Corey 1964, Hydrology Paper 3, Colorado State University).
    """
    return tuple(k for k, m in MODELS.items() if m.default)


def hysteresis_model() -> RetentionModel:
    """The model of each branch of the Kool & Parker (1987) joint hysteresis fit.

    The registry entry with ``hysteresis_base``.

    Returns
    -------
    RetentionModel
        The registry entry.

    References
    ----------
    Kool, J. B., Parker, J. C. (1987). Water Resour. Res. 23(1), 105-114. doi:10.1029/WR023i001p00105
    """
    return next(m for m in MODELS.values() if m.hysteresis_base)


def power_law_model() -> RetentionModel:
    """The model of the form S_e = (s_e/s)^λ above its air entry (the entry with ``power_law``).

    What `skempton-b --retention` takes (Morvan et al. 2016, eq. 13) and `retention-convert` converts to by default.

    Returns
    -------
    RetentionModel
        The registry entry.

    References
    ----------
    Brooks, R. H., Corey, A. T. (1964). Hydraulic properties of porous media. Hydrology Paper 3, Colorado State
    University.
    """
    return next(m for m in MODELS.values() if m.power_law is not None)


def json_name(internal: str, quantity: str = "S_R") -> tuple[str, float, str]:
    """The user's name of a retention parameter: (JSON name, factor SI -> JSON unit, JSON unit).

    Parameters
    ----------
    internal : str
        Internal name (``y_r``, ``alpha``, ``s_e`` ...).
    quantity : str
        ``"theta"`` (θ [m³/m³] fitted), ``"S_R"`` [-] or ``"w"`` (water content by mass [-]): names y_r, y_s
        (``theta_r``/``S_res``/``w_r``, ``theta_s``/``S_s``/``w_s``).

    Returns
    -------
    tuple of (str, float, str)
        E.g. ``("alpha_per_kPa", 1e3, "1/kPa")`` for ``alpha`` [1/Pa].

    References
    ----------
    The names of SWRC Fit (Seki 2007, Hydrol. Earth Syst. Sci. Discuss. 4:407-437) with the unit in the name.
    """
    if internal in ("y_r", "y_s"):
        names = {"theta": ("theta_r", "theta_s"), "w": ("w_r", "w_s")}.get(quantity, ("S_res", "S_s"))
        return names[internal == "y_s"], 1.0, "m³/m³" if quantity == "theta" else "-"
    if internal in JSON_NAMES:
        return JSON_NAMES[internal]
    unit = next((p.unit for m in MODELS.values() for p in m.parameters if p.name == internal), "-")
    return {"Pa": (f"{internal}_kPa", 1e-3, "kPa"), "1/Pa": (f"{internal}_per_kPa", 1e3, "1/kPa")}.get(
        unit, (internal, 1.0, "-")
    )


def internal_name(name: str) -> tuple[str, float]:
    """The internal name of a retention parameter given by its JSON (or internal) name.

    Parameters
    ----------
    name : str
        ``theta_r``, ``S_res``, ``alpha_per_kPa``, ``s_e_kPa``, ``lambda`` ... (or ``y_r``, ``alpha`` ...).

    Returns
    -------
    tuple of (str, float)
        Internal name and the factor JSON unit -> SI (1e-3 for 1/kPa -> 1/Pa).

    Raises
    ------
    KeyError
        Not a retention parameter.

    References
    ----------
    The inverse of :func:`json_name`.
    """
    lin = {"theta_s": "y_s", "S_s": "y_s", "w_s": "y_s", "theta_r": "y_r", "S_res": "y_r", "w_r": "y_r"}
    lin.update(y_s="y_s", y_r="y_r")
    if name in lin:
        return lin[name], 1.0
    for internal, (rep, f, _) in JSON_NAMES.items():
        if name in (rep, internal):
            return internal, 1.0 / f
    raise KeyError(name)


def _description(internal: str) -> str:
    for m in MODELS.values():
        for p in m.parameters:
            if p.name == internal:
                return p.description
    return {"alpha_d": "α of the drying branch", "alpha_w": "α of the wetting branch"}.get(internal, "")


class _Number:
    """Arithmetic and formatting of a parameter record through its value.

    So that a script's ``fit.params["n"] * 2`` (a float before, a record now) keeps working.
    """

    def __format__(self, spec):
        return format(float(self.value), spec)

    def __eq__(self, other):
        if isinstance(other, _UserParameter):
            return _UserParameter.__eq__(self, other)
        try:
            return float(self.value) == float(other)
        except (TypeError, ValueError):
            return NotImplemented

    def __hash__(self):
        return hash(float(self.value))

    def __array__(self, dtype=None, copy=None):
        return np.asarray(float(self.value), dtype=dtype)


def _delegate(op):
    def f(self, *other):
        return getattr(float(self.value), op)(*(float(o) for o in other))

    f.__name__ = op
    return f


for _op in (
    "__add__", "__radd__", "__sub__", "__rsub__", "__mul__", "__rmul__", "__truediv__", "__rtruediv__",
    "__pow__", "__rpow__", "__neg__", "__abs__", "__lt__", "__le__", "__gt__", "__ge__",
):  # fmt: skip
    setattr(_Number, _op, _delegate(_op))


@dataclass(frozen=True, repr=False, eq=False)
class FitParameter(_Number, _UserParameter):
    """A :class:`capred.parameters.Parameter` that also computes like its value (``p * 2``, ``f"{p:.3g}"``)."""


numbers.Real.register(FitParameter)  # pytest.approx, isinstance checks of old scripts


class RetentionParameters(Parameters):
    """The parameters of a retention fit by JSON name in the JSON's units (``theta_r``, ``alpha_per_kPa`` ...).

    The old internal names (``y_r``, ``y_s``, ``alpha`` [1/Pa], ``s_e`` [Pa], ``lam`` ...) still work for one
    release: they return the OLD value in the OLD (SI) unit as a float and raise a DeprecationWarning naming
    the new key (:func:`capred.parameters.deprecated`).

    Attributes
    ----------
    si : dict[str, float]
        ``{internal name: value}`` in SI units (Pa, 1/Pa, -): what the models evaluate.
    """

    def __init__(self, items_, correlation, si: dict, renamed: dict):
        object.__setattr__(self, "items_", tuple(items_))
        object.__setattr__(self, "correlation", dict(correlation))
        object.__setattr__(self, "si", dict(si))
        object.__setattr__(self, "renamed", dict(renamed))

    def __getitem__(self, name: str):
        if name in self.renamed and all(p.name != name for p in self.items_):
            new = self.renamed[name]
            unit = json_name(name)[2]
            return deprecated(
                f"fit.params[{name!r}] (SI units)",
                f"fit.params[{new!r}].value [{unit}]" if unit != "-" else f"fit.params[{new!r}].value",
                self.si[name],
            )
        return super().__getitem__(name)

    def __contains__(self, name) -> bool:
        return any(p.name == name for p in self.items_) or name in self.renamed

    def __eq__(self, other) -> bool:
        return isinstance(other, Parameters) and self.items_ == other.items_

    __hash__ = None


class RetentionErrors(dict):
    """Standard errors of a retention fit by JSON name, in the JSON's units.

    ``fit.stderr["alpha_per_kPa"]`` [1/kPa]; None where none applies: a fixed or held parameter, a converted curve.

    The old internal names (``y_r``, ``alpha`` [1/Pa], ``s_e`` [Pa] ...) still work for one release: they return
    the OLD value in the OLD (SI) unit and raise a DeprecationWarning naming the new key
    (:func:`capred.parameters.deprecated`).

    Attributes
    ----------
    si : dict[str, float or None]
        ``{internal name: standard error}`` in SI units.
    """

    def __init__(self, by_name: dict, si: dict, renamed: dict):
        super().__init__(by_name)
        self.si = dict(si)
        self.renamed = dict(renamed)

    def __getitem__(self, name: str):
        if not dict.__contains__(self, name) and name in self.renamed:
            new = self.renamed[name]
            unit = json_name(name)[2]
            return deprecated(
                f"fit.stderr[{name!r}] (SI units)",
                f"fit.stderr[{new!r}] [{unit}]" if unit != "-" else f"fit.stderr[{new!r}]",
                self.si[name],
            )
        return super().__getitem__(name)

    def get(self, name: str, default=None):
        """The standard error of ``name``, or ``default``.

        Parameters
        ----------
        name : str
            A JSON name (``"alpha_per_kPa"``); an old internal name works with a DeprecationWarning.
        default : object, optional
            What is returned where ``name`` has no standard error.

        Returns
        -------
        float or None
            The standard error in the JSON's unit of ``name``, else ``default``.
        """
        try:
            return self[name]
        except KeyError:
            return default

    def __contains__(self, name) -> bool:
        return dict.__contains__(self, name) or name in self.renamed


@dataclass
class RetentionFit(NonlinearFit):
    """A fitted retention curve: the :class:`~capred.fitting.nonlinear.NonlinearFit` of one model, callable.

    ``fit.params`` is a :class:`RetentionParameters` keyed by the JSON names in the JSON's units
    (``fit.params["alpha_per_kPa"].value``, ``.stderr``, ``.ci95``, ``.unit``); ``fit.params_si`` holds the
    same values by internal name in SI units (Pa, 1/Pa), as the models take them. ``fit.summary()`` is a
    plain-text report.

    Attributes (besides those of NonlinearFit)
    -------------------------------------------
    model : str
        Key of :data:`MODELS` (``"kool_parker"`` for the joint hysteresis fit).
    suction_points : tuple of float
        The distinct positive suctions of the data [Pa] (at most 200, evenly chosen, the extremes kept): the
        suction range over which the fit holds (``suction_range``).
    quantity : str
        ``"S_R"`` [-] or ``"theta"`` [m³/m³]: what was fitted.
    warnings : list of str
        Plain-language warnings on this fit (identifiability, AICc not computable ...).

    The methods evaluate the fitted curve: suction in Pa, water quantity in the unit of the data fitted
    (θ [m³/m³] or S_R [-]).
    """

    model: str = ""
    quantity: str = "S_R"  # what was fitted: "S_R" [-] or "theta" [m³/m³]
    warnings: list = field(default_factory=list)
    suction_points: tuple = ()  # the distinct positive suctions fitted [Pa] (at most 200, evenly chosen)

    @property
    def suction_range(self) -> tuple[float, float] | None:
        """(smallest, largest) positive suction of the data fitted [Pa]; None when unknown."""
        return (float(self.suction_points[0]), float(self.suction_points[-1])) if self.suction_points else None

    # ``params`` of NonlinearFit is stored as ``params_si``; reading ``params`` gives the user's records
    def _get_params(self) -> RetentionParameters:
        si = self.__dict__["params_si"]
        items, renamed = [], {}
        for k, v in si.items():
            name, f, unit = json_name(k, self.quantity)
            if name != k:
                renamed[k] = name
            se = self.stderr_si.get(k)
            se = float(se) * f if se is not None and np.isfinite(se) else float("nan")
            ci = self.ci95(k)
            items.append(
                FitParameter(
                    name,
                    float(v) * f,
                    se,
                    (ci[0] * f, ci[1] * f) if ci is not None else (float("nan"), float("nan")),
                    unit,
                    _description(k),
                    k in self.fixed,
                )
            )
        corr = {
            (json_name(a, self.quantity)[0], json_name(b, self.quantity)[0]): r
            for a, row in self.correlation().items()
            for b, r in row.items()
            if list(si).index(a) < list(si).index(b)
        }
        return RetentionParameters(items, corr, si, renamed)

    def _set_params(self, value) -> None:
        self.__dict__["params_si"] = dict(value.si if isinstance(value, RetentionParameters) else value)

    params = property(_get_params, _set_params)

    # ``stderr`` of NonlinearFit is stored as ``stderr_si``; reading ``stderr`` gives JSON names and units
    def _get_stderr(self) -> RetentionErrors:
        si = self.__dict__["stderr_si"]
        by_name, renamed = {}, {}
        for k, v in si.items():
            name, f, _ = json_name(k, self.quantity)
            if name != k:
                renamed[k] = name
            by_name[name] = float(v) * f if v is not None else None
        return RetentionErrors(by_name, si, renamed)

    def _set_stderr(self, value) -> None:
        self.__dict__["stderr_si"] = dict(value.si if isinstance(value, RetentionErrors) else value)

    stderr = property(_get_stderr, _set_stderr)

    @property
    def stderr_si(self) -> dict[str, float | None]:
        """``{internal name: standard error}`` in SI units (Pa, 1/Pa, -); None where none applies."""
        return self.__dict__["stderr_si"]

    @property
    def params_si(self) -> dict[str, float]:
        """``{internal name: value}`` in SI units (Pa, 1/Pa, -), the arguments of the model's functions."""
        return self.__dict__["params_si"]

    def ci95(self, name: str) -> tuple[float, float] | None:
        """95 % interval of one parameter by internal name, in SI units (None without a standard error).

        Parameters
        ----------
        name : str
            Internal name, e.g. "alpha".

        Returns
        -------
        tuple of float or None
            (lower, upper) in SI units (1/Pa, Pa, [-]).
        """
        se = self.stderr_si.get(name)
        if se is None or not np.isfinite(se):
            return None
        v = self.params_si[name]
        return v - self.t * se, v + self.t * se

    def at_bounds(self, rel: float = 1e-6) -> list[str]:
        """Free parameters (internal names) that ended on one of their bounds, judged on their own scale.

        Parameters
        ----------
        rel : float, optional
            Tolerance, as a share of the range's width on the parameter's scale [-] (default 1e-6).

        Returns
        -------
        list of str
            Internal names of the parameters at a bound.
        """
        from types import SimpleNamespace

        si = SimpleNamespace(free=self.free, params=self.params_si, bounds=self.bounds, log_params=self.log_params)
        return NonlinearFit.at_bounds(si, rel)  # the same rule on the SI values

    @property
    def label(self) -> str:
        """Display name of the model."""
        return MODELS[self.model].label if self.model in MODELS else "Kool & Parker (1987) hysteresis"

    def statistics(self) -> dict:
        """The fit statistics shown by :meth:`summary`.

        Returns
        -------
        dict of str to float
            ``{label: value}`` of n, k, RSS, RMSE, R², AIC, AICc and BIC (RSS and RMSE in the fitted quantity's unit).
        """
        return {
            "data points": self.n,
            "free params": self.nfree,
            "RSS": self.rss,
            "RMSE": self.rmse,
            "R²": self.r2,
            "AIC": self.aic,
            "AICc": self.aicc,
            "BIC": self.bic,
        }

    def summary(self, title: str | None = None) -> str:
        """A plain-text report of the fit (lmfit's ``fit_report`` in spirit).

        Parameters
        ----------
        title : str, optional
            First line (default: the model's label and the fitted quantity).

        Returns
        -------
        str
            Fit statistics, parameters in the JSON's units with SE and 95 % CI, correlations above 0.9,
            warnings.

        References
        ----------
        Newville, M. et al. (2014). LMFIT: Non-linear least-squares minimization and curve-fitting for Python,
        doi:10.5281/zenodo.11813 (the layout of ``fit_report``).
        """
        return fit_report(
            title or f"{self.label} fit of {'θ' if self.quantity == 'theta' else 'S_R'}",
            self.params,
            self.statistics(),
            list(self.warnings) + [n for n in self.notes if n not in self.warnings],
        )

    @property
    def entry(self) -> RetentionModel:
        """The registry entry of the fitted model."""
        return MODELS[self.model]

    def water(self, suction):
        """Fitted water content (or S_R) at ``suction``.

        Parameters
        ----------
        suction : array_like
            Suction [Pa].

        Returns
        -------
        numpy.ndarray
            y [m³/m³ or -], the shape of ``suction``.
        """
        if self.model == "kool_parker":  # the joint hysteresis fit: its main (drying) branch
            p = self.params_si
            return rp.vg_water(np.asarray(suction, float), p["y_r"], p["y_s"], p["alpha_d"], p["n"])
        return self.entry.water(np.asarray(suction, float), **self.params_si)

    __call__ = water

    def S_R(self, suction):
        """Degree of saturation S_R [-] at ``suction`` [Pa] (>= 0).

        The fitted curve itself when S_R was fitted, θ/θ_s when a volumetric water content was (θ_s taken as the
        porosity: the soil saturated at zero suction). A negative suction raises OptionError.

        Parameters
        ----------
        suction : float or array_like
            Suction [Pa], >= 0.

        Returns
        -------
        numpy.ndarray
            Degree of saturation [-].
        """
        s = np.asarray(suction, float)
        if np.any(s < 0):
            from ..errors import OptionError

            raise OptionError(f"suction must be >= 0 Pa (got {s[s < 0].flat[0]:g})")
        y = self.water(s)
        return y if self.quantity == "S_R" else y / self.params_si["y_s"]

    def suction_at_S_R(self, S_R):
        """Suction [Pa] at which the fitted curve gives the degree of saturation ``S_R`` [-] (inverse of S_R).

        NaN where S_R lies outside the fitted curve's range (S_res, S_s].

        Parameters
        ----------
        S_R : float or array_like
            Degree of saturation [-].

        Returns
        -------
        numpy.ndarray
            Suction [Pa].
        """
        S_R = np.asarray(S_R, float)
        return self.suction(S_R if self.quantity == "S_R" else S_R * self.params_si["y_s"])

    def effective_saturation(self, suction):
        """Fitted S_e = (y - y_r)/(y_s - y_r) [-] at ``suction`` [Pa] (y/y_s for Fredlund-Xing with C).

        Parameters
        ----------
        suction : float or array_like
            Suction [Pa].

        Returns
        -------
        numpy.ndarray
            Effective saturation [-].
        """
        return self.entry.effective_saturation(np.asarray(suction, float), self.params_si)

    def suction(self, water):
        """Suction [Pa] at which the fitted curve gives ``water``, the inverse of :meth:`water`.

        Parameters
        ----------
        water : array_like
            Water content [m³/m³] or S_R [-], in the unit fitted.

        Returns
        -------
        numpy.ndarray
            Suction [Pa]; 0 at y_s (the air-entry suction s_e for Brooks-Corey), NaN outside (y_r, y_s].
        """
        p = self.params_si
        water = np.asarray(water, float)
        y_r = p.get("y_r", 0.0) if self.entry.residual_form else 0.0
        S = (water - y_r) / (p["y_s"] - y_r)
        shape = {k: v for k, v in p.items() if k not in ("y_r", "y_s")}
        return self.entry.suction(S, **shape)

    def band(self, suction, level_t: float | None = None):
        """95 % confidence band of the fitted curve at ``suction`` [Pa]: (lower, upper), see :func:`confidence_band`.

        Parameters
        ----------
        suction : float or array_like
            Suction [Pa].
        level_t : float or None, optional
            The multiplier t (default: the fit's Student t of 95 %).

        Returns
        -------
        tuple of numpy.ndarray
            (lower, upper) [unit of the water quantity fitted].
        """
        return confidence_band(self.model, self, suction, level_t)


# ---------------------------------------------------------------------------------------------------------------
# identifiability

#: |correlation| of two estimates above which the data cannot tell them apart (issue 30: beyond 0.99)
CORRELATION_LIMIT = 0.99
#: standard error / |value| above which a strictly positive scale or shape parameter is not determined: its 68 %
#: interval reaches zero, the edge of its domain
RELATIVE_SE_LIMIT = 1.0
#: condition number of the Jacobian (columns scaled to unit length) above which JᵀJ, whose condition number is
#: its square, exceeds 1/ε in double precision: its inverse, the covariance, is not determined (where lmfit and
#: scipy say the covariance could not be estimated)
CONDITION_LIMIT = 1.0 / np.sqrt(np.finfo(float).eps)


def conditioning(water, s, params: dict, free, weights=None) -> tuple[float, tuple[str, ...]]:
    """Condition number of a fit's Jacobian and the parameters of its least determined direction.

    Parameters
    ----------
    water : callable
        ``water(s, **params)``, the model.
    s : array_like
        Suctions of the data [Pa].
    params : dict
        The optimum (internal names, SI).
    free : sequence of str
        The estimated parameters (not fixed, not held at a bound).
    weights : array_like, optional
        Weights of the readings.

    Returns
    -------
    (float, tuple of str)
        κ of the weighted Jacobian with unit-length columns (inf when a column vanishes), and the parameters
        whose component in the right singular vector of the smallest singular value exceeds 0.3.

    References
    ----------
    Belsley, D. A., Kuh, E., Welsch, R. E. (1980). Regression Diagnostics. Wiley, doi:10.1002/0471725153, ch. 3
    (condition number of the column-scaled design matrix; the variance-decomposition of its weakest direction).
    """
    free = list(free)
    if not free:
        return 1.0, ()
    s = np.asarray(s, float)
    sw = np.ones_like(s) if weights is None else np.sqrt(np.asarray(weights, float))
    cols = []
    with np.errstate(all="ignore"):
        for k in free:
            h = 1e-6 * max(abs(params[k]), 1e-6)
            up = water(s, **dict(params, **{k: params[k] + h}))
            dn = water(s, **dict(params, **{k: params[k] - h}))
            cols.append(sw * (up - dn) / (2 * h))
    J = np.column_stack(cols)
    norm = np.linalg.norm(J, axis=0)
    if not np.all(np.isfinite(J)) or np.any(norm == 0):
        return float("inf"), tuple(k for k, n in zip(free, norm) if not n > 0)
    _, sv, vt = np.linalg.svd(J / norm, full_matrices=False)
    kappa = float(sv[0] / sv[-1]) if sv[-1] > 0 else float("inf")
    return kappa, tuple(k for k, v in zip(free, vt[-1]) if abs(v) > 0.3)


def identifiability_warnings(fit) -> list[str]:
    """Plain-language warnings on what a fit cannot determine (JSON names, the JSON's units).

    A strictly positive scale or shape parameter (those on a logarithmic scale: n, α, λ, m, s_e, σ ...) whose
    standard error exceeds its value (:data:`RELATIVE_SE_LIMIT`); two estimates correlated beyond
    :data:`CORRELATION_LIMIT`; a Jacobian whose condition number exceeds :data:`CONDITION_LIMIT` (the
    parameters of its weakest direction named). Parameters that may truly be near zero (θ_r, S_res, w1) are
    judged by correlation and conditioning only. An AICc that cannot be computed (n − k − 1 ≤ 0) says why.

    Parameters
    ----------
    fit : RetentionFit
        The fit (``extra["condition_number"]`` and ``extra["weak_direction"]`` from :func:`fit_model`).

    Returns
    -------
    list of str

    References
    ----------
    Burnham, K. P., Anderson, D. R. (2002). Model Selection and Multimodel Inference, 2nd ed. Springer,
    doi:10.1007/b97636, eq. 2.2 (AICc); Belsley et al. (1980), see :func:`conditioning`.
    """

    def name(k):
        return json_name(k, fit.quantity)[0]

    out = []
    weak_se = []
    for k in fit.free:
        if k in fit.held or k not in fit.log_params:
            continue
        se = (fit.stderr_si if isinstance(fit, RetentionFit) else fit.stderr).get(k)
        v = fit.params_si[k]
        if se is not None and np.isfinite(se) and v != 0 and abs(se / v) > RELATIVE_SE_LIMIT:
            weak_se.append(f"{name(k)} (± {100 * abs(se / v):.3g} %)")
    if weak_se:
        out.append(
            f"not identifiable: the standard error of {', '.join(weak_se)} exceeds the value; the data do not "
            "determine it (fix it, or choose a model with fewer parameters)"
        )
    corr = fit.correlation()
    keys = list(corr)
    pairs = [
        f"{name(a)} and {name(b)} (r = {corr[a][b]:+.4f})"
        for i, a in enumerate(keys)
        for b in keys[i + 1 :]
        if abs(corr[a][b]) > CORRELATION_LIMIT
    ]
    if pairs:
        out.append(
            f"parameters correlated beyond {CORRELATION_LIMIT:g}: {'; '.join(pairs)}; the data determine a "
            "combination of them, not each"
        )
    kappa = fit.extra.get("condition_number")
    if kappa is not None and not kappa <= CONDITION_LIMIT:
        weak = ", ".join(name(k) for k in fit.extra.get("weak_direction", ())) or "some parameters"
        out.append(
            f"the fit cannot separate {weak}: the Jacobian's condition number is {kappa:.3g} (above "
            f"1/√ε = {CONDITION_LIMIT:.3g}); their standard errors are not determined"
        )
    if not fit.n - fit.nfree - 1 > 0:
        out.append(
            f"AICc cannot be computed: n − k − 1 = {fit.n - fit.nfree - 1} ≤ 0 ({fit.n} readings, {fit.nfree} "
            "free parameters); the model is not ranked by AICc"
        )
    return out


# ---------------------------------------------------------------------------------------------------------------
# variable projection


def _projected_rss(pb: _Problem, W, Y, YY, mS, mSS, mSy):
    """Projected RSS of curves S known by their weighted moments.

    The bounded weighted least-squares y_r, y_s of each curve, from its moments alone (every column of the linear
    problem is affine in S and y).

    ``W, Y, YY`` are Σw, Σw y, Σw y² of the data; ``mS, mSS, mSy`` are Σw S, Σw S², Σw S y of each curve (any
    broadcastable shape). With two linear parameters the box-constrained quadratic is solved exactly: the
    unconstrained solution if it is feasible, else the best point on the four edges.
    """

    def dot(f, g):  # <f, g> for f = p + q S + r y
        (p1, q1, r1), (p2, q2, r2) = f, g
        return (
            p1 * p2 * W
            + (p1 * q2 + q1 * p2) * mS
            + q1 * q2 * mSS
            + (p1 * r2 + r1 * p2) * Y
            + (q1 * r2 + r1 * q2) * mSy
            + r1 * r2 * YY
        )

    cols = {"y_r": (1.0, -1.0, 0.0), "y_s": (0.0, 1.0, 0.0)} if pb.model.residual_form else {"y_s": (0.0, 1.0, 0.0)}
    rhs = (
        -sum(v * cols[k][0] for k, v in pb.fixed_lin.items()),
        -sum(v * cols[k][1] for k, v in pb.fixed_lin.items()),
        1.0,
    )
    lin, b = pb.lin, pb.b
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        cc = dot(rhs, rhs)
        if not lin:
            return cc
        if len(lin) == 1:
            c = cols[lin[0]]
            a11, b1 = dot(c, c), dot(c, rhs)
            beta = np.clip(b1 / a11, *b[lin[0]])
            return cc - 2 * beta * b1 + beta * beta * a11
        c1, c2 = cols[lin[0]], cols[lin[1]]
        (lo1, hi1), (lo2, hi2) = b[lin[0]], b[lin[1]]
        a11, a12, a22 = dot(c1, c1), dot(c1, c2), dot(c2, c2)
        b1, b2 = dot(c1, rhs), dot(c2, rhs)
        det = a11 * a22 - a12 * a12
        with np.errstate(divide="ignore", invalid="ignore"):  # det = 0 (a singular row): not 'inside', edges below
            u1, u2 = (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det

        def q(x1, x2):
            return cc - 2 * (b1 * x1 + b2 * x2) + a11 * x1 * x1 + 2 * a12 * x1 * x2 + a22 * x2 * x2

        ok = (det > 0) & (u1 >= lo1) & (u1 <= hi1) & (u2 >= lo2) & (u2 <= hi2)
        best = np.where(ok, q(u1, u2), np.inf)
        for e in (lo1, hi1):
            best = np.fmin(best, q(e, np.clip((b2 - a12 * e) / a22, lo2, hi2)))
        for e in (lo2, hi2):
            best = np.fmin(best, q(np.clip((b1 - a12 * e) / a11, lo1, hi1), e))
        return np.maximum(best, 0.0)


class _Problem:
    """The projected least-squares problem of one model on one data set."""

    def __init__(self, model: RetentionModel, s, y, sw, fixed, bounds):
        self.model, self.s, self.y, self.sw, self.fixed, self.b = model, s, y, sw, fixed, bounds
        self.w2 = sw**2
        lin_names = ("y_r", "y_s") if model.residual_form else ("y_s",)
        self.lin = [k for k in lin_names if k not in fixed]
        self.fixed_lin = {k: fixed[k] for k in lin_names if k in fixed}
        self.shape = [k for k in model.names if k not in ("y_r", "y_s") and k not in fixed]
        self.fixed_shape = {k: v for k, v in fixed.items() if k not in ("y_r", "y_s")}
        offsets = model.log_params
        self.offset = [offsets.get(k) for k in self.shape]

    def linear(self, S) -> dict[str, float]:
        """The bounded weighted least-squares (y_r, y_s) for one curve S (scalar arithmetic, exact)."""
        lin, b = self.lin, self.b
        if not lin:
            return {}
        if self.model.residual_form:
            cols = {"y_r": 1.0 - S, "y_s": S}
        else:
            cols = {"y_s": S}
        rhs = self.y
        for k, v in self.fixed_lin.items():
            rhs = rhs - v * cols[k]
        w2 = self.w2
        if len(lin) == 1:
            c = cols[lin[0]]
            wc = w2 * c
            den = float(wc @ c)
            v = float(wc @ rhs) / den if den > 0 else b[lin[0]][1]
            return {lin[0]: min(max(v, b[lin[0]][0]), b[lin[0]][1])}
        c1, c2 = cols[lin[0]], cols[lin[1]]
        w1c, w2c = w2 * c1, w2 * c2
        a11, a12, a22 = float(w1c @ c1), float(w1c @ c2), float(w2c @ c2)
        b1, b2 = float(w1c @ rhs), float(w2c @ rhs)
        (lo1, hi1), (lo2, hi2) = b[lin[0]], b[lin[1]]
        det = a11 * a22 - a12 * a12
        if det > 1e-14 * max(a11 * a22, 1e-300):
            u1, u2 = (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det
            if lo1 <= u1 <= hi1 and lo2 <= u2 <= hi2:
                return {lin[0]: u1, lin[1]: u2}

        def q(x1, x2):
            return -2 * (b1 * x1 + b2 * x2) + a11 * x1 * x1 + 2 * a12 * x1 * x2 + a22 * x2 * x2

        cands = []
        for e in (lo1, hi1):
            x2 = min(max((b2 - a12 * e) / a22, lo2), hi2) if a22 > 0 else lo2
            cands.append((q(e, x2), e, x2))
        for e in (lo2, hi2):
            x1 = min(max((b1 - a12 * e) / a11, lo1), hi1) if a11 > 0 else lo1
            cands.append((q(x1, e), x1, e))
        _, x1, x2 = min(cands)
        return {lin[0]: x1, lin[1]: x2}

    def _resid_S(self, S):
        p = {**self.fixed_lin, **self.linear(S)}
        if self.model.residual_form:
            y_r = p.get("y_r", 0.0)
            f = y_r + (p["y_s"] - y_r) * S
        else:
            f = p["y_s"] * S
        r = (f - self.y) * self.sw
        return np.where(np.isfinite(r), r, 1e10)

    # fitting coordinates: u = ln(x - offset) for log-scaled parameters, x otherwise
    def x_rows(self, U):
        """Natural parameters of rows ``U`` (m, k) of the fitting coordinates."""
        X = np.array(U, float, copy=True)
        for j, o in enumerate(self.offset):
            if o is not None:
                X[:, j] = np.exp(U[:, j]) + o
        return X

    def u_rows(self, X):
        """Fitting coordinates of rows ``X`` (m, k) of natural parameters: ln(x - offset) or x."""
        U = np.array(X, float, copy=True)
        for j, o in enumerate(self.offset):
            if o is not None:
                U[:, j] = np.log(X[:, j] - o)
        return U

    def fitted_rows(self, S):
        """The fitted curve of each row of S (m, n): y_r + (y_s - y_r) S (or y_s S).

        With the bounded weighted least-squares y_r, y_s of that row (the arithmetic of :meth:`linear`, vectorised over
        the rows).
        """
        lin, b, w2 = self.lin, self.b, self.w2
        cols = {"y_r": 1.0 - S, "y_s": S} if self.model.residual_form else {"y_s": S}
        rhs, f = self.y, 0.0
        for k, v in self.fixed_lin.items():
            rhs = rhs - v * cols[k]
            f = f + v * cols[k]
        if not lin:
            return f + np.zeros_like(S)
        if len(lin) == 1:
            c = cols[lin[0]]
            wc = w2 * c
            den = np.einsum("mn,mn->m", wc, c)
            v = np.where(den > 0, np.einsum("mn,mn->m", wc, np.broadcast_to(rhs, S.shape)) / den, b[lin[0]][1])
            return f + np.clip(v, *b[lin[0]])[:, None] * c
        c1, c2 = cols[lin[0]], cols[lin[1]]
        C = np.empty((S.shape[0], 3, S.shape[1]))  # (m, 3, n): the Gram matrix in one product
        C[:, 0], C[:, 1], C[:, 2] = c1, c2, rhs
        gram = (C * w2) @ C.transpose(0, 2, 1)
        a11, a12, a22, b1, b2 = gram[:, 0, 0], gram[:, 0, 1], gram[:, 1, 1], gram[:, 0, 2], gram[:, 1, 2]
        (lo1, hi1), (lo2, hi2) = b[lin[0]], b[lin[1]]
        det = a11 * a22 - a12 * a12
        with np.errstate(divide="ignore", invalid="ignore"):  # det = 0 (a singular row): not 'inside', edges below
            u1, u2 = (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det
        inside = (det > 1e-14 * np.maximum(a11 * a22, 1e-300)) & (u1 >= lo1) & (u1 <= hi1) & (u2 >= lo2) & (u2 <= hi2)
        x1, x2 = u1, u2
        if not inside.all():
            # the unconstrained minimum leaves the box: the constrained one lies on an edge it violates, at the
            # best point of that edge (a corner included); both candidates are feasible, the lower one wins
            out = np.flatnonzero(~inside)
            a11, a12, a22, b1, b2 = a11[out], a12[out], a22[out], b1[out], b2[out]
            with np.errstate(divide="ignore", invalid="ignore"):
                p1 = np.clip(np.where(np.isfinite(u1[out]), u1[out], lo1), lo1, hi1)
                p2 = np.clip(np.where(np.isfinite(u2[out]), u2[out], lo2), lo2, hi2)
                q2 = np.clip((b2 - a12 * p1) / a22, lo2, hi2)
                q1 = np.clip((b1 - a12 * p2) / a11, lo1, hi1)
            q2, q1 = np.where(np.isfinite(q2), q2, p2), np.where(np.isfinite(q1), q1, p1)
            X1, X2 = np.stack([p1, q1]), np.stack([q2, p2])
            q = -2 * (b1 * X1 + b2 * X2) + a11 * X1 * X1 + 2 * a12 * X1 * X2 + a22 * X2 * X2
            pick = (q[1] < q[0]).astype(int)
            x1, x2 = u1.copy(), u2.copy()
            x1[out], x2[out] = X1[pick, np.arange(out.size)], X2[pick, np.arange(out.size)]
        return f + x1[:, None] * c1 + x2[:, None] * c2

    def resid_rows(self, U):
        """Weighted projected residuals (m, n) at rows ``U`` (m, k) of the fitting coordinates."""
        X = self.x_rows(U)
        with np.errstate(all="ignore"):
            S = self.model.saturation(
                self.s[None, :], **self.fixed_shape, **{name: X[:, j][:, None] for j, name in enumerate(self.shape)}
            )
            S = np.broadcast_to(S, (X.shape[0], self.s.size))
            r = (self.fitted_rows(S) - self.y) * self.sw
        return np.where(np.isfinite(r), r, 1e10)

    def resid_jac_rows(self, U, hi):
        """Residuals (m, n) at rows ``U`` (m, k) and their forward-difference Jacobians (m, n, k).

        All in one evaluation of the model (backward where a forward step would leave the box ``U <= hi``: a one-sided
        derivative from inside).
        """
        m, k = U.shape
        h = 1.49e-8 * np.maximum(np.abs(U), 1.0)
        h = np.where(U + h > hi, -h, h)
        pts = np.concatenate([U[:, None, :], U[:, None, :] + h[:, :, None] * np.eye(k)], axis=1)
        Rs = self.resid_rows(pts.reshape(m * (k + 1), k)).reshape(m, k + 1, -1)
        return Rs[:, 0], ((Rs[:, 1:] - Rs[:, :1]) / h[:, :, None]).transpose(0, 2, 1)

    def full(self, x) -> dict:
        S = self.model.saturation(self.s, **self.fixed_shape, **dict(zip(self.shape, x)))
        return {**self.fixed, **dict(zip(self.shape, (float(v) for v in x))), **self.linear(S)}


def _grid_values(par: Parameter, lo: float, hi: float, s_min: float, s_max: float, knots) -> np.ndarray:
    """The start-grid values of one parameter on its own scale, within [lo, hi]."""
    if par.kind in ("suction", "inverse_suction", "suction_to_absolute"):
        f = par.grid_span
        if par.kind == "inverse_suction":
            a, b = max(lo, 1.0 / (f * s_max)), min(hi, f / s_min)
        else:
            a, b = max(lo, s_min / f), min(hi, s_max * f)
        if a >= b:
            a, b = lo, hi
        k = max(int(np.ceil(np.log10(b / a) * par.grid)) + 1, 2)
        vals = np.concatenate([np.geomspace(a, b, k), [lo * 1.0000001, hi / 1.0000001]])
        if par.kinks_at_data:
            inside = knots[(knots > lo) & (knots < hi)]
            mids = np.sqrt(inside[1:] * inside[:-1])
            vals = np.concatenate([vals, inside, mids])
        return np.unique(vals[(vals >= lo) & (vals <= hi)])
    if par.log_offset is not None:
        o = par.log_offset
        return o + np.geomspace((lo - o) * 1.0000001, (hi - o) / 1.0000001, par.grid)
    return np.linspace(lo, hi, par.grid)


def _screen(pb: _Problem, idx):
    """Projected RSS over the start grid.

    Returns (names, axes, rss array of the grid's shape, mixture weights or None, mixture).

    The grid parameters are passed to the model on separate broadcast axes, so a part of the model that
    depends on some of them only is evaluated once per combination of those; each curve enters the projection
    by its three weighted moments. A mixture's two components are evaluated on their own axes and every pair
    is combined from the components' moments and cross products (no curve of a pair is ever built).
    """
    model = pb.model
    mix = model.mixture if model.mixture is not None and model.mixture[0] in pb.shape else None
    grid_names = [k for k in pb.shape if mix is None or k != mix[0]]
    s, y, w2 = pb.s[idx], pb.y[idx], pb.w2[idx]
    pos = pb.s[pb.s > 0]
    knots = _knots(pb.s)
    axes = [_grid_values(model.parameter(k), *pb.b[k], float(pos.min()), float(pos.max()), knots) for k in grid_names]
    nd, shape = len(axes), tuple(len(a) for a in axes)
    par = {
        k: a.reshape([-1 if i == j else 1 for i in range(nd)] + [1]) for j, (k, a) in enumerate(zip(grid_names, axes))
    }
    sb = s.reshape((1,) * nd + (-1,))
    wy = w2 * y
    W, Y, YY = w2.sum(), wy.sum(), wy @ y
    weights = None
    with np.errstate(all="ignore"):
        if mix is None:
            mS, mSS, mSy = (np.empty(shape) for _ in range(3))
            step = max(1, _CHUNK // max(s.size * int(np.prod(shape[1:])), 1)) if nd else 1
            for start in range(0, shape[0] if nd else 1, step):
                sl = slice(start, start + step)
                p = {k: (v[sl] if j == 0 else v) for j, (k, v) in enumerate(par.items())}
                S = model.saturation(sb, **pb.fixed_shape, **p)
                S = np.broadcast_to(S, ((min(step, shape[0] - start),) + shape[1:] if nd else ()) + (s.size,))
                mS[sl], mSS[sl], mSy[sl] = S @ w2, (S * S) @ w2, S @ wy
        else:
            S1, S2 = mix[1](sb, **pb.fixed_shape, **{k: v for k, v in par.items()})
            S1, S2 = np.broadcast_to(S1, S1.shape[:-1] + (s.size,)), np.broadcast_to(S2, S2.shape[:-1] + (s.size,))
            m1, m2, G11, G22 = S1 @ w2, S2 @ w2, (S1 * S1) @ w2, (S2 * S2) @ w2
            m1y, m2y = S1 @ wy, S2 @ wy
            G12 = _cross(S1 * w2, S2, shape)
            weights = np.broadcast_to(_mixture_weight(W, Y, m1, m2, G11, G12, G22, m1y, m2y), shape)
            u = 1.0 - weights
            mS = weights * m1 + u * m2
            mSS = weights * weights * G11 + 2 * weights * u * G12 + u * u * G22
            mSy = weights * m1y + u * m2y
        rss = np.broadcast_to(_projected_rss(pb, W, Y, YY, mS, mSS, mSy), shape).copy()
    rss[~np.isfinite(rss)] = np.inf
    if model.grid_order is not None and all(k in par for k in model.grid_order):
        a, b = model.grid_order
        rss[~np.broadcast_to(par[a][..., 0] >= par[b][..., 0], shape)] = np.inf
    return grid_names, axes, rss, weights, mix


def _cross(A, B, shape):
    """Σ_n A[..., n] B[..., n] of two arrays broadcast over the grid axes.

    Each is summed on its own axes only (a matrix product when they share none): the result broadcasts to ``shape``.
    """
    nd = len(shape)
    letters = "abcdefghijklmnopqrstuvwxy"[:nd]
    ax_a = [i for i in range(nd) if A.shape[i] > 1]
    ax_b = [i for i in range(nd) if B.shape[i] > 1]
    out = sorted(set(ax_a) | set(ax_b))
    spec = (
        f"{''.join(letters[i] for i in ax_a)}z,{''.join(letters[i] for i in ax_b)}z->{''.join(letters[i] for i in out)}"
    )
    C = np.einsum(
        spec, A.reshape([A.shape[i] for i in ax_a] + [-1]), B.reshape([B.shape[i] for i in ax_b] + [-1]), optimize=True
    )
    return C.reshape([shape[i] if i in out else 1 for i in range(nd)])


def _mixture_weight(W, Y, m1, m2, G11, G12, G22, m1y, m2y):
    """The weight w = c1/(c1 + c2) of S = w S1 + (1 - w) S2, clipped to [0, 1]; 0.5 where undefined.

    From the unconstrained weighted linear fit y = c0 + c1 S1 + c2 S2 (its normal equations from the moments,
    regularised by 1e-14 of their trace).
    """
    m1, m2, G11, G12, G22, m1y, m2y = np.broadcast_arrays(m1, m2, G11, G12, G22, m1y, m2y)
    A = np.stack(
        [np.stack([np.full_like(m1, W), m1, m2], -1), np.stack([m1, G11, G12], -1), np.stack([m2, G12, G22], -1)], -2
    )
    rhs = np.stack([np.full_like(m1, Y), m1y, m2y], -1)
    A = A + np.eye(3) * (1e-14 * (W + G11 + G22))[..., None, None]
    with np.errstate(all="ignore"):
        try:
            c = np.linalg.solve(A, rhs[..., None])[..., 0]
        except np.linalg.LinAlgError:
            c = (np.linalg.pinv(A) @ rhs[..., None])[..., 0]
        w = c[..., 1] / (c[..., 1] + c[..., 2])
    return np.clip(np.where(np.isfinite(w), w, 0.5), 0.0, 1.0)


def _local_minima(rss: np.ndarray) -> np.ndarray:
    """Flat indices of the grid's local minima (no neighbour along any axis lower), best first."""
    pad = np.pad(rss, 1, constant_values=np.inf)
    core = tuple(slice(1, -1) for _ in range(rss.ndim))
    mask = np.isfinite(rss)
    for ax in range(rss.ndim):
        for shift in (-1, 1):
            sl = list(core)
            sl[ax] = slice(1 + shift, rss.shape[ax] + 1 + shift)
            mask &= rss <= pad[tuple(sl)]
    idx = np.flatnonzero(mask.ravel())
    return idx[np.argsort(rss.ravel()[idx])]


def _screen_points(s) -> np.ndarray:
    """Indices of the data points that rank the start grid and run the first, loose refinement.

    All points, or ``_SCREEN_POINTS`` of them evenly spread in the order of suction.
    """
    order = np.argsort(s, kind="stable")
    if s.size <= _SCREEN_POINTS:
        return order
    return order[np.linspace(0, s.size - 1, _SCREEN_POINTS).round().astype(int)]


def _starts(pb: _Problem, n_starts: int):
    """Start points (shape parameters) and their search boxes from the grid, best first."""
    names, axes, rss, weights, mix = _screen(pb, _screen_points(pb.s))
    flat = rss.ravel()
    minima = _local_minima(rss) if rss.ndim else np.array([0])
    if minima.size == 0:
        minima = np.array([int(np.argmin(flat))])
    lo, hi = (np.array([pb.b[k][0] for k in pb.shape]), np.array([pb.b[k][1] for k in pb.shape]))
    knots = _knots(pb.s)
    kinked = [j for j, k in enumerate(names) if pb.model.parameter(k).kinks_at_data]
    if kinked:
        return _interval_starts(pb, names, axes, rss, weights, mix, kinked[0], lo, hi, knots, n_starts)
    out = []
    for g in minima[:n_starts]:
        pos = np.unravel_index(int(g), rss.shape) if rss.ndim else ()
        out.append((_point(pb, names, axes, weights, mix, pos), lo, hi))
    return out


def _point(pb, names, axes, weights, mix, pos) -> np.ndarray:
    vals = {k: float(axes[i][pos[i]]) for i, k in enumerate(names)}
    if mix is not None:
        vals[mix[0]] = float(weights[pos])
    return np.array([vals[k] for k in pb.shape])


def _interval_starts(pb, names, axes, rss, weights, mix, axis, lo, hi, knots, n_starts):
    """Starts of a model with kinks at the data suctions in one parameter.

    The best grid point of each interval between neighbouring data suctions, the intervals ranked by it; the box of each
    start is its interval.
    """
    j = pb.shape.index(names[axis])
    edges = np.unique(np.concatenate([[lo[j]], knots[(knots > lo[j]) & (knots < hi[j])], [hi[j]]]))
    values = axes[axis]
    best_along = np.moveaxis(rss, axis, 0).reshape(len(values), -1)
    arg = np.argmin(best_along, axis=1)
    val = best_along[np.arange(len(values)), arg]
    which = np.clip(np.searchsorted(edges, values, side="right") - 1, 0, edges.size - 2)
    ranked = []
    for i in range(edges.size - 1):
        inside = np.flatnonzero((values >= edges[i]) & (values <= edges[i + 1]))
        if inside.size == 0:
            continue
        g = inside[np.argmin(val[inside])]
        ranked.append((val[g], i, g))
    del which
    ranked.sort()
    out = []
    other_shape = tuple(n for a, n in enumerate(rss.shape) if a != axis)
    for v, i, g in ranked[: max(n_starts, 6)]:
        rest = np.unravel_index(int(arg[g]), other_shape) if other_shape else ()
        pos = tuple(rest[:axis]) + (int(g),) + tuple(rest[axis:])
        blo, bhi = lo.copy(), hi.copy()
        blo[j], bhi[j] = edges[i], edges[i + 1]
        out.append((_point(pb, names, axes, weights, mix, pos), blo, bhi))
    return out


def _distinct(U, cost, close: float) -> np.ndarray:
    """Indices of the rows of ``U`` with a cost within ``close`` (relative) of the lowest, best first.

    Without the rows that repeat a better one (every coordinate within 1e-6 of it, relative).
    """
    order = np.argsort(cost, kind="stable")
    order = order[cost[order] <= cost[order[0]] * (1 + close) + 1e-300]
    out: list[int] = []
    for i in order:
        if not any(np.all(np.abs(U[i] - U[j]) <= 1e-6 * (1 + np.abs(U[j]))) for j in out):
            out.append(int(i))
    return np.array(out)


def _interval_walk(pb: _Problem, u, j: int, lo, hi):
    """Polish a start of a model with kinks at the data suctions in parameter ``j``.

    Fitting coordinates ``u``, box ``lo``, ``hi``: a bounded fit in each interval between neighbouring distinct data
    suctions around ``u[j]`` (one each side), moving on while the lowest lies next to an unexplored one. Returns (u,
    cost, converged).
    """
    o = pb.offset[j]
    knots = np.unique(pb.s[pb.s > 0])
    knots = np.log(knots - o) if o is not None else knots
    lo_all, hi_all = pb.u_rows(np.array([[pb.b[k][0] for k in pb.shape], [pb.b[k][1] for k in pb.shape]]))
    edges = np.unique(np.concatenate([[lo_all[j]], knots[(knots > lo_all[j]) & (knots < hi_all[j])], [hi_all[j]]]))
    here = int(np.clip(np.searchsorted(edges, u[j], side="right") - 1, 0, edges.size - 2))
    start, cost, converged = u, np.inf, False
    done: set[int] = set()
    while True:
        todo = np.array([i for i in range(here - 1, here + 2) if 0 <= i < edges.size - 1 and i not in done])
        if todo.size == 0:
            return u, cost, converged
        done.update(todo.tolist())
        U0 = np.repeat(u[None, :], todo.size, axis=0)
        LO, HI = np.repeat(lo[None, :], todo.size, axis=0), np.repeat(hi[None, :], todo.size, axis=0)
        LO[:, j], HI[:, j] = edges[todo], edges[todo + 1]
        U0[:, j] = np.clip(start[j], LO[:, j], HI[:, j])
        inner = (U0[:, j] <= LO[:, j]) | (U0[:, j] >= HI[:, j])
        U0[:, j] = np.where(inner, 0.5 * (LO[:, j] + HI[:, j]), U0[:, j])  # other intervals: from their middle
        Ut, ct, okt = _levenberg_marquardt(pb, U0, LO, HI, ftol=1e-14, max_iter=200)
        b = int(np.argmin(ct))
        if ct[b] < cost:
            u, cost, converged, here = Ut[b], float(ct[b]), bool(okt[b]), int(todo[b])


def _step_search(pb: _Problem, model: RetentionModel, u, converged: bool):
    """Search a pore system as a step.

    Its n at the upper bound and its α in every interval between neighbouring data suctions (the objective is piecewise
    flat in α there, so a local fit stays where it starts), each refined within its interval, the best then refined in
    the whole box; kept when it lowers the cost. Returns (u, converged).
    """
    lo_all, hi_all = pb.u_rows(np.array([[pb.b[k][0] for k in pb.shape], [pb.b[k][1] for k in pb.shape]]))
    R, _ = pb.resid_jac_rows(u[None, :], hi_all[None, :])
    best_c = float(R[0] @ R[0])
    for a, n in model.steps:
        if a not in pb.shape or n not in pb.shape:
            continue
        ja, jn = pb.shape.index(a), pb.shape.index(n)
        knots = _knots(pb.s)
        x = 1.0 / knots if model.parameter(a).kind == "inverse_suction" else knots
        o = pb.offset[ja]
        ek = np.log(x - o) if o is not None else x
        edges = np.unique(np.concatenate([[lo_all[ja]], ek[(ek > lo_all[ja]) & (ek < hi_all[ja])], [hi_all[ja]]]))
        rows = edges.size - 1
        U0 = np.repeat(u[None, :], rows, axis=0)
        LO, HI = np.repeat(lo_all[None, :], rows, axis=0), np.repeat(hi_all[None, :], rows, axis=0)
        LO[:, ja], HI[:, ja] = edges[:-1], edges[1:]
        U0[:, ja] = 0.5 * (edges[:-1] + edges[1:])
        U0[:, jn] = hi_all[jn]
        Ut, ct, _ = _levenberg_marquardt(pb, U0, LO, HI, ftol=1e-12, max_iter=100)
        i = int(np.argmin(ct))
        U2, c2, ok2 = _levenberg_marquardt(pb, Ut[i : i + 1], lo_all[None, :], hi_all[None, :], 1e-14, 200)
        if c2[0] < best_c * (1 - 1e-12):
            u, best_c, converged = U2[0], float(c2[0]), bool(ok2[0])
    return u, converged


def _knots(s, most: int = 150) -> np.ndarray:
    """The distinct positive data suctions where a kinked model changes form (at most ``most``, evenly chosen)."""
    knots = np.unique(s[s > 0])
    if knots.size > most:
        knots = knots[np.linspace(0, knots.size - 1, most).round().astype(int)]
    return knots


def _levenberg_marquardt(pb: _Problem, U, lo, hi, ftol: float, max_iter: int, prune: float = 0.0):
    """Box-constrained Levenberg-Marquardt from every row of ``U`` at once.

    Steps are projected on each row's box ``lo``, ``hi``; Marquardt's diagonal scaling.

    Each row runs its own iteration (its own damping, acceptance and stop), the rows are only evaluated
    together. A variable on a bound whose gradient points outwards is frozen for the step (an active
    constraint). A row stops when an accepted step lowers its cost by less than ``ftol`` relative, when no
    step helps, or after ``max_iter`` accepted steps (not converged). With ``prune`` > 0, a row is also given up
    (not converged) once another has converged at cost c and the lowest cost its undamped Gauss-Newton model
    can reach is above ``prune`` c: a start that its own local model places in a worse basin.
    Returns (U, cost = sum r^2 per row, converged per row).
    """
    U = np.clip(np.asarray(U, float), lo, hi)
    G, k = U.shape
    R, J = pb.resid_jac_rows(U, hi)
    cost = np.einsum("gn,gn->g", R, R)
    lam = np.full(G, 1e-3)
    active = np.ones(G, bool)
    converged = np.zeros(G, bool)
    steps = np.zeros(G, int)
    eye = np.eye(k, dtype=bool)

    def solve(M, rhs):
        try:
            return np.linalg.solve(M, rhs[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:  # a singular row: solve row by row, NaN where singular
            out = np.full(rhs.shape, np.nan)
            for i in range(M.shape[0]):
                try:
                    out[i] = np.linalg.solve(M[i], rhs[i])
                except np.linalg.LinAlgError:
                    pass
            return out

    with np.errstate(all="ignore"):
        for _ in range(64 * max_iter):
            a = np.flatnonzero(active)
            if a.size == 0:
                break
            Ja, Ua, ca, loa, hia = J[a], U[a], cost[a], lo[a], hi[a]
            g = np.einsum("gnk,gn->gk", Ja, R[a])
            A = np.einsum("gnk,gnl->gkl", Ja, Ja)
            frozen = ((Ua <= loa) & (g > 0)) | ((Ua >= hia) & (g < 0))
            any_frozen = frozen.any()
            if any_frozen:  # frozen variables: their rows and columns of the system replaced by the identity
                off = frozen[:, :, None] | frozen[:, None, :]
                A = np.where(off, 0.0, A) + frozen[:, :, None] * eye
                g = np.where(frozen, 0.0, g)
            d = np.maximum(np.diagonal(A, axis1=1, axis2=2), 1e-300)
            step = solve(A + (lam[a][:, None] * d)[:, :, None] * eye, -g)
            ok = np.all(np.isfinite(step), axis=1)
            trial = np.clip(Ua + np.where(ok[:, None], step, 0.0), loa, hia)
            step = trial - Ua
            R_t, J_t = pb.resid_jac_rows(trial, hia)
            c_t = np.where(ok, np.einsum("gn,gn->g", R_t, R_t), np.inf)
            acc = c_t < ca
            small = (ca - c_t <= ftol * ca) | (np.max(np.abs(step), axis=1) <= 1e-13 * (1 + np.max(np.abs(Ua), axis=1)))
            i = a[acc]
            lam[i] = np.maximum(lam[i] * 0.2, 1e-12)
            U[i], R[i], J[i], cost[i] = trial[acc], R_t[acc], J_t[acc], c_t[acc]
            steps[i] += 1
            stop = i[small[acc]]
            active[stop], converged[stop] = False, True
            active[i[~small[acc] & (steps[i] >= max_iter)]] = False
            if prune and converged.any() and active[a].any():
                live = active[a]
                floor = ca[live] - np.einsum(
                    "gk,gk->g", g[live], solve(A[live] + (1e-12 * d[live])[:, :, None] * eye, g[live])
                )
                active[a[live][floor > prune * cost[converged].min()]] = False
            rej = ~acc
            if rej.any():
                # a rejected step: more damping; no descent left (the undamped Gauss-Newton step promises a
                # decrease below ftol, or the damping has made every step vanish): a (bounded) minimum
                j = a[rej]
                lam[j] *= 8.0
                A_r, g_r = A[rej], g[rej]
                promised = np.einsum("gk,gk->g", g_r, solve(A_r + (1e-12 * d[rej])[:, :, None] * eye, g_r))
                flat = j[(lam[j] > 1e14) | (promised <= ftol * ca[rej]) | frozen[rej].all(1)]
                active[flat], converged[flat] = False, True
    return U, cost, converged


def fit_model(name: str, s, y, fixed=None, weights=None, n_starts: int | None = None) -> RetentionFit:
    r"""Fit one retention model by (weighted) least squares at the global optimum inside the bounds.

    Minimises :math:`\sum_i w_i\,(y(s_i) - y_i)^2` with y(s) the model of ``MODELS[name]`` (see the
    module docstring for the search: variable projection of y_r, y_s; a grid over the shape parameters;
    bounded refinement of the best grid minima).

    Parameters
    ----------
    name : str
        A key of :data:`MODELS`.
    s : array_like
        Suctions [Pa], >= 0.
    y : array_like
        Water contents θ [m³/m³] or degrees of saturation S_R [-].
    fixed : dict[str, float], optional
        Parameters held at given values (internal names and SI units).
    weights : array_like, optional
        Per-point weights (default 1): a reading of weight 2 counts as that reading twice.
    n_starts : int, optional
        Grid minima refined (default 3 for up to two shape parameters, 8 above; at least 6 intervals of a
        parameter with kinks at the data suctions).

    Returns
    -------
    RetentionFit
        Estimates, standard errors, statistics, and the fitted curve as callables.

    Raises
    ------
    FitError
        Negative, NaN or infinite data, fewer than two distinct positive suctions, too few points, or a
        fixed value outside its range.

    References
    ----------
    The models: each entry's ``references`` (e.g. van Genuchten 1980, doi:10.2136/sssaj1980.03615995004400050002x,
    eq. 21). Marquardt, D. W. (1963). An algorithm for least-squares estimation of nonlinear parameters.
    J. Soc. Ind. Appl. Math. 11(2):431-441, doi:10.1137/0111030 (the local refinement).
    Golub, G. H., Pereyra, V. (1973). The differentiation of pseudo-inverses and nonlinear least squares
    problems whose variables separate. SIAM J. Numer. Anal. 10(2):413-432, doi:10.1137/0710036
    (variable projection).
    """
    if name not in MODELS:
        raise FitError(f"unknown retention model '{name}'; choose from {', '.join(MODELS)}")
    s = np.asarray(s, float)
    y = np.asarray(y, float)
    fixed = dict(fixed or {})
    model = MODELS[name]
    if s.shape != y.shape or s.ndim != 1:
        raise FitError("suction and water content must be 1-D arrays of the same length")
    if not np.all(np.isfinite(s)) or not np.all(np.isfinite(y)) or np.any(s < 0):
        raise FitError("the retention data hold negative, NaN or infinite values")
    if np.unique(s[s > 0]).size < 2:
        raise FitError("fewer than two distinct positive suctions: no retention curve can be fitted")
    b = bounds_for(s, y, name)
    for k, v in fixed.items():
        if k not in b:
            raise FitError(f"'{k}' is not a parameter of {name} ({', '.join(model.names)})")
        lo, hi = b[k]
        if not lo <= v <= hi:
            raise FitError(f"fixed value {k} = {v:.6g} is outside its range [{lo:.4g}, {hi:.4g}]")
    free = [k for k in model.names if k not in fixed]
    if s.size <= len(free):
        raise FitError(f"{s.size} points for {len(free)} free parameters: too few to fit")

    sw = np.ones_like(y) if weights is None else np.sqrt(np.asarray(weights, float))
    pb = _Problem(model, s, y, sw, fixed, b)
    best_x, converged = np.array([]), True
    if pb.shape:
        k = len(pb.shape)
        n_starts = n_starts or (3 if k <= 2 else 8)
        starts = _starts(pb, n_starts)
        X0 = np.array([x for x, _, _ in starts])
        ulo, uhi = pb.u_rows(np.array([b for _, b, _ in starts])), pb.u_rows(np.array([b for _, _, b in starts]))
        lo_x, hi_x = np.array([b for _, b, _ in starts]), np.array([b for _, _, b in starts])
        U0 = np.clip(pb.u_rows(np.clip(X0, lo_x, hi_x)), ulo, uhi)
        # phase 1: every start, loose tolerance, on the points that ranked the grid
        idx = _screen_points(s)
        pb1 = pb if idx.size == s.size else _Problem(model, s[idx], y[idx], sw[idx], fixed, b)
        loose = 20 if k <= 3 else 80
        U1, cost1, _ = _levenberg_marquardt(pb1, U0, ulo, uhi, ftol=1e-6, max_iter=loose, prune=2.0)
        order = np.arange(U1.shape[0])
        if pb1 is not pb:  # those within 5 % of the best, loosely again on all points
            order = _distinct(U1, cost1, 0.05)
            U1, cost1, _ = _levenberg_marquardt(pb, U1[order], ulo[order], uhi[order], ftol=1e-6, max_iter=loose)
        # phase 2 on all points: polish the distinct end points within 1e-4 of the best
        keep = _distinct(U1, cost1, 1e-4)
        order = order[keep]
        kinked = [j for j, p in enumerate(pb.shape) if model.parameter(p).kinks_at_data]
        if kinked and np.unique(s[s > 0]).size > _knots(s).size:
            # the start boxes held several data suctions: polish in the intervals between them around each
            walks = [_interval_walk(pb, U1[r], kinked[0], ulo[o], uhi[o]) for r, o in zip(keep, order)]
            u, _, converged = min(walks, key=lambda w: w[1])
        else:
            U2, cost2, ok2 = _levenberg_marquardt(pb, U1[keep], ulo[order], uhi[order], ftol=1e-14, max_iter=200)
            i = int(np.argmin(cost2))
            u, converged = U2[i], bool(ok2[i])
        if model.steps and not any(k in fixed for pair in model.steps for k in pair):
            u, converged = _step_search(pb, model, u, converged)
        best_x = pb.x_rows(u[None, :])[0]
    optimum = pb.full(best_x)
    if model.canonical is not None and not fixed:
        optimum = model.canonical(optimum)
    nl = summarize_fit(
        model.water, s, y, model.names, optimum, b, fixed, weights, converged, log_params=model.log_params
    )
    fit = RetentionFit(
        **{f.name: getattr(nl, f.name) for f in fields(nl)}, model=name, suction_points=tuple(_knots(s, 200).tolist())
    )
    fit.extra["condition_number"], fit.extra["weak_direction"] = conditioning(
        model.water, s, fit.params_si, [k for k in fit.free if k not in fit.held], weights
    )
    fit.warnings = identifiability_warnings(fit)
    return fit


def confidence_band(name: str, fit: NonlinearFit, s_grid, level_t: float | None = None):
    r"""95 % confidence band of the mean fitted curve (delta method).

    .. math:: y(s) \pm t\, \sqrt{g(s)^T\, \mathrm{Cov}\, g(s)}, \qquad g = \partial y / \partial p

    Parameters
    ----------
    name : str
        A key of :data:`MODELS`.
    fit : NonlinearFit
        A fit of that model.
    s_grid : array_like
        Suctions [Pa].
    level_t : float, optional
        The multiplier t (default: the fit's Student t of 95 %).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        Lower and upper band [unit of y]; both equal the curve without a covariance.

    References
    ----------
    Bates, D. M., Watts, D. G. (1988). Nonlinear Regression Analysis and Its Applications. Wiley,
    doi:10.1002/9780470316757, section 2.3.1 (confidence band of the expectation surface).
    """
    model = MODELS[name]
    s_grid = np.asarray(s_grid, float)
    p = getattr(fit, "params_si", fit.params)
    base = model.water(s_grid, **p)
    if fit.covariance is None or not fit.free:
        return base, base
    cols = []
    for k in fit.free:
        h = 1e-6 * max(abs(p[k]), 1e-6)
        up = dict(p, **{k: p[k] + h})
        dn = dict(p, **{k: p[k] - h})
        cols.append((model.water(s_grid, **up) - model.water(s_grid, **dn)) / (2 * h))
    J = np.column_stack(cols)
    var = np.einsum("ij,jk,ik->i", J, fit.covariance, J)
    half = (level_t if level_t is not None else fit.t) * np.sqrt(np.maximum(var, 0.0))
    return base - half, base + half


def fit_hysteresis(s_d, y_d, s_w, y_w, fixed=None, weights=None) -> NonlinearFit:
    r"""Drying and wetting branches fitted jointly by van Genuchten (m = 1 - 1/n) after Kool & Parker (1987).

    Both branches share y_s, y_r and n; α differs (α_d drying, α_w wetting):

    .. math:: y = y_r + (y_s - y_r)\left[1 + (\alpha_{d|w}\, s)^n\right]^{-(1 - 1/n)}

    Parameters
    ----------
    s_d, y_d : array_like
        Drying branch: suctions [Pa] and water contents [m³/m³] (or S_R [-]).
    s_w, y_w : array_like
        Wetting branch, the same units.
    fixed : dict[str, float], optional
        Any of y_r, y_s, n, alpha_d, alpha_w held fixed [SI].
    weights : array_like, optional
        Per-point weights, drying points first.

    Returns
    -------
    RetentionFit
        Parameters y_r, y_s, n, alpha_d [1/Pa], alpha_w [1/Pa] (``model`` "kool_parker"; ``params`` by JSON name).

    References
    ----------
    Kool, J. B., Parker, J. C. (1987). Water Resour. Res. 23(1):105-114, doi:10.1029/WR023i001p00105;
    van Genuchten (1980), doi:10.2136/sssaj1980.03615995004400050002x, eq. 21.
    """
    s = np.concatenate([np.asarray(s_d, float), np.asarray(s_w, float)])
    y = np.concatenate([np.asarray(y_d, float), np.asarray(y_w, float)])
    branch = np.concatenate([np.zeros(len(s_d)), np.ones(len(s_w))])

    def water(x, y_r, y_s, n, alpha_d, alpha_w):
        alpha = np.where(branch == 0, alpha_d, alpha_w)
        return rp.vg_water(x, y_r, y_s, alpha, n)

    b = bounds_for(s, y, hysteresis_model().name)
    b = {**b, "alpha_d": b["alpha"], "alpha_w": b["alpha"]}
    pos = s[s > 0]
    mid = float(np.median(pos)) if pos.size else 1.0
    base = {"y_r": max(float(np.min(y)) * 0.5, 0.0), "y_s": float(np.max(y))}
    starts = [
        {**base, "n": n, "alpha_d": a / mid, "alpha_w": a * r / mid}
        for a in (0.3, 1.0, 3.0)
        for n in (1.5, 3.0, 8.0)
        for r in (1.0, 2.0)
    ]
    nl = fit_curve(
        water,
        s,
        y,
        ("y_r", "y_s", "n", "alpha_d", "alpha_w"),
        starts,
        b,
        fixed,
        weights,
        log_params={"n": 1.0, "alpha_d": 0.0, "alpha_w": 0.0},
    )
    fit = RetentionFit(
        **{f.name: getattr(nl, f.name) for f in fields(nl)},
        model="kool_parker",
        suction_points=tuple(_knots(s, 200).tolist()),
    )
    fit.extra["condition_number"], fit.extra["weak_direction"] = conditioning(
        water, s, fit.params_si, [k for k in fit.free if k not in fit.held], weights
    )
    fit.warnings = identifiability_warnings(fit)
    return fit
