"""`capred retention`: what it reads (``SCHEMA``) and its options (``RetentionOptions``).

Numpy-free (see :mod:`capred.spec`): the models are those of the registry capred.spec.retention_models.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import OptionError
from .columns import Column
from .constants import GAMMA_W
from .options import Interval, Options, StrOptions
from .retention_models import MODELS as FITTERS

#: a reversal must exceed this fraction of the suction at the reversal point (2 %: twice the ±1 % of reading a
#: dew-point potentiameter states above 5 MPa, below any scanning loop worth comparing with a curve)
REVERSAL_RELATIVE = 0.02
#: ... and this fraction of the record's measured suction range (0.2 %: of the order of a tensiometer's absolute
#: resolution on its ~85 kPa range; an evaporation record's dips of a few hundredths of a cm are far below; the
#: floor near zero suction, where a fraction of the reading vanishes)
REVERSAL_RANGE = 0.002

#: the labels a branch may carry (column 'branch' or inferred)
LABELS = ("drying", "wetting", "scanning")


def default_models() -> tuple[str, ...]:
    """The models `capred retention` fits when none are named.

    The registry entries with ``default``, in registry order.

    Returns
    -------
    tuple of str
        Their registry names.
    """
    return tuple(k for k, m in FITTERS.items() if m.default)


def to_internal(name: str) -> tuple[str, float]:
    """The internal name of a retention parameter and the factor from its JSON unit to SI.

    The hysteresis α's are not options.

    Parameters
    ----------
    name : str
        A parameter's JSON name (``"alpha_per_kPa"``; an internal name works too).

    Returns
    -------
    internal : str
        Its internal name (``"alpha"``).
    factor : float
        SI value = factor × value in the JSON's unit (1e-3 for 1/kPa -> 1/Pa).

    Raises
    ------
    KeyError
        For an unknown name, or a hysteresis α.
    """
    from ..fitting.retention_models import internal_name  # numpy: at run time only

    internal, f = internal_name(name)
    if internal in ("alpha_d", "alpha_w"):
        raise KeyError(name)
    return internal, f


SCHEMA = [
    Column("suction", "pressure", "kPa", "suction", ("s", "matric_suction", "delta_u", "ua_uw"), "nonnegative"),
    Column(
        "head",
        "length",
        "cm",
        "suction head",
        ("h", "suction_head", "pressure_head", "z1", "matric_head"),
        "nonnegative",
    ),
    Column("pF", "dimensionless", "-", "pF (log10 of the head in cm of water)", ("pf", "p_f"), None),
    Column("S_R", "dimensionless", "-", "S_R", ("Sr", "degree_of_saturation", "saturation"), "fraction"),
    Column(
        "theta",
        "dimensionless",
        "-",
        "theta",
        ("theta_vol", "vwc", "water_content_vol", "theta_vol_m3_per_m3", "volumetric_water_content"),
        "fraction",
    ),
    Column(
        "w",
        "dimensionless",
        "-",
        "gravimetric water content w",
        ("gravimetric_water_content", "w_grav", "water_content"),
        "nonnegative",
    ),
    Column("rho_d", "density", "kg/m^3", "dry density", ("dry_density", "rhod"), "positive"),
    Column("z2", "volume", "cm^3", "air volume z2", ("air_volume", "burette", "V_a"), "nonnegative"),
    Column("V_v", "volume", "cm^3", "void volume V_v", ("Vv", "void_volume"), "positive"),
    Column("weight", "dimensionless", "-", "weight", ("weights", "w_fit"), "positive"),
    Column("branch", "text", None, "branch", ("path",), choices=LABELS),
]


@dataclass(frozen=True)
class RetentionOptions(Options):
    """Options of `capred retention`.

    Attributes
    ----------
    models : tuple of str
        Models to fit (registry names, or 'all').
    fixed : dict
        Fixed parameters by report name, in report units (kPa, 1/kPa).
    gamma_w : float
        Unit weight of water [N/m^3, or a string with a unit].
    rho_w : float
        Density of water [kg/m^3] (theta = w rho_d/rho_w).
    hysteresis : str or None
        kool-parker: fit the drying and wetting branches jointly.
    branches : str
        auto: the 'branch' column, else drying, wetting and scanning branches inferred from the order of readings,
        reversals below the noise tolerance ignored; single: every reading on one curve.
    reversal_relative : float
        Noise tolerance of a reversal, as a fraction of the suction at the reversal point [-].
    reversal_range : float
        Noise tolerance of a reversal, as a fraction of the measured suction range [-].
    """

    QUANTITIES = {"gamma_w": "gamma_w", "rho_w": "rho_w"}
    CONSTRAINTS = {
        "hysteresis": StrOptions(("kool-parker",)),
        "branches": StrOptions(("auto", "single")),
        "reversal_relative": Interval(0, 1, closed="left", text="be a fraction in [0, 1)"),
        "reversal_range": Interval(0, 1, closed="left", text="be a fraction in [0, 1)"),
    }

    models: tuple[str, ...] = default_models()
    fixed: dict[str, float] = field(default_factory=dict)
    gamma_w: float = GAMMA_W
    rho_w: float = 1000.0
    hysteresis: str | None = None
    branches: str = "auto"
    reversal_relative: float = REVERSAL_RELATIVE
    reversal_range: float = REVERSAL_RANGE

    def __post_init__(self) -> None:
        super().__post_init__()
        models = (self.models,) if isinstance(self.models, str) else tuple(self.models)
        if models == ("all",):
            models = tuple(FITTERS)
        unknown = [m for m in models if m not in FITTERS]
        if unknown or not models:
            raise OptionError(
                f"unknown model {unknown[0] if unknown else ''!r}; choose from {', '.join(FITTERS)} or all"
            )
        object.__setattr__(self, "models", models)
        for name in self.fixed:
            try:
                to_internal(name)
            except KeyError:
                raise OptionError(f"fixed: unknown parameter '{name}'") from None


__all__ = [
    "to_internal",
    "LABELS",
    "REVERSAL_RANGE",
    "REVERSAL_RELATIVE",
    "SCHEMA",
    "RetentionOptions",
    "default_models",
]
