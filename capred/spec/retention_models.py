"""The water-retention models of `capred retention`: one registry, declared without numerics.

Each :class:`RetentionModel` of :data:`MODELS` holds everything about a model: its name, label, equation
(plain text), parameters with units and valid ranges, references (keys of :mod:`capred.references`), the
method text of report.html, the help text and the line style, with its functions (S(s), its inverse, ...)
named as ``"module:function"`` (they live in `capred.fitting.retention_models`, imported only when a model is
evaluated or fitted). Adding a model is adding one entry. Importing this module imports no numpy.

References
----------
.. [1] van Genuchten, M. Th. (1980). A closed-form equation for predicting the hydraulic conductivity of
   unsaturated soils. Soil Sci. Soc. Am. J. 44:892-898. doi:10.2136/sssaj1980.03615995004400050002x.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from .callables import CallableField, resolve

__all__ = ["MODELS", "N_POSITIVE", "REGISTRY", "Y_R", "Y_S", "Parameter", "RetentionModel", "make_parameter"]

#: where the registry's numerical functions live
_F = "capred.fitting.retention_models:"


@dataclass(frozen=True)
class Parameter:
    r"""One parameter of a retention model.

    Attributes
    ----------
    name : str
        Internal name (the key of ``NonlinearFit.params``).
    symbol : str
        Matplotlib mathtext, e.g. ``r"$\alpha$"``.
    unit : str
        Unit of the internal value: "Pa", "1/Pa", "-", or "y" (the unit of the fitted water quantity,
        m³/m³ for θ, - for S_R).
    description : str
        Meaning, in a few words.
    kind : str
        How its search range follows the data: "residual" [0, max y]; "saturated" [min y, max(1, max y)];
        "suction" [lower·s_min, upper·s_max]; "inverse_suction" [lower/s_max, upper/s_min]; "absolute"
        [lower, upper]; "suction_to_absolute" [lower·s_min, upper].
    lower, upper : float
        The numbers of that rule.
    log_offset : float or None
        The parameter's own scale is ln(value - log_offset) (None: linear). The start grid is evenly
        spaced and bound warnings are judged on that scale.
    grid : int
        Start-grid points: per decade for suction-like kinds, in total otherwise (0: not on the grid).
    kinks_at_data : bool
        The model has kinks in this parameter at the data suctions (searched interval by interval).
    grid_span : float
        Suction-like kinds: the start grid covers the data's suction range widened by this factor each way
        (plus the two bounds).
    domain : str
        The parameter's natural domain in its model's paper, with the reference (the search range lies inside
        it: capred's bounds only keep the search finite).
    """

    name: str
    symbol: str
    unit: str
    description: str
    kind: str = "absolute"
    lower: float = -math.inf
    upper: float = math.inf
    log_offset: float | None = None
    grid: int = 0
    kinks_at_data: bool = False
    grid_span: float = 100.0
    domain: str = ""

    def bounds(self, s_min: float, s_max: float, y_min: float, y_max: float) -> tuple[float, float]:
        """Search bounds [unit] for data with positive suctions in [s_min, s_max] [Pa] and y in [y_min, y_max].

        Parameters
        ----------
        s_min, s_max : float
            Smallest and largest positive suction of the data [Pa].
        y_min, y_max : float
            Smallest and largest water quantity of the data [unit of y].

        Returns
        -------
        tuple of float
            (lower, upper) in the parameter's SI unit.
        """
        if self.kind == "residual":
            return 0.0, y_max
        if self.kind == "saturated":
            return y_min, max(1.0, y_max)
        if self.kind == "suction":
            return self.lower * s_min, self.upper * s_max
        if self.kind == "inverse_suction":
            return self.lower / s_max, self.upper / s_min
        if self.kind == "suction_to_absolute":
            return self.lower * s_min, self.upper
        return self.lower, self.upper

    @property
    def range_text(self) -> str:
        """The valid range in words (s_min, s_max: the smallest and largest positive suction of the data)."""
        return {
            "residual": "0 … max(y)",
            "saturated": "min(y) … max(1, max(y))",
            "suction": f"{self.lower:g}·s_min … {self.upper:g}·s_max",
            "inverse_suction": f"{self.lower:g}/s_max … {self.upper:g}/s_min",
            "suction_to_absolute": f"{self.lower:g}·s_min … {self.upper:g} Pa",
        }.get(self.kind, f"{self.lower:g} … {self.upper:g}")


def make_parameter(
    name,
    symbol,
    unit,
    description,
    kind="absolute",
    lower=-math.inf,
    upper=math.inf,
    log_offset=None,
    grid=0,
    kinks=False,
    grid_span=100.0,
) -> Parameter:
    """A :class:`Parameter` from its fields in order (``kinks`` for ``kinks_at_data``), its domain left empty.

    Parameters
    ----------
    name, symbol, unit, description, kind : str
        As the fields of :class:`Parameter`.
    lower, upper, log_offset, grid, kinks, grid_span
        As the fields ``lower``, ``upper``, ``log_offset``, ``grid``, ``kinks_at_data``, ``grid_span``.

    Returns
    -------
    Parameter
    """
    return Parameter(name, symbol, unit, description, kind, lower, upper, log_offset, grid, kinks, grid_span)


def _dom(p: Parameter, text: str) -> Parameter:
    """``p`` with its natural domain and the paper that sets it."""
    return dataclasses.replace(p, domain=text)


Y_R = _dom(
    make_parameter("y_r", r"$\theta_r$", "y", "residual water content (or S_res)", "residual"),
    "0 ≤ θ_r < θ_s (van Genuchten 1980, eq. 21; Brooks & Corey 1964)",
)
Y_S = _dom(
    make_parameter("y_s", r"$\theta_s$", "y", "saturated water content (or S_s)", "saturated"),
    "θ_r < θ_s ≤ porosity (S_s ≤ 1 up to scatter) (van Genuchten 1980, eq. 21)",
)


def _alpha(name="alpha", symbol=r"$\alpha$", grid=4, grid_span=100.0, domain="α > 0 (van Genuchten 1980, eq. 21)"):
    return _dom(_alpha_p(name, symbol, grid, grid_span), domain)


def _alpha_p(name, symbol, grid, grid_span):
    return make_parameter(
        name,
        symbol,
        "1/Pa",
        "inverse of a characteristic suction",
        "inverse_suction",
        1e-3,
        1e3,
        0.0,
        grid,
        grid_span=grid_span,
    )


def _n(
    name="n", symbol="$n$", grid=12, domain="n > 1, so that m = 1 − 1/n > 0 (van Genuchten 1980, eq. 21)", lower=1.005
):
    """The shape index n: n > 1 where m = 1 − 1/n (searched on ln(n − 1)), n > 0 where m is free (on ln n)."""
    offset = 1.0 if lower > 1 else 0.0
    return _dom(make_parameter(name, symbol, "-", "pore-size index", "absolute", lower, 100.0, offset, grid), domain)


#: n > 0 where m is its own parameter (Fredlund & Xing 1994; van Genuchten 1980 with m free): the search reaches
#: 0.01, a curve flatter than any soil's over twelve decades of suction
N_POSITIVE = 0.01


@dataclass(frozen=True)
class RetentionModel:
    """One retention model: everything capred knows about it.

    Attributes
    ----------
    name : str
        Registry key and CLI name (``--model``).
    label : str
        Display name (plain text, also valid mathtext).
    equation : str
        The model as its figure legend shows it: plain text with Unicode sub- and superscripts (no mathtext, so
        that a figure never builds matplotlib's mathtext parser, ~0.1 s of a run).
    parameters : tuple[Parameter, ...]
        All parameters in order (y_r, y_s first where present).
    saturation : callable
        ``saturation(s, **shape) -> S`` [-]: S_e, or C(s)·S_e for Fredlund-Xing with C; broadcasts over
        array-valued parameters.
    references : tuple[str, ...]
        Keys of :data:`capred.references.REFERENCES`, the defining paper first.
    method : str
        One or two sentences for the method section of report.html, with the equation.
    help : str
        One line for ``capred retention --help``.
    style : dict
        Matplotlib line style of the fitted curve.
    residual_form : bool
        True: y = y_r + (y_s - y_r) S; False: y = y_s S.
    mixture : tuple or None
        ``(weight_name, components)`` when S = w S_1 + (1 - w) S_2 with ``components(s, **others) -> (S_1, S_2)``:
        the weight is then projected on the start grid like y_r and y_s.
    inverse : callable or None
        Closed-form ``inverse(S, **shape) -> s`` [Pa]; None: bisection on ln s.
    grid_order : tuple[str, str] or None
        ``(a, b)``: on the start grid only a >= b (removes a symmetry of the model).
    canonical : callable or None
        ``canonical(params) -> params``: one labelling of a symmetric model's optimum (Durner: the pore system
        of larger α first).
    steps : tuple of (str, str)
        ``(α, n)`` pairs of a pore system that may fit as a step (n at its upper bound), where the objective is
        piecewise flat in α between data suctions: α is then searched in every interval (Durner's second system).
    default : bool
        Fitted by `capred retention` when no ``--models`` are named.
    derived : tuple of (str, callable)
        ``(JSON name, f(params_si) -> value)`` of quantities reported beside the parameters (van Genuchten's
        m = 1 − 1/n).
    hysteresis_base : bool
        The model of each branch of the Kool & Parker (1987) joint hysteresis fit (van Genuchten with
        m = 1 − 1/n): fitted to each branch as well, to compare with the joint fit.
    power_law : tuple of (str, str) or None
        ``(air-entry suction, index)`` of a model S_e = (s_e/s)^λ above s_e: the form Morvan et al.'s suction
        equilibrium takes (`skempton-b --retention`), and the default target of `retention-convert`.
    """

    name: str
    label: str
    equation: str
    parameters: tuple[Parameter, ...]
    saturation: object = field(default=CallableField(), repr=False)
    references: tuple[str, ...] = ()
    method: str = ""
    help: str = ""
    style: dict = field(default_factory=dict)
    residual_form: bool = True
    mixture: object = field(default=CallableField(shape="second"), repr=False)
    inverse: object = field(default=CallableField(), repr=False)
    grid_order: tuple[str, str] | None = None
    canonical: object = field(default=CallableField(), repr=False)
    steps: tuple[tuple[str, str], ...] = ()
    default: bool = False
    derived: object = field(default=CallableField((), shape="pairs"), repr=False)
    hysteresis_base: bool = False
    power_law: tuple[str, str] | None = None

    @property
    def names(self) -> tuple[str, ...]:
        """Parameter names, in order."""
        return tuple(p.name for p in self.parameters)

    @property
    def reference(self) -> str:
        """Key of the defining paper."""
        return self.references[0]

    @property
    def log_params(self) -> dict[str, float]:
        """``{name: offset}`` of the parameters with a logarithmic scale."""
        return {p.name: p.log_offset for p in self.parameters if p.log_offset is not None}

    def parameter(self, name: str) -> Parameter:
        """The :class:`Parameter` called ``name``.

        Parameters
        ----------
        name : str
            Internal name, e.g. "alpha".

        Returns
        -------
        Parameter
        """
        return next(p for p in self.parameters if p.name == name)

    def water(self, s, **params):
        """Water content (or S_R) at suction ``s`` [Pa]: :math:`y_r + (y_s - y_r) S(s)` (or :math:`y_s S(s)`).

        Parameters
        ----------
        s : array_like
            Suction [Pa].
        **params : float
            Every parameter of the model (internal names, SI units).

        Returns
        -------
        numpy.ndarray
            y(s) in the unit of y_r and y_s.
        """
        shape = {k: v for k, v in params.items() if k not in ("y_r", "y_s")}
        S = self.saturation(s, **shape)
        if self.residual_form:
            y_r = params.get("y_r", 0.0)
            return y_r + (params["y_s"] - y_r) * S
        return params["y_s"] * S

    def effective_saturation(self, s, p: dict):
        """S_e(s) in [0, 1]: (y - y_r)/(y_s - y_r) (for Fredlund-Xing with C: y/y_s).

        Parameters
        ----------
        s : array_like
            Suction [Pa].
        p : dict
            Every parameter of the model by internal name, in SI units (``y_s`` included).

        Returns
        -------
        numpy.ndarray
            Effective saturation [-].
        """
        y = self.water(s, **p)
        y_r = p.get("y_r", 0.0)
        return (y - y_r) / (p["y_s"] - y_r)

    def suction(self, S, **shape):
        """Suction [Pa] at which the model's S(s) equals ``S`` [-] (NaN where no suction gives it).

        Parameters
        ----------
        S : array_like
            Value of the model's ``saturation`` [-] (S_e, or C·S_e for Fredlund-Xing with C).
        **shape
            The shape parameters by internal name, in SI units.

        Returns
        -------
        numpy.ndarray
            Suction [Pa]: the closed-form inverse where the model has one, else a monotone root search.
        """
        return resolve(_F + "model_suction")(self, S, **shape)


# ---------------------------------------------------------------------------------------------------------------
# the registry

_M = _dom(
    make_parameter("m", "$m$", "-", "shape exponent", "absolute", 1e-3, 20.0, 0.0, 10),
    "m > 0 (van Genuchten 1980, eq. 21 with m free; Fredlund & Xing 1994, eq. 26)",
)

_FX_A = _dom(
    make_parameter("a", "$a$", "Pa", "suction parameter (near the air entry)", "suction", 1e-3, 1e3, 0.0, 4),
    "a > 0 (Fredlund & Xing 1994, eq. 26)",
)
_FX_N = "n > 0 (Fredlund & Xing 1994, eq. 26: n controls the slope; they require n > 0, not n > 1)"
_FX_M = "m > 0 (Fredlund & Xing 1994, eq. 26)"

MODELS: dict[str, RetentionModel] = {
    m.name: m
    for m in (
        RetentionModel(
            "vg",
            "van Genuchten, m = 1 - 1/n",
            "Sₑ = [1 + (αs)ⁿ]⁻ᵐ",
            (Y_R, Y_S, _alpha(), _n()),
            _F + "_vg_saturation",
            ("vangenuchten1980",),
            "van Genuchten (1980, eq. 21) with Mualem's constraint: θ = θ_r + (θ_s − θ_r)[1 + (αs)^n]^−m, m = 1 − 1/n.",
            "vg: van Genuchten (1980), m = 1 - 1/n",
            dict(ls="-", color="blue", marker="o"),
            inverse=_F + "_vg_inverse",
            default=True,
            derived=(("m", _F + "_vg_m"),),
            hysteresis_base=True,
        ),
        RetentionModel(
            "vg_m_free",
            "van Genuchten, m free",
            "Sₑ = [1 + (αs)ⁿ]⁻ᵐ",
            (
                Y_R,
                Y_S,
                _alpha(),
                _n(grid=10, domain="n > 0 with m free (van Genuchten 1980, eq. 21)", lower=N_POSITIVE),
                _M,
            ),
            _F + "_vg_m_free_saturation",
            ("vangenuchten1980",),
            "van Genuchten (1980, eq. 21) with m free: θ = θ_r + (θ_s − θ_r)[1 + (αs)^n]^−m.",
            "vg_m_free: van Genuchten (1980) with m free",
            dict(ls="--", color="sky", marker="s"),
            inverse=_F + "_vg_m_free_inverse",
            default=True,
        ),
        RetentionModel(
            "bc",
            "Brooks-Corey",
            "Sₑ = (sₑ/s)^λ above sₑ, 1 below",
            (
                Y_R,
                Y_S,
                _dom(
                    make_parameter("s_e", "$s_e$", "Pa", "air-entry suction", "suction", 1e-3, 1.0, 0.0, 4, kinks=True),
                    "s_e > 0 (Brooks & Corey 1964)",
                ),
                _dom(
                    make_parameter(
                        "lam", r"$\lambda$", "-", "pore-size distribution index", "absolute", 1e-3, 50.0, 0.0, 12
                    ),
                    "λ > 0 (Brooks & Corey 1964)",
                ),
            ),
            _F + "_bc_saturation",
            ("brooks_corey1964",),
            "Brooks & Corey (1964): θ = θ_r + (θ_s − θ_r)(s_e/s)^λ above the air-entry suction s_e, θ_s below; "
            "s_e is searched between each pair of neighbouring data suctions, where the fit is smooth.",
            "bc: Brooks & Corey (1964) with the air-entry suction",
            dict(ls="-.", color="vermillion", marker="^"),
            inverse=_F + "_bc_inverse",
            default=True,
            power_law=("s_e", "lam"),
        ),
        RetentionModel(
            "kosugi",
            "Kosugi (lognormal)",
            "Sₑ = Q(ln(s/sₘ)/σ)",
            (
                Y_R,
                Y_S,
                _dom(
                    make_parameter(
                        "s_m",
                        "$s_m$",
                        "Pa",
                        "median suction of the pore-size distribution",
                        "suction",
                        1e-3,
                        1e3,
                        0.0,
                        4,
                    ),
                    "s_m > 0 (Kosugi 1996)",
                ),
                _dom(
                    make_parameter(
                        "sigma",
                        r"$\sigma$",
                        "-",
                        "standard deviation of ln(pore radius)",
                        "absolute",
                        1e-3,
                        10.0,
                        0.0,
                        12,
                    ),
                    "σ > 0 (Kosugi 1996)",
                ),
            ),
            _F + "_kosugi_saturation",
            ("kosugi1996",),
            "Kosugi (1996), a lognormal pore-size distribution: θ = θ_r + (θ_s − θ_r) Q(ln(s/s_m)/σ), Q the "
            "complementary standard normal distribution.",
            "kosugi: Kosugi (1996), lognormal",
            dict(ls=":", marker="o"),
            inverse=_F + "_kosugi_inverse",
        ),
        RetentionModel(
            "fx",
            "Fredlund-Xing with C(s)",
            "θ = θₛ C(s) [ln(e + (s/a)ⁿ)]⁻ᵐ",
            (
                Y_S,
                _FX_A,
                _n(grid=8, domain=_FX_N, lower=N_POSITIVE),
                _dom(make_parameter("m", "$m$", "-", "shape exponent", "absolute", 1e-3, 20.0, 0.0, 8), _FX_M),
                _dom(
                    make_parameter(
                        "s_r",
                        "$s_r$",
                        "Pa",
                        "suction of the residual water content",
                        "suction_to_absolute",
                        1.0,
                        1e9,
                        0.0,
                        1,
                    ),
                    "s_r > 0 (Fredlund & Xing 1994, eq. 26: C(s) = 1 − ln(1 + s/s_r)/ln(1 + 10⁶ kPa/s_r))",
                ),
            ),
            _F + "_fx_saturation",
            ("fredlund_xing1994",),
            "Fredlund & Xing (1994, eq. 26): θ = θ_s C(s)[ln(e + (s/a)^n)]^−m with "
            "C(s) = 1 − ln(1 + s/s_r)/ln(1 + 10⁶ kPa/s_r).",
            "fx: Fredlund & Xing (1994) with the correction factor C(s)",
            dict(ls=(0, (5, 1)), marker="s"),
            residual_form=False,
        ),
        RetentionModel(
            "fx_no_c",
            "Fredlund-Xing without C(s)",
            "Sₑ = [ln(e + (s/a)ⁿ)]⁻ᵐ",
            (
                Y_R,
                Y_S,
                _FX_A,
                _n(grid=10, domain=_FX_N, lower=N_POSITIVE),
                _dom(_M, _FX_M),
            ),
            _F + "_fx_no_c_saturation",
            ("fredlund_xing1994",),
            "Fredlund & Xing (1994, eq. 26) without the correction factor: θ = θ_r + (θ_s − θ_r)[ln(e + (s/a)^n)]^−m.",
            "fx_no_c: Fredlund & Xing (1994) without C(s)",
            dict(ls=(0, (3, 1, 1, 1)), marker="^"),
        ),
        RetentionModel(
            "durner",
            "Durner (bimodal van Genuchten)",
            "Sₑ = w₁ S₁ + (1 − w₁) S₂, Sᵢ = [1 + (αᵢs)^nᵢ]^−mᵢ",
            (
                Y_R,
                Y_S,
                _dom(
                    make_parameter("w1", "$w_1$", "-", "weight of the first pore system", "absolute", 0.0, 1.0),
                    "0 ≤ w₁ ≤ 1 (Durner 1994)",
                ),
                _alpha("alpha1", r"$\alpha_1$", 4, 3.0, "α₁ > 0 (Durner 1994)"),
                _n("n1", "$n_1$", 10, "n₁ > 1, m₁ = 1 − 1/n₁ (Durner 1994)"),
                _alpha("alpha2", r"$\alpha_2$", 4, 3.0, "α₂ > 0 (Durner 1994)"),
                _n("n2", "$n_2$", 10, "n₂ > 1, m₂ = 1 − 1/n₂ (Durner 1994)"),
            ),
            _F + "_durner_saturation",
            ("durner1994",),
            "Durner (1994), two van Genuchten pore systems: S_e = w₁[1 + (α₁s)^n₁]^−m₁ + (1 − w₁)[1 + (α₂s)^n₂]^−m₂, "
            "m_i = 1 − 1/n_i.",
            "durner: Durner (1994), bimodal van Genuchten",
            dict(ls=(0, (7, 2, 1, 2, 1, 2)), marker="D"),  # dash-dot-dot (Kosugi is dotted), diamonds
            mixture=("w1", _F + "_durner_components"),
            grid_order=("alpha1", "alpha2"),
            canonical=_F + "_durner_canonical",
            steps=(("alpha2", "n2"), ("alpha1", "n1")),
        ),
    )
}

#: the same registry under the name used by the other families
REGISTRY = MODELS


#: the same registry under the name used by the other families
REGISTRY = MODELS
